// sslr::Context: creation (GL 4.5 check, function table, samplers, buffers), the render targets
// of a size, resize and the public entry points. A frame is in frame.cpp and passes/*.cpp, the
// composite in composite.cpp.
#include <algorithm>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include "context_impl.hpp"

namespace sslr {

const char* toString(StatusCode code) {
  switch (code) {
    case StatusCode::Ok: return "ok";
    case StatusCode::InvalidSettings: return "invalid settings";
    case StatusCode::InvalidInput: return "invalid input";
    case StatusCode::InvalidProjection: return "invalid projection";
    case StatusCode::InvalidSize: return "invalid size";
    case StatusCode::NoCurrentContext: return "no current GL context";
    case StatusCode::GlUnavailable: return "GL 4.5 unavailable";
    case StatusCode::ShaderBuild: return "shader build failed";
    case StatusCode::NoFrame: return "no frame";
    case StatusCode::Failed: return "failed";
  }
  return "unknown";
}

const char* libraryVersion() { return SSLR_VERSION_STRING; }
static_assert(kMaxViews == SSLR_MAX_VIEWS, "the public limit is the shaders'");


// ---- Render targets -------------------------------------------------------------------------

GLuint Context::Impl::makeTexture(GLenum format, const char* name) const {
  const GLuint t = createTexture(format, 1, width, height);
  label(GL_TEXTURE, t, name);
  return t;
}

void Context::Impl::createTargets() {
  reflection = makeTexture(GL_RGBA16F, "sslr.reflection");
  scratch = makeTexture(GL_RGBA16F, "sslr.scratch");
  resolved = makeTexture(GL_RGBA16F, "sslr.resolved");
  const FrameArea whole = areaOf(Viewport{0, 0, width, height});  // the largest frame's pyramid
  pyramid.levels = whole.levels;
  pyramid.level1Width = whole.level1Width;
  pyramid.level1Height = whole.level1Height;
  area = whole;
  lastRect = whole.rect;
  // The passes' own resources are created by the first dispatch that needs them
  // (createFrameResources).
  gl.CreateBuffers(1, &tileBuffer);
  const std::vector<GLuint> tiles = initialTileList();
  gl.NamedBufferStorage(tileBuffer, static_cast<GLsizeiptr>(tiles.size() * sizeof(GLuint)), tiles.data(),
                        GL_DYNAMIC_STORAGE_BIT);
  label(GL_BUFFER, tileBuffer, "sslr.tiles");
  const float zero[4] = {0, 0, 0, 0};
  for (GLuint t : {reflection, resolved}) gl.ClearTexImage(t, 0, GL_RGBA, GL_FLOAT, zero);
}

// Header (see common/tiles.glsl), traced tiles, tiles to blur, per-tile stamps (zero: frame
// indices start at 1), the previous frame's traced tiles (none: the outputs start cleared); each
// array holds every view's tiles.
std::vector<GLuint> Context::Impl::initialTileList() const {
  const size_t tiles = static_cast<size_t>(tilesX()) * tilesY() * views;
  std::vector<GLuint> list(kTileHeader + kTileArrays * tiles, 0u);
  list[kCleanupDispatchOffset / 4 + 1] = list[kCleanupDispatchOffset / 4 + 2] = 1;
  return list;
}

void Context::Impl::resetFrameState(std::uint64_t dispatchesBefore, int frameIndexBefore) {
  const std::vector<GLuint> tiles = initialTileList();
  gl.NamedBufferSubData(tileBuffer, 0, static_cast<GLsizeiptr>(tiles.size() * sizeof(GLuint)), tiles.data());
  const float zero[4] = {0, 0, 0, 0};
  for (GLuint t : {reflection, scratch, resolved, trace.hit, trace.iterations, trace.hitDistance, trace.quadHit,
                   trace.quadSurface, temporal.color, temporal.key, temporal.confidence})
    if (t != 0) gl.ClearTexImage(t, 0, GL_RGBA, GL_FLOAT, zero);
  if (feedback.fence != nullptr) gl.DeleteSync(feedback.fence);
  feedback.fence = nullptr;
  feedback.traversalInline = feedback.hasTraversal = feedback.lastFrameListedNoTile = false;
  temporal.valid = false;
  const FrameArea whole = areaOf(Viewport{0, 0, width, height});
  area = whole;
  lastRect = whole.rect;
  // The warm-up frames are no frames of the host's: their stats slots are dropped, the counters
  // put back.
  for (StatsSlot& slot : statsRing)
    if (slot.frame > dispatchesBefore) {
      if (slot.fence != nullptr) gl.DeleteSync(slot.fence);
      slot.fence = nullptr;
      slot.frame = 0;
    }
  dispatches = dispatchesBefore;
  frameIndex = frameIndexBefore;
  haveFrame = false;
}

Context::Impl::FrameArea Context::Impl::areaOf(const Viewport& rect) {
  FrameArea a;
  a.rect = rect;
  a.tilesX = (rect.width + SSLR_TILE_SIZE - 1) / SSLR_TILE_SIZE;
  a.tilesY = (rect.height + SSLR_TILE_SIZE - 1) / SSLR_TILE_SIZE;
  a.levels = shared::sslrHiZLevelCount(rect.width, rect.height);
  const int top = 1 << a.levels;
  a.level1Width = (rect.width + top - 1) / top * (top / 2);
  a.level1Height = (rect.height + top - 1) / top * (top / 2);
  return a;
}

void Context::Impl::destroyTargets() {
  const GLuint textures[] = {reflection, scratch, resolved};
  gl.DeleteTextures(3, textures);
  pyramid.destroy(gl);
  trace.destroy(gl);
  temporal.destroy(gl);
  gl.DeleteBuffers(1, &feedback.buffer);
  if (feedback.fence != nullptr) gl.DeleteSync(feedback.fence);
  feedback.fence = nullptr;
  feedback.traversalInline = feedback.hasTraversal = feedback.lastFrameListedNoTile = false;
  gl.DeleteBuffers(1, &tileBuffer);
  reflection = scratch = resolved = feedback.buffer = tileBuffer = 0;
}

void Context::Impl::destroy() {
  if (gl.DeleteTextures == nullptr) return;  // loading failed: nothing was created
  destroyTargets();
  gl.DeleteBuffers(1, &frameUbo);
  for (StatsSlot& slot : statsRing) {
    gl.DeleteBuffers(1, &slot.buffer);
    gl.DeleteQueries(Impl::kTimestamps, slot.queries);
    if (slot.fence != nullptr) gl.DeleteSync(slot.fence);
    slot = {};
  }
  GLuint samplers[] = {nearestSampler, linearSampler};
  gl.DeleteSamplers(2, samplers);
  gl.DeleteVertexArrays(1, &vao);
  for (auto& [key, program] : programs) gl.DeleteProgram(program);
  programs.clear();
  for (auto& [key, pending] : pendingPrograms) {
    for (const auto& [shader, entry] : pending.shaders) gl.DeleteShader(shader);
    gl.DeleteProgram(pending.program);
  }
  pendingPrograms.clear();
  frameUbo = nearestSampler = linearSampler = vao = 0;
}

// ---- Context ------------------------------------------------------------------------------

Context::Context(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Context::~Context() = default;

// What Context::create refuses in a ContextDesc before it touches GL: its size, views and pass
// shapes.
static Status checkContextDesc(const ContextDesc& desc) {
  if (desc.width <= 0 || desc.height <= 0 || desc.width > 16384 || desc.height > 16384)
    return Status::error(StatusCode::InvalidSize, "sslr: ContextDesc size " + std::to_string(desc.width) + "x" +
                         std::to_string(desc.height) + " is invalid (must be 1..16384 each)");
  if (desc.views < 1 || desc.views > kMaxViews)
    return Status::error(StatusCode::InvalidSettings, "sslr: ContextDesc views = " + std::to_string(desc.views) +
                         " is invalid (must be 1.." + std::to_string(kMaxViews) + ")");
  if (desc.device != DeviceProfile::Auto && desc.device != DeviceProfile::Gpu && desc.device != DeviceProfile::Software)
    return Status::error(StatusCode::InvalidSettings, "sslr: ContextDesc device = " +
                         std::to_string(static_cast<int>(desc.device)) + " is not a DeviceProfile");
  if (desc.traversalPass != TraversalPass::Auto && desc.traversalPass != TraversalPass::Inline &&
      desc.traversalPass != TraversalPass::Deferred)
    return Status::error(StatusCode::InvalidSettings, "sslr: ContextDesc traversalPass = " +
                         std::to_string(static_cast<int>(desc.traversalPass)) + " is not a TraversalPass");
  return {};
}

// Those of `names` the current context does not list among its extensions, joined by " and ".
static std::string missingExtensions(const detail::Gl& gl, std::initializer_list<const char*> names) {
  GLint count = 0;
  gl.GetIntegerv(GL_NUM_EXTENSIONS, &count);
  std::string missing;
  for (const char* name : names) {
    bool found = false;
    for (GLint i = 0; i < count && !found; ++i) {
      const GLubyte* listed = gl.GetStringi(GL_EXTENSIONS, static_cast<GLuint>(i));
      found = listed != nullptr && std::strcmp(reinterpret_cast<const char*>(listed), name) == 0;
    }
    if (!found) missing += (missing.empty() ? "" : " and ") + std::string(name);
  }
  return missing;
}

Expected<std::unique_ptr<Context>> Context::create(const ContextDesc& desc) {
  if (Status s = checkContextDesc(desc); !s) return s;
  auto impl = std::make_unique<Impl>();
  impl->log = desc.log;
  impl->traversalPass = desc.traversalPass;
  impl->oneBodyTraversal = desc.oneBodyTraversal;
  impl->occupancyExit = desc.occupancyExit;
  if (Status s = impl->gl.load(desc.getProcAddress); !s) {
    impl->gl = {};
    return s;
  }
  const detail::Gl& gl = impl->gl;
  GLint major = 0, minor = 0;
  gl.GetIntegerv(GL_MAJOR_VERSION, &major);
  gl.GetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45) {
    impl->gl = {};
    return Status::error(StatusCode::GlUnavailable, "sslr: needs OpenGL 4.5, the current context is " + std::to_string(major) +
                         "." + std::to_string(minor));
  }
  if (desc.device == DeviceProfile::Auto) {
    if (const GLubyte* renderer = gl.GetString(GL_RENDERER)) {
      const std::string name(reinterpret_cast<const char*>(renderer));
      for (const char* cpu : {"llvmpipe", "softpipe", "SwiftShader"})
        if (name.find(cpu) != std::string::npos) impl->softwareRenderer = true;
    }
  } else {
    impl->softwareRenderer = desc.device == DeviceProfile::Software;
  }
  GLint vertexSsbos = 0;
  gl.GetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &vertexSsbos);
  if (vertexSsbos < 1) {
    impl->gl = {};
    return Status::error(StatusCode::GlUnavailable, "sslr: the GL implementation allows no storage blocks in vertex shaders "
                         "(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS = 0); composite needs one");
  }
  if (desc.occupancyExit) {
    if (std::string missing = missingExtensions(gl, {"GL_ARB_shader_ballot", "GL_ARB_gpu_shader_int64"}); !missing.empty()) {
      impl->gl = {};
      return Status::error(StatusCode::GlUnavailable, "sslr: ContextDesc::occupancyExit needs " + missing +
                           ", which the GL implementation does not offer");
    }
  }
  impl->width = desc.width;
  impl->height = desc.height;
  impl->views = desc.views;
  gl.CreateBuffers(1, &impl->frameUbo);  // one SslrFrame a view (std140: an array of them)
  gl.NamedBufferStorage(impl->frameUbo, static_cast<GLsizeiptr>(sizeof(shared::SslrFrame)) * desc.views, nullptr,
                        GL_DYNAMIC_STORAGE_BIT);
  impl->label(GL_BUFFER, impl->frameUbo, "sslr.frame");
  for (Impl::StatsSlot& slot : impl->statsRing) {
    gl.CreateBuffers(1, &slot.buffer);
    // In video memory: the trace's atomics count into it (in client memory each atomic would cross
    // the bus); NVIDIA's performance note on the read back is the lesser cost.
    gl.NamedBufferStorage(slot.buffer, SSLR_STATS_COUNT * sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
    impl->label(GL_BUFFER, slot.buffer, "sslr.stats");
    gl.CreateQueries(GL_TIMESTAMP, Impl::kTimestamps, slot.queries);
  }
  GLint timestampBits = 0;
  gl.GetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &timestampBits);
  impl->timestamps = timestampBits > 0;
  gl.CreateSamplers(1, &impl->nearestSampler);
  gl.CreateSamplers(1, &impl->linearSampler);
  for (GLuint s : {impl->nearestSampler, impl->linearSampler}) {
    const GLint filter = s == impl->linearSampler ? GL_LINEAR : GL_NEAREST;
    gl.SamplerParameteri(s, GL_TEXTURE_MIN_FILTER, filter);
    gl.SamplerParameteri(s, GL_TEXTURE_MAG_FILTER, filter);
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    // The host's depth texture may have comparison enabled; sslr reads raw depth.
    gl.SamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  }
  impl->label(GL_SAMPLER, impl->nearestSampler, "sslr.nearest");
  impl->label(GL_SAMPLER, impl->linearSampler, "sslr.linear");
  gl.CreateVertexArrays(1, &impl->vao);
  impl->label(GL_VERTEX_ARRAY, impl->vao, "sslr.emptyVao");
  impl->createTargets();
  return std::unique_ptr<Context>(new Context(std::move(impl)));
}

Status Context::resize(int width, int height) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    return Status::error(StatusCode::InvalidSize, "sslr: resize to " + std::to_string(width) + "x" + std::to_string(height) +
                         " is invalid (must be 1..16384 each)");
  if (width == impl_->width && height == impl_->height) return {};
  // Freeing and making the targets needs the context: without it the calls go nowhere and the
  // context would be left with no targets.
  if (Status s = impl_->checkCurrentContext("resize()"); !s) return s;
  impl_->destroyTargets();
  impl_->width = width;
  impl_->height = height;
  impl_->createTargets();
  impl_->haveFrame = false;
  return {};
}

int Context::width() const { return impl_->width; }
int Context::height() const { return impl_->height; }
DeviceProfile Context::device() const {
  return impl_->softwareRenderer ? DeviceProfile::Software : DeviceProfile::Gpu;
}
int Context::views() const { return impl_->views; }
Status Context::dispatch(const FrameInputs& inputs, const Settings& settings) {
  return impl_->dispatch(std::span<const FrameInputs>(&inputs, 1), settings);
}
Status Context::dispatch(std::span<const FrameInputs> views, const Settings& settings) {
  return impl_->dispatch(views, settings);
}
Status Context::prepare(const FrameInputs& inputs, const Settings& settings, const PrepareOptions& options) {
  return impl_->prepare(std::span<const FrameInputs>(&inputs, 1), settings, options);
}
Status Context::prepare(std::span<const FrameInputs> views, const Settings& settings, const PrepareOptions& options) {
  return impl_->prepare(views, settings, options);
}
Status Context::composite(GLName framebuffer, const CompositeOptions& options) {
  return impl_->composite(framebuffer, options);
}
GLName Context::reflectionTexture() const { return impl_->reflection; }
GLName Context::resolvedTexture() const { return impl_->resolved; }
GLName Context::hitTexture() const { return impl_->trace.hit; }
GLName Context::iterationsTexture() const { return impl_->trace.iterations; }
GLName Context::hitDistanceTexture() const { return impl_->trace.hitDistance; }
GLName Context::historyConfidenceTexture() const { return impl_->temporal.confidence; }
FrameStats Context::lastStats() const {
  impl_->harvestStats(false);
  return impl_->stats;
}
FrameStats Context::waitForStats() const {
  impl_->harvestStats(true);
  return impl_->stats;
}

}  // namespace sslr
