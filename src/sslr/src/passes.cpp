// The passes of a frame: classify (tile list) -> clean-up of last frame's tiles -> depth pyramid
// (when a mode traces it) -> trace (deferred traversal: first stage -> retrace of the listed
// pixels; half resolution: quads [-> quad retrace] -> reuse -> retrace) -> blur H -> blur V.
// Everything after classification runs over the listed tiles (or listed pixels) only.
#include <algorithm>
#include <cmath>

#include "context_impl.hpp"
#include "gl_state.hpp"
#include "sslr/reference.hpp"

namespace sslr {

void Context::Impl::bindInputs(const FrameInputs& in) const {
  gl.bindTexture2D(SSLR_UNIT_DEPTH, in.depthTexture);
  gl.BindSampler(SSLR_UNIT_DEPTH, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_NORMAL, in.normalTexture);
  gl.BindSampler(SSLR_UNIT_NORMAL, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_COLOR, in.colorTexture);
  gl.BindSampler(SSLR_UNIT_COLOR, linearSampler);
  gl.bindTexture2D(SSLR_UNIT_MATERIAL, in.materialTexture);  // 0 unless the host keeps materials apart
  gl.BindSampler(SSLR_UNIT_MATERIAL, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_MASK, in.maskTexture);  // 0 unless the host limits where rays start
  gl.BindSampler(SSLR_UNIT_MASK, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_BACK_DEPTH, in.backDepthTexture);  // 0 unless the host measures thickness
  gl.BindSampler(SSLR_UNIT_BACK_DEPTH, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_BASE_COLOR, in.baseColorTexture);  // 0 unless the host gives coloured F0
  gl.BindSampler(SSLR_UNIT_BASE_COLOR, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_PYRAMID, pyramid.texture);  // read by the depth-only trace (built when a mode needs it)
  gl.BindSampler(SSLR_UNIT_PYRAMID, nearestSampler);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, SSLR_BINDING_FRAME_UBO, frameUbo);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_TILE_SSBO, tileBuffer);
  gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileBuffer);
}

// Levels 0 and 1 of the pyramid, as classification, the level-1 pass and the curved pass write
// them (passes/pyramid_levels01.glsl): image units 1 and 0.
void Context::Impl::bindPyramidLevels01() const {
  gl.BindImageTexture(SSLR_IMAGE_PYRAMID_LEVEL1, pyramid.texture, 1, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
  gl.BindImageTexture(SSLR_IMAGE_PYRAMID_LEVEL0, pyramid.texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
}

// The min-max depth pyramid above level 1, indirect: the group counts are zero unless
// classification listed a tile (common/tiles.glsl). One dispatch builds levels 2..7 (2_pyramid_levels2to7.comp, a
// work group per level-7 cell), a second level 8 where the screen has one.
void Context::Impl::buildPyramid(GLuint blockProgram, GLuint singleProgram) const {
  const int blockTop = std::min(area.levels, kHizBlockTop);
  useProgram(blockProgram);
  gl.bindTexture2D(SSLR_UNIT_PYRAMID, pyramid.texture);
  gl.BindSampler(SSLR_UNIT_PYRAMID, nearestSampler);
  gl.ProgramUniform1i(blockProgram, 0, area.levels);  // uTopLevel
  for (int level = 2; level <= kHizBlockTop; ++level)  // above the top: the top's image, never stored to
    gl.BindImageTexture(static_cast<GLuint>(SSLR_IMAGE_PYRAMID_BLOCK + level - 2), pyramid.texture, std::min(level, blockTop), GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
  dispatchComputeIndirect(kHizDispatchOffset + 3 * 4 * 1);  // level 2's arguments: the blocks
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  const int single = kHizBlockTop + 1;  // (SSLR_HIZ_MAX_LEVELS is 8: one level at most above the blocks)
  if (area.levels < single) return;
  useProgram(singleProgram);
  gl.ProgramUniform1i(singleProgram, 0, single);
  gl.BindImageTexture(SSLR_IMAGE_PYRAMID_BLOCK, pyramid.texture, single, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
  dispatchComputeIndirect(kHizDispatchOffset + 3 * 4 * (single - 1));  // its level's arguments
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

// The last fed-back frame's counts (without waiting: a frame still in flight leaves everything as
// it is): whether it listed a tile (where level 1 is written), and Auto's choice on a software
// renderer. Hysteresis keeps a scene near the threshold from switching every frame; the answers
// are the same either way.
void Context::Impl::readFeedback() {
  if (feedback.fence == nullptr) return;
  const GLenum r = gl.ClientWaitSync(feedback.fence, 0, 0);
  if (r != GL_ALREADY_SIGNALED && r != GL_CONDITION_SATISFIED) return;
  gl.DeleteSync(feedback.fence);
  feedback.fence = nullptr;
  GLuint counts[4] = {};
  gl.GetNamedBufferSubData(feedback.buffer, 0, sizeof(counts), counts);
  feedback.lastFrameListedNoTile = counts[0] == 0;
  if (!feedback.hasTraversal) return;
  const double tileCells = double(counts[0]) * feedback.cellsPerTile;  // pixels, or quads
  const double share = tileCells > 0.0 ? double(counts[3]) / tileCells : 0.0;
  feedback.traversalInline = share > (feedback.traversalInline ? kInlineTraversalShare - 0.05 : kInlineTraversalShare + 0.05);
}

// A frame: validate, plan (which passes run and with which programs, before any GL state is
// touched), create what the plan needs, then the passes in order. Each pass function issues its
// GL commands through the counting wrappers (FrameStats' per-pass commands).
Status Context::Impl::dispatch(const FrameInputs& in, const Settings& settings) {
  haveFrame = false;
  // Temporal history is the previous dispatch's only if that one stored it: a failed or
  // non-temporal dispatch in between breaks the chain (the host's "previous" matrices would not
  // describe the stored frame).
  bool hadHistory = history.valid && !in.historyReset;
  history.valid = false;
  if (Status s = checkCurrentContext("dispatch()"); !s) return s;
  auto constants = frameConstants(in, settings, width, height);  // validates settings + projection
  if (!constants) return constants.status();
  TrafficModel formats;
  if (Status s = checkInputs(in, settings.method, &formats); !s) return s;
  setArea(in);
  recording = {};
  recordingPass = 0;
  // History is of the last frame's rectangle; another one starts afresh (as after a resize).
  hadHistory = hadHistory && !area.changed;
  FramePlan plan = planFrame(settings, constants.value(), hadHistory);
  if (plan.collectStats) plan.traffic = trafficModel(plan, formats, settings);
  if (Status s = buildPrograms(plan, in, settings); !s) return s;
  recordFrame(plan, in, "sslr.dispatch");
  haveFrame = true;
  frameIsRadiance = settings.output == OutputMode::Radiance;
  return {};
}

// This frame's rectangle (FrameInputs::viewport, validated by frameConstants) and its shapes.
void Context::Impl::setArea(const FrameInputs& in) {
  const Viewport rect = frameViewport(in, width, height).value();
  area = areaOf(rect);
  area.changed = rect.x != lastRect.x || rect.y != lastRect.y || rect.width != lastRect.width ||
                 rect.height != lastRect.height;
}

// Every program variant a dispatch with these inputs and settings can choose: with and without
// the level-1 pass (a frame after an empty one), and, under TraversalPass::Auto on a software
// renderer, with the traversal inline and deferred. And both composite programs. Drivers compile a
// program's machine code at its first use, for the textures and samplers bound then (llvmpipe
// does), so each variant also runs once on the host's inputs, as a frame would; then the frame
// state is put back as after create() (warmUp, resetFrameState).
Status Context::Impl::prepare(const FrameInputs& in, const Settings& settings, const PrepareOptions& options) {
  if (Status s = checkCurrentContext("prepare()"); !s) return s;
  auto constants = frameConstants(in, settings, width, height);  // validates settings + projection
  if (!constants) return constants.status();
  if (Status s = checkInputs(in, settings.method); !s) return s;
  if (options.composite) {
    if (settings.output == OutputMode::Radiance)
      return Status::error(StatusCode::InvalidSettings, "sslr: prepare(): PrepareOptions::composite with "
                           "Settings::output = OutputMode::Radiance, which composite() refuses");
    if (Status s = checkCompositeOptions(options.compositeOptions); !s) return s;
  }
  setArea(in);
  const FramePlan base = planFrame(settings, constants.value(), false);
  const std::uint64_t dispatchesBefore = dispatches;
  const int frameIndexBefore = frameIndex;
  // However prepare ends, the warm-up frames leave nothing behind.
  struct Reset {
    Impl& impl;
    std::uint64_t dispatches;
    int frameIndex;
    ~Reset() { impl.resetFrameState(dispatches, frameIndex); }
  } reset{*this, dispatchesBefore, frameIndexBefore};
  for (bool level1Pass : {false, true}) {
    for (bool defer : {false, true}) {
      if ((level1Pass && !base.pyramid) || (defer != base.deferTraversal && !base.feedback)) continue;
      FramePlan f = base;
      f.level1Pass = level1Pass;
      f.deferTraversal = defer;
      f.countTraversal = f.feedback && !defer;
      f.retracePass = f.halfResolution || defer;
      f.quadRetracePass = f.halfResolution && defer;
      f.feedbackWritten = false;
      f.useHistory = false;
      if (Status s = buildPrograms(f, in, settings); !s) return s;
      warmUp(f, in);
      if (options.composite && !level1Pass && defer == base.deferTraversal)
        if (Status s = warmUpComposite(options); !s) return s;
    }
  }
  for (bool overFallback : {false, true})
    if (auto p = compositeProgram(overFallback); !p) return p.status();
  gl.Finish();  // the driver's compiles happen here, not in the host's first frame
  return {};
}

// One frame of plan `f` on the host's inputs, its outputs discarded (prepare).
void Context::Impl::warmUp(FramePlan& f, const FrameInputs& in) {
  recordFrame(f, in, "sslr.prepare");
  history.valid = false;
}

// The frame's passes in order, under the state guard and a debug group of that name.
void Context::Impl::recordFrame(FramePlan& f, const FrameInputs& in, const char* debugGroup) {
  createFrameResources(f);
  detail::StateGuard guard(gl, false);
  gl.PushDebugGroup(GL_DEBUG_SOURCE_THIRD_PARTY, 0, -1, debugGroup);
  beginFrame(f);
  runClassify(f, in);
  runPyramid(f);
  runTrace(f);
  runBlur(f);
  runTemporal(f, in);
  finishFrame(f);
  gl.PopDebugGroup();
}

// Which passes this frame runs. Reads the last frame's feedback (readFeedback), which decides
// where level 1 is written and where the traversal runs.
Context::Impl::FramePlan Context::Impl::planFrame(const Settings& settings,
                                                  const shared::SslrFrame& constants, bool hadHistory) {
  FramePlan f;
  f.frame = constants;
  f.method = settings.method;
  f.halfResolution = settings.halfResolution;
  f.temporal = settings.temporal.enabled;
  f.debugOutputs = settings.debug.outputs;
  f.hitDistance = settings.hitDistance;
  f.historyConfidence = settings.temporal.enabled && settings.temporal.outputConfidence;
  f.collectStats = settings.debug.collectStats;
  // frameConstants decided whether the trace uses the traversal; the pyramid follows it, and so
  // do the curved solids (sslr_shared.h).
  f.pyramid = constants.trace.hizMode != SSLR_HIZ_OFF;
  f.curvedSolids = f.pyramid && constants.trace.curvedSolids != 0;
  // TraversalPass::Auto defers the second tracer (the traversal; traversal first: adaptive L) on
  // software renderers, unless most pixels (at half resolution: quads) needed it last frame (then
  // it runs inline: the pass of its own costs more than it saves). The share is fed back from each
  // such frame.
  const bool adaptiveWithTraversal = settings.method == Method::AdaptiveL && f.pyramid;
  f.feedback = adaptiveWithTraversal && settings.traversal.pass == TraversalPass::Auto && softwareRenderer;
  if (f.pyramid) readFeedback();
  // This frame's counts go to the feedback buffer unless an earlier frame's are still unread there.
  f.feedbackWritten = f.pyramid && feedback.fence == nullptr;
  // After a frame that listed no tile, classification does not write level 1: a pass of its own
  // does, dispatched only if this frame lists one (an empty frame's classification then reads the
  // G-buffer and nothing more).
  f.level1Pass = f.pyramid && feedback.lastFrameListedNoTile;
  f.deferTraversal = adaptiveWithTraversal && (settings.traversal.pass == TraversalPass::Deferred ||
                                               (f.feedback && !feedback.traversalInline));
  // Inline under Auto: the trace (at half resolution the quad pass) counts the pixels (quads) that
  // needed the traversal, as deferred would have listed them.
  f.countTraversal = f.feedback && !f.deferTraversal;
  f.countQuads = f.feedback && settings.halfResolution;
  f.retracePass = settings.halfResolution || f.deferTraversal;
  f.quadRetracePass = settings.halfResolution && f.deferTraversal;
  f.blur = settings.blur.enabled && settings.blur.maxRadiusPx > 0.0f;
  f.wideClassify = !softwareRenderer;
  // History of the previous frame only if it stored one (else its keys may be older: cleared).
  f.useHistory = settings.temporal.enabled && hadHistory;
  return f;
}

// What FrameStats' traffic model needs of this frame: the input formats, which passes and paths
// the plan runs and the pyramid's cell counts.
TrafficModel Context::Impl::trafficModel(const FramePlan& f, TrafficModel formats, const Settings& settings) const {
  TrafficModel m = formats;
  m.width = area.rect.width;
  m.height = area.rect.height;
  m.pyramid = f.pyramid;
  m.classifyLevels01 = f.pyramid && !f.level1Pass;
  m.levels01Pass = f.level1Pass;
  if (f.curvedSolids) m.normalGathers = f.frame.surface.normalEncoding == SSLR_NORMALS_OCTAHEDRAL ? 2 : 3;
  auto cells = [&](int level) {
    const std::uint64_t side = std::uint64_t(1) << level;
    return ((std::uint64_t(area.rect.width) + side - 1) / side) * ((std::uint64_t(area.rect.height) + side - 1) / side);
  };
  m.level1Cells = f.pyramid ? cells(1) : 0;
  for (int level = 2; f.pyramid && level <= area.levels; ++level) m.upperCells += cells(level);
  // A counted fetch is a depth, position or pyramid texel; where both depth and pyramid texels are
  // read the larger (the pyramid's RG32F) is the bound.
  m.fetchBytes = f.method == Method::PositionBuffer ? m.positionBytes
                 : f.pyramid                        ? std::max(m.depthBytes, 8)
                                                    : m.depthBytes;
  m.halfResolution = f.halfResolution;
  m.hitRecord = f.debugOutputs || f.temporal;
  m.iterations = f.debugOutputs;
  m.hitDistance = f.hitDistance;
  m.temporal = f.temporal;
  m.blurTaps = f.blur ? static_cast<int>(std::ceil(std::min(settings.blur.maxRadiusPx, 32.0f))) : 0;
  return m;
}

// Every program the plan runs, built (or found in the cache) before any state is touched. The
// optional inputs, the normal encoding, the material channels and the tracer's role are compiled
// in or out rather than branched on: a CPU rasterizer runs an untaken branch under a lane mask.
Status Context::Impl::buildPrograms(FramePlan& f, const FrameInputs& in, const Settings& settings) {
  const shared::SslrSurface& surface = f.frame.surface;
  inputDefines = std::string(in.maskTexture != 0 ? "#define SSLR_HAS_MASK 1\n" : "") +
                 "#define SSLR_BACK_DEPTH " + (in.backDepthTexture != 0 ? "1\n" : "0\n") +
                 (in.materialTexture != 0 ? "#define SSLR_SEPARATE_MATERIAL 1\n" : "") +
                 (in.baseColorTexture != 0 ? "#define SSLR_COLORED_F0 1\n" : "") +
                 "#define SSLR_NORMAL_ENCODING " + std::to_string(surface.normalEncoding) + "\n" +
                 "#define SSLR_WORLD_NORMALS " + (surface.normalFromStored0.w != 0.0f ? "1" : "0") + "\n" +
                 "#define SSLR_NORMAL_UNSIGNED " + (shared::sslrUnsignedNormalUnpack(surface) ? "1" : "0") + "\n" +
                 "#define SSLR_ROUGHNESS_CHANNEL " + std::to_string(surface.roughnessChannel) + "\n" +
                 "#define SSLR_REFLECTANCE_CHANNEL " + std::to_string(surface.reflectanceChannel) + "\n";
  std::string methodDefines = "#define SSLR_HIZ_MODE " + std::to_string(f.frame.trace.hizMode) + "\n";
  const std::string curvedDefine = std::string("#define SSLR_CURVED_SOLIDS ") + (f.curvedSolids ? "1\n" : "0\n");
  methodDefines += curvedDefine;
  if (settings.debug.oneBodyTraversal) methodDefines += "#define SSLR_HIZ_ONE_BODY 1\n";
  if (settings.method == Method::PositionBuffer) methodDefines += "#define SSLR_METHOD_POSITION_BUFFER 1\n";
  if (settings.method == Method::ScreenSpaceDDA) methodDefines += "#define SSLR_METHOD_DDA 1\n";
  if (settings.method == Method::FidelityFxSssr) methodDefines += "#define SSLR_METHOD_FFX 1\n";
  const std::string statsDefine = settings.debug.collectStats ? "#define SSLR_COLLECT_STATS 1\n" : "";
  std::string traceDefines = methodDefines + statsDefine;
  if (settings.debug.outputs) traceDefines += "#define SSLR_DEBUG_OUTPUTS 1\n";
  if (settings.temporal.enabled) traceDefines += "#define SSLR_TEMPORAL_HITS 1\n";
  if (settings.hitDistance) traceDefines += "#define SSLR_HIT_DISTANCE 1\n";
  if (settings.glossy.mode == GlossyMode::Stochastic) traceDefines += "#define SSLR_STOCHASTIC 1\n";
  const std::string deferDefine = f.deferTraversal ? "#define SSLR_DEFER_TRAVERSAL 1\n" : "";
  const std::string countDefine = "#define SSLR_COUNT_TRAVERSAL 1\n";
  // The full-resolution trace; at half resolution the shading from the quads' rays instead.
  const char* traceEntry = settings.halfResolution ? "3_shade_from_quads.comp" : "3_trace.comp";
  const std::string retraceDefines = traceDefines;
  if (!settings.halfResolution) traceDefines += deferDefine + (f.countTraversal ? countDefine : "");
  const std::string quadDefines = methodDefines + statsDefine;
  // With the pyramid, classification (which reads every depth anyway) writes its levels 0 and 1,
  // unless the last frame listed no tile (then the levels-0-and-1 pass does, if this frame lists
  // one). Under DeviceProfile::Gpu it also does the clean-up's and the pyramid arguments' work.
  std::string classifyDefines = f.pyramid && !f.level1Pass ? "#define SSLR_CLASSIFY_LEVEL1 1\n" + curvedDefine : "";
  if (f.wideClassify && f.pyramid) classifyDefines += "#define SSLR_CLASSIFY_ARGS 1\n";
  const std::pair<GLuint*, Expected<GLuint>> built[] = {
      {&f.programs.classify, computeProgram(f.wideClassify ? "1_classify_wide.comp" : "1_classify.comp", classifyDefines)},
      {&f.programs.cleanup, optionalProgram(!f.wideClassify, "1_clear_untraced.comp", "")},
      {&f.programs.hizArgs, optionalProgram(f.pyramid && !f.wideClassify, "2_pyramid_arguments.comp", curvedDefine)},
      {&f.programs.level1, optionalProgram(f.level1Pass, "2_pyramid_levels01.comp", curvedDefine)},
      {&f.programs.curved, optionalProgram(f.curvedSolids, "2_pyramid_curved.comp", curvedDefine)},
      {&f.programs.hizBuild, optionalProgram(f.pyramid, "2_pyramid_levels2to7.comp", "")},
      {&f.programs.hizSingle, optionalProgram(f.pyramid && area.levels > kHizBlockTop, "2_pyramid_top_level.comp", "")},
      {&f.programs.trace, computeProgram(traceEntry, traceDefines)},
      {&f.programs.quads, optionalProgram(settings.halfResolution, "3_trace_quads.comp",
                                          quadDefines + deferDefine + (f.countQuads ? countDefine : "") +
                                              (f.wideClassify ? "#define SSLR_QUADS_WIDE 1\n" : ""))},
      {&f.programs.quadRetrace, optionalProgram(f.quadRetracePass, "3_retrace_quads.comp", quadDefines)},
      {&f.programs.retrace, optionalProgram(f.retracePass, "3_retrace.comp", retraceDefines)},
      {&f.programs.blurH, optionalProgram(f.blur, "4_blur.comp", "#define SSLR_BLUR_AXIS ivec2(1, 0)\n")},
      {&f.programs.blurV, optionalProgram(f.blur, "4_blur.comp", "#define SSLR_BLUR_AXIS ivec2(0, 1)\n#define SSLR_BLUR_VERTICAL 1\n")},
      {&f.programs.temporalBlend,
       optionalProgram(settings.temporal.enabled, "5_temporal_blend.comp",
                       f.historyConfidence ? "#define SSLR_HISTORY_CONFIDENCE 1\n" : "")},
      {&f.programs.temporalStore, optionalProgram(settings.temporal.enabled, "5_temporal_store.comp", "")},
      {&f.programs.historyCleanup, optionalProgram(settings.temporal.enabled, "5_clear_untraced_history.comp", "")}};
  for (const auto& [slot, program] : built) {
    if (!program) return program.status();
    *slot = program.value();
  }
  return {};
}

Expected<GLuint> Context::Impl::optionalProgram(bool wanted, const char* entry, const std::string& defines) {
  return wanted ? computeProgram(entry, defines) : Expected<GLuint>(GLuint(0));
}

// The textures and buffers the plan needs that no earlier frame created.
void Context::Impl::createFrameResources(const FramePlan& f) {
  if (f.halfResolution && halfRes.quadHit == 0) {
    const int qw = (width + 1) / 2, qh = (height + 1) / 2;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &halfRes.quadHit);
    gl.TextureStorage2D(halfRes.quadHit, 1, GL_RGBA32F, qw, qh);
    label(GL_TEXTURE, halfRes.quadHit, "sslr.quadHit");
    gl.CreateTextures(GL_TEXTURE_2D, 1, &halfRes.quadSurface);
    gl.TextureStorage2D(halfRes.quadSurface, 1, GL_RGBA16F, qw, qh);
    label(GL_TEXTURE, halfRes.quadSurface, "sslr.quadSurface");
  }
  if (f.curvedSolids && pyramid.curvedQuads == 0) {
    gl.CreateBuffers(1, &pyramid.curvedQuads);  // header (passes/curved_quads.glsl) + one entry per quad
    gl.NamedBufferStorage(pyramid.curvedQuads, static_cast<GLsizeiptr>((8 + static_cast<size_t>(pyramid.level1Width) * pyramid.level1Height) * sizeof(GLuint)),
                          nullptr, GL_DYNAMIC_STORAGE_BIT);
    label(GL_BUFFER, pyramid.curvedQuads, "sslr.curvedQuads");
  }
  if (f.pyramid && pyramid.texture == 0) createPyramid();
  if (f.pyramid && feedback.buffer == 0) {
    gl.CreateBuffers(1, &feedback.buffer);
    gl.NamedBufferStorage(feedback.buffer, 4 * sizeof(GLuint), nullptr, 0);
    label(GL_BUFFER, feedback.buffer, "sslr.feedback");
  }
  if ((f.retracePass || f.countTraversal) && retraceBuffer == 0) {
    gl.CreateBuffers(1, &retraceBuffer);
    // Header, then a pixel list (at most every pixel of the traced tiles) or the quad list (a slot
    // and a tile's quads per tile; passes/retrace_list.glsl).
    const size_t tileCount = static_cast<size_t>(tilesX()) * tilesY();
    gl.NamedBufferStorage(retraceBuffer,
                          static_cast<GLsizeiptr>((4 + tileCount * SSLR_TILE_SIZE * SSLR_TILE_SIZE) * sizeof(GLuint)),
                          nullptr, GL_DYNAMIC_STORAGE_BIT);
    label(GL_BUFFER, retraceBuffer, "sslr.retrace");
  }
  // The hit record and iteration images only for the frames that write them (20 B per pixel).
  if ((f.debugOutputs || f.temporal) && hit == 0) hit = makeTexture(GL_RGBA32F, "sslr.hit");
  if (f.hitDistance && hitDistance == 0) hitDistance = makeTexture(GL_R32F, "sslr.hitDistance");
  if (f.historyConfidence && history.confidence == 0) history.confidence = makeTexture(GL_R8, "sslr.historyConfidence");
  if (f.debugOutputs && iterations == 0) iterations = makeTexture(GL_R32F, "sslr.iterations");
  if (f.temporal && history.color == 0) {
    history.color = makeTexture(GL_RGBA16F, "sslr.history");
    history.key = makeTexture(GL_R32F, "sslr.historyKey");
  }
}

// The frame's constants, the tile list's header, the debug images and the stats slot.
void Context::Impl::beginFrame(FramePlan& f) {
  const float zero[4] = {0, 0, 0, 0};
  if (f.temporal && !f.useHistory) clearTexImage(history.key, GL_RED, GL_FLOAT, zero);
  f.frame.temporal.history = f.useHistory ? 1 : 0;
  frameIndex = frameIndex == 0x7fffffff ? 1 : frameIndex + 1;
  f.frame.trace.frameIndex = frameIndex;
  bufferSubData(frameUbo, 0, sizeof(f.frame), &f.frame);
  writeTileHeader();
  if (area.changed) startNewArea();
  // reflection and resolved are not cleared: the clean-up pass (1_clear_untraced.comp)
  // zeroes the tiles the previous frame traced and this one does not. The debug images are
  // cleared whole (debug only).
  if (f.debugOutputs) {
    clearTexImage(hit, GL_RGBA, GL_FLOAT, zero);
    clearTexImage(iterations, GL_RED, GL_FLOAT, zero);
  }
  // The hit distance is cleared whole too (0: no hit), so that tiles not traced read 0.
  if (f.hitDistance) clearTexImage(hitDistance, GL_RED, GL_FLOAT, zero);
  if (f.historyConfidence) clearTexImage(history.confidence, GL_RED, GL_FLOAT, zero);
  // Stats go to the ring slot of this dispatch (the oldest; a slot still unread is overwritten:
  // lastStats then reports a later frame).
  ++dispatches;
  if (f.collectStats) {
    f.slot = &statsRing[dispatches % kStatsRing];
    if (f.slot->fence != nullptr) gl.DeleteSync(f.slot->fence);
    f.slot->fence = nullptr;
    f.slot->frame = dispatches;
    const GLuint statsZero[SSLR_STATS_COUNT] = {};
    bufferSubData(f.slot->buffer, 0, sizeof(statsZero), statsZero);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_STATS_SSBO, f.slot->buffer);
  }
}

// Tile list header: trace dispatch (0, 1, 1), draw (6 vertices, 0 instances), blur dispatch,
// pyramid dispatches (0, 1, 1) per level and their real group counts (2_pyramid_arguments.comp copies them
// over when it lists a tile). The previous frame's trace dispatch and tile list become the
// clean-up pass's.
void Context::Impl::writeTileHeader() const {
  // (The tile arrays are laid out for this frame's tile grid, common/tiles.glsl.)
  const GLsizeiptr capacity = static_cast<GLsizeiptr>(area.tilesX) * area.tilesY;
  copyBufferSubData(tileBuffer, tileBuffer, 0, kCleanupDispatchOffset, 3 * sizeof(GLuint));
  copyBufferSubData(tileBuffer, tileBuffer, kTileHeader * sizeof(GLuint),
                    (kTileHeader + 4 * capacity) * sizeof(GLuint), capacity * sizeof(GLuint));
  shared::SslrTileHeader header{};
  header.dispatchY = header.dispatchZ = 1;  // the trace: no tile yet
  header.drawCount = 6;                     // the composite: 6 vertices per tile, no instance yet
  header.blurDispatchY = header.blurDispatchZ = 1;
  header.quadDispatchY = header.quadDispatchZ = 1;  // the quad pass under DeviceProfile::Gpu: no group yet
  // Used: level 1's (the level-1 pass: 8x8 level-1 cells a group), level 2's (2_pyramid_levels2to7.comp's blocks:
  // one kHizBlockTop cell a group) and the level above the blocks' (8x8 of its cells a group).
  for (int level = 1; level <= SSLR_HIZ_MAX_LEVELS; ++level) {
    GLuint* live = &header.hizDispatch[3 * (level - 1)];
    GLuint* real = &header.hizGroups[3 * (level - 1)];
    live[0] = 0, live[1] = 1, live[2] = 1;
    // Pixels a group spans: 8 cells of its level (the blocks: one kHizBlockTop cell); the padded
    // frame is 2 level1Width x 2 level1Height pixels.
    const int groupPx = level == 2 ? 1 << kHizBlockTop : 8 << level;
    const bool used = level <= area.levels && (level <= 2 || level == kHizBlockTop + 1);
    real[0] = used ? static_cast<GLuint>((2 * area.level1Width + groupPx - 1) / groupPx) : 0u;
    real[1] = used ? static_cast<GLuint>((2 * area.level1Height + groupPx - 1) / groupPx) : 1u;
    real[2] = 1;
  }
  bufferSubData(tileBuffer, 0, kHeaderUploadBytes, &header);
}

// A frame in another rectangle of the textures than the last frame run (FrameInputs::viewport):
// the clean-up passes know only the tiles of the current rectangle's grid, so the last rectangle
// of the outputs is cleared here, and the tile arrays (laid out for the grid) zeroed, with no
// clean-up of the last frame's list. Nothing is reallocated.
void Context::Impl::startNewArea() {
  const float zero[4] = {0, 0, 0, 0};
  for (GLuint t : {reflection, resolved}) {
    gl.ClearTexSubImage(t, 0, lastRect.x, lastRect.y, 0, lastRect.width, lastRect.height, 1, GL_RGBA, GL_FLOAT, zero);
    ++recording[recordingPass].uploads;
  }
  const GLuint zeroWord = 0;
  const GLsizeiptr arrays = static_cast<GLsizeiptr>(kTileArrays) * tilesX() * tilesY();  // (allocated for the context)
  gl.ClearNamedBufferSubData(tileBuffer, GL_R32UI, kTileHeader * sizeof(GLuint), arrays * sizeof(GLuint), GL_RED_INTEGER,
                             GL_UNSIGNED_INT, &zeroWord);
  ++recording[recordingPass].uploads;
  const GLuint noCleanup[3] = {0, 1, 1};
  bufferSubData(tileBuffer, kCleanupDispatchOffset, sizeof(noCleanup), noCleanup);
  lastRect = area.rect;
}

// Pass `pass` starts here: its timestamp, and its commands counted from here on.
void Context::Impl::beginPass(const FramePlan& f, int pass) const {
  if (f.slot != nullptr && timestamps) gl.QueryCounter(f.slot->queries[pass], GL_TIMESTAMP);
  recordingPass = pass;
}

// Pass 1: classification over the screen (the tile list; with the pyramid, its levels 0 and 1),
// then the clean-up of the tiles the previous frame traced and this one does not (DeviceProfile::Gpu:
// inside classification).
void Context::Impl::runClassify(const FramePlan& f, const FrameInputs& in) const {
  beginPass(f, 0);
  bindInputs(in);
  if (f.method == Method::PositionBuffer) {
    gl.bindTexture2D(SSLR_UNIT_POSITION, in.positionTexture);
    gl.BindSampler(SSLR_UNIT_POSITION, nearestSampler);
  }
  useProgram(f.programs.classify);
  if (f.pyramid) bindPyramidLevels01();
  if (f.curvedSolids) {
    // The curved pass's dispatch (0, 1, 1) until the pyramid-args pass sets it; no quad listed.
    const GLuint curvedHeader[8] = {0, 1, 1, 0, 0, 0, 0, 0};
    bufferSubData(pyramid.curvedQuads, 0, sizeof(curvedHeader), curvedHeader);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_CURVED_SSBO, pyramid.curvedQuads);
  }
  if (f.wideClassify) {  // 2x2 tiles a group, the clean-up inside
    gl.BindImageTexture(SSLR_IMAGE_CLASSIFY_REFLECTION, reflection, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl.BindImageTexture(SSLR_IMAGE_CLASSIFY_RESOLVED, resolved, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatchCompute(static_cast<GLuint>((area.tilesX + 1) / 2), static_cast<GLuint>((area.tilesY + 1) / 2), 1);
  } else {
    dispatchCompute(static_cast<GLuint>(area.tilesX), static_cast<GLuint>(area.tilesY), 1);
  }
  memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  if (f.wideClassify) return;
  useProgram(f.programs.cleanup);
  gl.BindImageTexture(SSLR_IMAGE_REFLECTION, reflection, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  gl.BindImageTexture(SSLR_IMAGE_RESOLVED, resolved, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  dispatchComputeIndirect(kCleanupDispatchOffset);
  memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

// Pass 2: the depth pyramid, when the trace reads it: its dispatch arguments (zero groups unless a
// tile was listed), level 1 where classification left it, the curved quads' cells, levels 2+.
void Context::Impl::runPyramid(const FramePlan& f) const {
  beginPass(f, 1);
  if (!f.pyramid) return;
  if (!f.wideClassify) {  // (Gpu: classification set the arguments)
    useProgram(f.programs.hizArgs);
    dispatchCompute(1, 1, 1);
    memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  }
  if (f.level1Pass) {  // level 1 (2_pyramid_levels01.comp) through level 1's pyramid arguments
    useProgram(f.programs.level1);
    bindPyramidLevels01();  // (the clean-up pass took image unit 0)
    dispatchComputeIndirect(kHizDispatchOffset);
    memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                  GL_COMMAND_BARRIER_BIT);
  }
  if (f.curvedSolids) {  // the listed quads' cells with their solids (2_pyramid_curved.comp)
    useProgram(f.programs.curved);
    bindPyramidLevels01();
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, pyramid.curvedQuads);
    dispatchComputeIndirect(0);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileBuffer);
    memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  buildPyramid(f.programs.hizBuild, f.programs.hizSingle);
}

// Pass 3: the trace over the listed tiles (half resolution: the quad pass first; a deferred
// traversal or half resolution: the retrace pass after).
void Context::Impl::runTrace(const FramePlan& f) const {
  beginPass(f, 2);
  const GLuint retraceHeader[4] = {0, 1, 1, 0};  // dispatch (0, 1, 1), count 0
  if (f.retracePass || f.countTraversal) {
    bufferSubData(retraceBuffer, 0, sizeof(retraceHeader), retraceHeader);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_RETRACE_SSBO, retraceBuffer);
  }
  if (f.halfResolution) runQuads(f);
  useProgram(f.programs.trace);
  gl.BindImageTexture(SSLR_IMAGE_REFLECTION, reflection, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  gl.BindImageTexture(SSLR_IMAGE_RESOLVED, resolved, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  if (f.debugOutputs || f.temporal) gl.BindImageTexture(SSLR_IMAGE_HIT, hit, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  if (f.debugOutputs) gl.BindImageTexture(SSLR_IMAGE_ITERATIONS, iterations, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  if (f.hitDistance)
    gl.BindImageTexture(SSLR_IMAGE_HIT_DISTANCE, hitDistance, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  dispatchComputeIndirect(0);
  if (f.retracePass) {  // the pixels whose quad's ray did not answer them, or that need the traversal
    memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    useProgram(f.programs.retrace);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, retraceBuffer);
    dispatchComputeIndirect(0);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileBuffer);
  }
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                GL_COMMAND_BARRIER_BIT);
}

// Half resolution's quad pass (one ray per 2x2 quad), its retrace of the quads that need the
// traversal, and the retrace list handed on to the pixels.
void Context::Impl::runQuads(const FramePlan& f) const {
  const GLuint retraceHeader[4] = {0, 1, 1, 0};
  useProgram(f.programs.quads);
  gl.BindImageTexture(SSLR_IMAGE_QUAD_HIT, halfRes.quadHit, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  gl.BindImageTexture(SSLR_IMAGE_QUAD_SURFACE, halfRes.quadSurface, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  // One group per listed tile (Software: 16 invocations), or per 4 of them (Gpu: 64).
  dispatchComputeIndirect(f.wideClassify ? kQuadDispatchOffset : 0);
  if (f.quadRetracePass) {  // the quads whose ray needs the traversal
    memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    useProgram(f.programs.quadRetrace);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, retraceBuffer);
    dispatchComputeIndirect(0);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileBuffer);
  }
  if (f.quadRetracePass || f.countQuads) {
    // The quads that needed the traversal (Auto's feedback), then the list is the pixels'.
    memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    if (f.countQuads && f.feedbackWritten)
      copyBufferSubData(retraceBuffer, feedback.buffer, 3 * sizeof(GLuint), 3 * sizeof(GLuint), sizeof(GLuint));
    bufferSubData(retraceBuffer, 0, sizeof(retraceHeader), retraceHeader);
  }
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  gl.bindTexture2D(SSLR_UNIT_QUAD_HIT, halfRes.quadHit);
  gl.BindSampler(SSLR_UNIT_QUAD_HIT, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_QUAD_SURFACE, halfRes.quadSurface);
  gl.BindSampler(SSLR_UNIT_QUAD_SURFACE, nearestSampler);
}

// Pass 4: the separable blur (resolved -> blurTemp -> resolved, radii from the reflection's alpha)
// over the tiles the trace listed as having a pixel to blur.
void Context::Impl::runBlur(const FramePlan& f) const {
  beginPass(f, 3);
  if (!f.blur) return;
  for (GLuint unit : {SSLR_UNIT_BLUR_INPUT, SSLR_UNIT_BLUR_REFLECTION, SSLR_UNIT_BLUR_UNBLURRED})
    gl.BindSampler(unit, nearestSampler);
  useProgram(f.programs.blurH);
  gl.bindTexture2D(SSLR_UNIT_BLUR_INPUT, resolved);
  gl.bindTexture2D(SSLR_UNIT_BLUR_REFLECTION, reflection);
  gl.BindImageTexture(SSLR_IMAGE_BLUR_OUTPUT, blurTemp, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  dispatchComputeIndirect(kBlurDispatchOffset);
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  useProgram(f.programs.blurV);
  gl.bindTexture2D(SSLR_UNIT_BLUR_INPUT, blurTemp);
  gl.bindTexture2D(SSLR_UNIT_BLUR_UNBLURRED, resolved);  // read where blurTemp is not written (see 4_blur.comp)
  gl.BindImageTexture(SSLR_IMAGE_BLUR_OUTPUT, resolved, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  dispatchComputeIndirect(kBlurDispatchOffset);
}

// Pass 5 (Settings::temporal): blend with the reprojected history, store this frame's output and
// keys, forget the tiles traced last frame and not now.
void Context::Impl::runTemporal(const FramePlan& f, const FrameInputs& in) {
  beginPass(f, 4);
  if (!f.temporal) return;
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  for (GLuint unit : {SSLR_UNIT_TEMPORAL_CURRENT, SSLR_UNIT_HISTORY, SSLR_UNIT_HISTORY_KEY})
    gl.BindSampler(unit, nearestSampler);
  useProgram(f.programs.temporalBlend);
  gl.bindTexture2D(SSLR_UNIT_MOTION, in.motionTexture);  // the pyramid's unit: free after the trace
  gl.BindSampler(SSLR_UNIT_MOTION, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_HIT_RECORD, hit);  // written by the trace on the listed tiles (SSLR_TEMPORAL_HITS)
  gl.BindSampler(SSLR_UNIT_HIT_RECORD, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_TEMPORAL_CURRENT, resolved);
  gl.bindTexture2D(SSLR_UNIT_HISTORY, history.color);
  gl.bindTexture2D(SSLR_UNIT_HISTORY_KEY, history.key);
  gl.BindImageTexture(SSLR_IMAGE_TEMPORAL_OUTPUT, blurTemp, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  if (f.historyConfidence)
    gl.BindImageTexture(SSLR_IMAGE_HISTORY_CONFIDENCE, history.confidence, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8);
  dispatchComputeIndirect(0);
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  useProgram(f.programs.temporalStore);
  gl.bindTexture2D(SSLR_UNIT_TEMPORAL_CURRENT, blurTemp);
  gl.bindTexture2D(SSLR_UNIT_HISTORY, 0);
  gl.bindTexture2D(SSLR_UNIT_HISTORY_KEY, 0);
  gl.BindImageTexture(SSLR_IMAGE_TEMPORAL_OUTPUT, resolved, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  gl.BindImageTexture(SSLR_IMAGE_HISTORY, history.color, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  gl.BindImageTexture(SSLR_IMAGE_HISTORY_KEY, history.key, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  dispatchComputeIndirect(0);
  memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  useProgram(f.programs.historyCleanup);
  dispatchComputeIndirect(kCleanupDispatchOffset);
  history.valid = true;
}

// The end of a frame: every write made visible to the host, the feedback and the stats copied on
// the GPU (no read-back) and fenced.
void Context::Impl::finishFrame(const FramePlan& f) {
  beginPass(f, 5);
  memoryBarrier(GL_ALL_BARRIER_BITS);
  if (f.feedbackWritten) {  // (listed tiles, -, -, pixels or quads that needed the traversal)
    copyBufferSubData(tileBuffer, feedback.buffer, 0, 0, sizeof(GLuint));
    if (f.feedback && !f.halfResolution)  // (half resolution copied its quads' count in runQuads)
      copyBufferSubData(retraceBuffer, feedback.buffer, 3 * sizeof(GLuint), 3 * sizeof(GLuint), sizeof(GLuint));
    feedback.hasTraversal = f.feedback;
    feedback.cellsPerTile = f.halfResolution ? SSLR_TILE_QUADS : SSLR_TILE_SIZE * SSLR_TILE_SIZE;
    feedback.fence = gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  }
  if (f.slot != nullptr) {
    f.slot->traversalDeferred = f.deferTraversal;
    f.slot->followedEmptyFrame = f.level1Pass;
    f.slot->traffic = f.traffic;
    copyBufferSubData(tileBuffer, f.slot->buffer, 0, SSLR_STATS_LISTED_TILES * sizeof(GLuint), sizeof(GLuint));
    copyBufferSubData(tileBuffer, f.slot->buffer, kBlurDispatchOffset, SSLR_STATS_BLUR_TILES * sizeof(GLuint),
                      sizeof(GLuint));
    f.slot->fence = gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    f.slot->commands = recording;
  }
}

}  // namespace sslr
