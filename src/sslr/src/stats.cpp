// FrameStats without a stall: the dispatch records into a ring slot (frame.cpp); this reads
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

PassTraffic FrameStats::totalTraffic() const {
  PassTraffic total;
  for (const PassTraffic* t : {&classifyTraffic, &pyramidTraffic, &traceTraffic, &blurTraffic, &temporalTraffic}) {
    total.texelsRead += t->texelsRead;
    total.texelsWritten += t->texelsWritten;
    total.bytesRead += t->bytesRead;
    total.bytesWritten += t->bytesWritten;
  }
  return total;
}

RayWork FrameStats::totalRayWork() const {
  RayWork total;
  for (const RayWork* w : {&traceWork, &retraceWork, &quadWork, &quadRetraceWork}) {
    total.laneSteps += w->laneSteps;
    total.simt32 += w->simt32;
    total.simt64 += w->simt64;
    total.longestChain += w->longestChain;
    total.groups += w->groups;
  }
  return total;
}

namespace {
using U64 = std::uint64_t;
void read(PassTraffic& t, U64 texels, int bytes) {
  t.texelsRead += texels;
  t.bytesRead += texels * U64(bytes);
}
void write(PassTraffic& t, U64 texels, int bytes) {
  t.texelsWritten += texels;
  t.bytesWritten += texels * U64(bytes);
}
constexpr int kRgba16f = 8, kRg32f = 8, kRgba32f = 16, kR32f = 4;

// Pyramid levels 0 and 1 from the depths (classification, or its pass of their own, which read
// the depths themselves): the back depth and the curved solids' normal channels gathered with
// them; level 1 whole and level 0 at most whole (quads of background alone write none).
void levels01(PassTraffic& t, const TrafficModel& m, U64 pixels) {
  if (m.backDepthBytes > 0) read(t, pixels, m.backDepthBytes);
  read(t, pixels * U64(m.normalGathers), m.normalBytes);
  write(t, m.level1Cells, kRg32f);
  write(t, pixels, kRg32f);
}

// The G-buffer reads of one trace-pass pixel: normal, depth, the separate material texel.
void pixelSetup(PassTraffic& t, const TrafficModel& m, U64 pixels) {
  read(t, pixels, m.normalBytes);
  read(t, pixels, m.depthBytes);
  if (m.materialBytes > 0) read(t, pixels, m.materialBytes);
  if (m.positionBytes > 0) read(t, pixels, m.positionBytes);
}
}  // namespace

// The model: P screen pixels, T listed tiles (64 pixels each, counted whole at the screen's
// edge), R rays traced, F counted fetches, B blurred tiles. Bounds where the CPU cannot know the
// count: level 0 written for every quad, a colour and a hit normal read for every ray, every
// blurred tile staged at the widest apron, history looked up twice per pixel. Not counted: the
// clean-up passes' zeros and the curved pass (their counts stay on the GPU).
void estimateTraffic(const TrafficModel& m, FrameStats& f) {
  const U64 pixels = U64(m.width) * U64(m.height);
  const U64 tilePixels = U64(f.tiles) * (SSLR_TILE_SIZE * SSLR_TILE_SIZE);
  const U64 rays = f.tracedPixels;
  f.classifyTraffic = {};
  read(f.classifyTraffic, pixels, m.depthBytes);
  read(f.classifyTraffic, pixels * U64(m.materialGathers), m.materialBytes > 0 ? m.materialBytes : m.normalBytes);
  if (m.maskBytes > 0) read(f.classifyTraffic, pixels, m.maskBytes);
  if (m.classifyLevels01) levels01(f.classifyTraffic, m, pixels);
  const bool traced = f.tiles > 0;
  f.pyramidTraffic = {};
  if (m.pyramid && traced) {
    if (m.levels01Pass) {
      read(f.pyramidTraffic, pixels, m.depthBytes);
      levels01(f.pyramidTraffic, m, pixels);
    }
    read(f.pyramidTraffic, m.level1Cells, kRg32f);
    write(f.pyramidTraffic, m.upperCells, kRg32f);
  }
  f.traceTraffic = {};
  if (traced) {
    PassTraffic& t = f.traceTraffic;
    pixelSetup(t, m, tilePixels);
    if (m.halfResolution) {  // the quads' rays pick among their four pixels, then every pixel reads two records
      pixelSetup(t, m, tilePixels);
      write(t, tilePixels / 4, kRgba32f);  // the quads' hit records
      write(t, tilePixels / 4, kRgba16f);  // ... and surfaces
      read(t, tilePixels, kRgba32f);
      read(t, tilePixels, kRgba16f);
    }
    read(t, f.fetches, m.fetchBytes);
    read(t, rays * 4, m.colorBytes);  // the bilinear colour read of a hit
    read(t, rays, m.normalBytes);     // the hit's normal
    if (m.baseColorBytes > 0) read(t, rays, m.baseColorBytes);  // coloured F0, per hit
    write(t, tilePixels * 2, kRgba16f);  // reflection, resolved
    if (m.hitRecord) write(t, tilePixels, kRgba32f);
    if (m.hitDistance) write(t, tilePixels, kR32f);
    if (m.iterations) write(t, tilePixels, kR32f);
  }
  f.blurTraffic = {};
  if (m.blurTaps > 0 && f.blurTiles > 0) {
    const U64 staged = U64(f.blurTiles) * U64(SSLR_TILE_SIZE * (SSLR_TILE_SIZE + 2 * m.blurTaps));
    const U64 blurred = U64(f.blurTiles) * (SSLR_TILE_SIZE * SSLR_TILE_SIZE);
    for (int pass = 0; pass < 2; ++pass) {  // H, then V
      pixelSetup(f.blurTraffic, m, staged);
      read(f.blurTraffic, staged * (pass == 0 ? 1 : 2), kRgba16f);  // values (V: its radius too)
      read(f.blurTraffic, blurred * 2, kRgba16f);                   // radius and centre value
      write(f.blurTraffic, blurred, kRgba16f);
    }
  }
  f.temporalTraffic = {};
  if (m.temporal && traced) {
    PassTraffic& t = f.temporalTraffic;
    read(t, tilePixels * 9, kRgba16f);      // blend: this frame's 3x3
    read(t, tilePixels * 8, kRgba16f);      // history, at most two lookups of four texels
    read(t, tilePixels * 8, kR32f);         // their keys
    read(t, tilePixels, kRgba32f);          // the hit record
    read(t, tilePixels * 3, m.normalBytes);  // the normal and two neighbours'
    read(t, tilePixels, m.depthBytes);
    if (m.motionBytes > 0) read(t, tilePixels, m.motionBytes);
    if (m.stochasticFilter) {  // the 3x3 filter's neighbours (every pixel counted: an upper bound)
      read(t, tilePixels * 8, m.depthBytes);
      read(t, tilePixels * 8, m.normalBytes);
      if (m.materialBytes > 0) read(t, tilePixels * 8, m.materialBytes);
    }
    write(t, tilePixels, kRgba16f);
    read(t, tilePixels, kRgba16f);          // store: the blend, depth, normal
    read(t, tilePixels, m.depthBytes);
    read(t, tilePixels, m.normalBytes);
    write(t, tilePixels * 2, kRgba16f);     // resolved and history
    write(t, tilePixels, kR32f);            // keys
  }
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
    GLuint counters[SSLR_STATS_COUNT] = {};
    gl.GetNamedBufferSubData(oldest->buffer, 0, sizeof(counters), counters);
    FrameStats f;
    f.frame = oldest->frame;
    f.tracedPixels = counters[0];
    f.fetches = counters[1];
    f.hierarchicalPixels = counters[2];
    f.tiles = counters[SSLR_STATS_LISTED_TILES];
    f.blurTiles = counters[SSLR_STATS_BLUR_TILES];
    const std::array work{&f.traceWork, &f.retraceWork, &f.quadWork, &f.quadRetraceWork};
    static_assert(work.size() == SSLR_RAY_WORK_DISPATCHES);
    for (int d = 0; d < SSLR_RAY_WORK_DISPATCHES; ++d) {
      const GLuint* c = counters + SSLR_STATS_RAY_WORK + d * SSLR_RAY_WORK_FIELDS;
      *work[static_cast<size_t>(d)] = {c[SSLR_RAY_WORK_LANE_STEPS], c[SSLR_RAY_WORK_SIMT32], c[SSLR_RAY_WORK_SIMT64],
                                       c[SSLR_RAY_WORK_CHAIN], c[SSLR_RAY_WORK_GROUPS]};
    }
    f.traversalDeferred = oldest->traversalDeferred;
    f.followedEmptyFrame = oldest->followedEmptyFrame;
    estimateTraffic(oldest->traffic, f);
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
