// FrameStats without a stall: the dispatch records into a ring slot (passes.cpp); this reads
// back the slots whose fence has signalled, so a read never waits for the GPU unless asked to.
#include <array>

#include "context_impl.hpp"

namespace sslr {

namespace {
// FrameStats' per-pass command counts in pass order (the ring slot's order too).
template <typename Stats>
auto passCommandsOf(Stats& f) {
  return std::array{&f.classifyCommands, &f.pyramidCommands, &f.traceCommands,
                    &f.blurCommands,     &f.temporalCommands, &f.finishCommands};
}
}  // namespace

PassCommands FrameStats::totalCommands() const {
  PassCommands total;
  for (const PassCommands* c : passCommandsOf(*this)) {
    total.dispatches += c->dispatches;
    total.indirectDispatches += c->indirectDispatches;
    total.barriers += c->barriers;
    total.programs += c->programs;
    total.uploads += c->uploads;
  }
  return total;
}

void Context::Impl::harvestStats(bool waitNewest) const {
  if (waitNewest) {
    const StatsSlot* newest = nullptr;
    for (const StatsSlot& s : statsRing)
      if (s.fence != nullptr && (newest == nullptr || s.frame > newest->frame)) newest = &s;
    if (newest != nullptr) {
      // Flush once, then wait in 1 s steps (a lost device must not hang the caller forever).
      GLenum r = gl.ClientWaitSync(newest->fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000ull);
      for (int i = 0; i < 30 && r == GL_TIMEOUT_EXPIRED; ++i) r = gl.ClientWaitSync(newest->fence, 0, 1000000000ull);
    }
  }
  // Oldest first, so that the newest finished slot ends up in `stats`.
  for (;;) {
    StatsSlot* oldest = nullptr;
    for (StatsSlot& s : statsRing)
      if (s.fence != nullptr && (oldest == nullptr || s.frame < oldest->frame)) oldest = &s;
    if (oldest == nullptr) return;
    const GLenum r = gl.ClientWaitSync(oldest->fence, 0, 0);
    if (r != GL_ALREADY_SIGNALED && r != GL_CONDITION_SATISFIED) return;  // not done yet: later
    GLuint counters[6] = {};
    gl.GetNamedBufferSubData(oldest->buffer, 0, sizeof(counters), counters);
    FrameStats f;
    f.frame = oldest->frame;
    f.tracedPixels = counters[0];
    f.fetches = counters[1];
    f.hierarchicalPixels = counters[2];
    f.tiles = counters[4];
    f.blurTiles = counters[5];
    f.traversalDeferred = oldest->traversalDeferred;
    f.level1Pass = oldest->level1Pass;
    const auto commands = passCommandsOf(f);
    static_assert(commands.size() == kPasses);
    for (int i = 0; i < kPasses; ++i) *commands[i] = oldest->commands[i];
    if (timestamps) {
      // With a buffer bound to GL_QUERY_BUFFER the result would go into it: unbind it meanwhile.
      GLint queryBuffer = 0;
      gl.GetIntegerv(GL_QUERY_BUFFER_BINDING, &queryBuffer);
      if (queryBuffer != 0) gl.BindBuffer(GL_QUERY_BUFFER, 0);
      GLuint64 t[kTimestamps] = {};
      for (int i = 0; i < kTimestamps; ++i) gl.GetQueryObjectui64v(oldest->queries[i], GL_QUERY_RESULT, &t[i]);
      if (queryBuffer != 0) gl.BindBuffer(GL_QUERY_BUFFER, static_cast<GLuint>(queryBuffer));
      auto ms = [&](int a, int b) { return t[b] >= t[a] ? static_cast<double>(t[b] - t[a]) * 1e-6 : 0.0; };
      f.classifyMs = ms(0, 1);
      f.pyramidMs = ms(1, 2);
      f.traceMs = ms(2, 3);
      f.blurMs = ms(3, 4);
      f.temporalMs = ms(4, 5);
    }
    gl.DeleteSync(oldest->fence);
    oldest->fence = nullptr;
    stats = f;
  }
}

}  // namespace sslr
