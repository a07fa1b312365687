// A frame: validation, its plan (which passes run, with which programs), the resources the plan
// needs, the frame's start (constants, tile list header, stats slot) and end (feedback, stats),
// and prepare()'s warm-up of every variant. The passes themselves are in passes/*.cpp:
// classify -> pyramid (when a mode traces it) -> trace (deferred traversal: first stage ->
// retrace of the listed pixels; half resolution: quads [-> quad retrace] -> reuse -> retrace) ->
// blur H -> blur V -> temporal. Everything after classification runs over the listed tiles (or
// listed pixels) only.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "context_impl.hpp"
#include "gl_state.hpp"
#include "sslr/reference.hpp"

namespace sslr {

namespace {

// A tracing pass's program defines in each role a frame can give it (passes/retrace_list.glsl):
// the first stage alone (a deferred frame; SSLR_DEFER_TRAVERSAL), the whole tracer over the listed
// tiles, and the whole tracer that is also the retrace's program (SSLR_RETRACE_ROLE). `count`:
// TraversalPass::Auto's feedback count (SSLR_COUNT_TRAVERSAL).
struct TraceRoleDefines {
  std::string firstStage, whole, retrace;
};

TraceRoleDefines traceRoleDefines(const std::string& base, bool count) {
  const std::string countDefine = count ? "#define SSLR_COUNT_TRAVERSAL 1\n" : "";
  TraceRoleDefines d;
  d.firstStage = base + "#define SSLR_DEFER_TRAVERSAL 1\n" + countDefine;
  d.whole = base + countDefine;
  d.retrace = d.whole + "#define SSLR_RETRACE_ROLE 1\n";
  return d;
}

// The projection's kind and the depth convention as #defines (shared/projection.h): view 0's where
// every view agrees, else -1 (the programs read the block). All three are defined or none is (the
// header's defaults come as one).
std::string projectionDefines(const shared::SslrFrame& view0, const std::vector<shared::SslrFrame>& others) {
  const auto agreed = [&](const char* name, int (*of)(const shared::SslrFrame&)) {
    for (const shared::SslrFrame& view : others)
      if (of(view) != of(view0)) return "#define " + std::string(name) + " -1\n";
    return "#define " + std::string(name) + " " + std::to_string(of(view0)) + "\n";
  };
  return agreed("SSLR_ORTHOGRAPHIC", [](const shared::SslrFrame& v) { return v.proj.orthographic; }) +
         agreed("SSLR_NDC_ZERO_TO_ONE", [](const shared::SslrFrame& v) { return v.proj.ndcZeroToOne; }) +
         agreed("SSLR_REVERSED_Z", [](const shared::SslrFrame& v) { return v.surface.reversedZ; });
}

}  // namespace

// A frame: validate, plan (which passes run and with which programs, before any GL state is
// touched), create what the plan needs, then the passes in order. Each pass function issues its
// GL commands through the counting wrappers (FrameStats' per-pass commands).
Status Context::Impl::dispatch(std::span<const FrameInputs> inputs, const Settings& settings) {
  haveFrame = false;
  // Temporal history is the previous dispatch's only if that one stored it: a failed or
  // non-temporal dispatch in between breaks the chain (the host's "previous" matrices would not
  // describe the stored frame).
  bool hadHistory = temporal.valid && !inputs.empty() && !inputs[0].historyReset;
  temporal.valid = false;
  if (Status s = checkCurrentContext("dispatch()"); !s) return s;
  // Without a history (the first temporal frame, a reset) no previous frame exists: a host's
  // all-zero previousClipFromView says so and is taken as this frame's own (nothing is reprojected).
  std::vector<FrameInputs> firstFrame;
  const auto givesNoPrevious = [](const FrameInputs& view) { return view.previousClipFromView == glm::dmat4(0.0); };
  if (settings.temporal.enabled && !hadHistory && std::any_of(inputs.begin(), inputs.end(), givesNoPrevious)) {
    firstFrame.assign(inputs.begin(), inputs.end());
    for (FrameInputs& view : firstFrame)
      if (givesNoPrevious(view)) view.previousClipFromView = view.clipFromView;
    inputs = firstFrame;
  }
  shared::SslrFrame constants{};
  std::vector<shared::SslrFrame> otherViews;
  if (Status s = viewConstants(inputs, settings, "dispatch()", constants, otherViews); !s) return s;
  const FrameInputs& in = inputs[0];  // (the textures, layout and viewport every view shares)
  TrafficModel formats;
  if (Status s = checkInputs(in, settings.method, &formats); !s) return s;
  setArea(in);
  recording = {};
  recordingPass = 0;
  // History is of the last frame's rectangle; another one starts afresh (as after a resize).
  hadHistory = hadHistory && !area.changed;
  FramePlan plan = planFrame(settings, constants, hadHistory);
  plan.otherViews = std::move(otherViews);
  if (plan.collectStats) plan.traffic = trafficModel(plan, formats, settings);
  if (Status s = buildPrograms(plan, in, settings); !s) return s;
  recordFrame(plan, in, "sslr.dispatch");
  haveFrame = true;
  frameIsRadiance = settings.output == OutputMode::Radiance;
  return {};
}

// Every view's constants (frameConstants validates each view's settings and projection); the
// views share their textures, layout, viewport and everything but their matrices, so that one
// plan and one set of programs serve them all.
Status Context::Impl::viewConstants(std::span<const FrameInputs> in, const Settings& settings, const char* call,
                                    shared::SslrFrame& constants, std::vector<shared::SslrFrame>& others) const {
  const std::string where = std::string("sslr: ") + call + ": ";
  if (in.size() != static_cast<size_t>(views))
    return Status::error(StatusCode::InvalidInput, where + std::to_string(in.size()) + " FrameInputs for a context of " +
                         std::to_string(views) + " view(s) (ContextDesc::views): give one a view");
  others.clear();
  for (size_t v = 0; v < in.size(); ++v) {
    auto c = frameConstants(in[v], settings, width, height);
    if (!c) {
      if (views == 1) return c.status();
      return Status::error(c.status().code(), c.status().message() + " (view " + std::to_string(v) + ")");
    }
    if (v == 0) {
      constants = c.value();
      continue;
    }
    const FrameInputs& a = in[0];
    const FrameInputs& b = in[v];
    const std::string which = where + "views[" + std::to_string(v) + "] ";
    const std::pair<GLName FrameInputs::*, const char*> textures[] = {
        {&FrameInputs::colorTexture, "colorTexture"},       {&FrameInputs::normalTexture, "normalTexture"},
        {&FrameInputs::depthTexture, "depthTexture"},       {&FrameInputs::positionTexture, "positionTexture"},
        {&FrameInputs::materialTexture, "materialTexture"}, {&FrameInputs::maskTexture, "maskTexture"},
        {&FrameInputs::backDepthTexture, "backDepthTexture"}, {&FrameInputs::baseColorTexture, "baseColorTexture"},
        {&FrameInputs::motionTexture, "motionTexture"}};
    for (const auto& [member, name] : textures)
      if (a.*member != b.*member)
        return Status::error(StatusCode::InvalidInput, which + "names " + name + " " + std::to_string(b.*member) +
                             ", views[0] " + std::to_string(a.*member) +
                             ": every view reads its layer of the same 2D array textures");
    if (a.historyReset != b.historyReset)
      return Status::error(StatusCode::InvalidInput, which + "historyReset differs from views[0]'s: the views share one history");
    // Asked apart: the uniform block holds the exposure only where the radiance clamp reads it.
    if (a.exposure != b.exposure)
      return Status::error(StatusCode::InvalidInput, which + "exposure " + std::to_string(b.exposure) + " differs from views[0]'s " +
                           std::to_string(a.exposure) + ": the views share one exposure");
    // What the plan and the programs are built from must agree: all but the normal transform
    // (world normals: each view's viewFromWorld) and the projection.
    shared::SslrSurface sa = constants.surface, sb = c.value().surface;
    for (shared::SslrSurface* sv : {&sa, &sb})
      for (glm::vec4* row : {&sv->normalFromStored0, &sv->normalFromStored1, &sv->normalFromStored2})
        *row = glm::vec4(0.0f, 0.0f, 0.0f, row->w);
    if (std::memcmp(&sa, &sb, sizeof(sa)) != 0 || std::memcmp(&constants.trace, &c.value().trace, sizeof(constants.trace)) != 0)
      return Status::error(StatusCode::InvalidInput, which + "differs from views[0] in its depth convention, surface layout, "
                           "viewport or exposure: views may differ only in their matrices");
    others.push_back(c.value());
  }
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
Status Context::Impl::prepare(std::span<const FrameInputs> inputs, const Settings& settings, const PrepareOptions& options) {
  if (Status s = checkCurrentContext("prepare()"); !s) return s;
  shared::SslrFrame constants{};
  std::vector<shared::SslrFrame> otherViews;
  if (Status s = viewConstants(inputs, settings, "prepare()", constants, otherViews); !s) return s;
  const FrameInputs& in = inputs[0];
  if (Status s = checkInputs(in, settings.method); !s) return s;
  if (options.composite) {
    if (settings.output == OutputMode::Radiance)
      return Status::error(StatusCode::InvalidSettings, "sslr: prepare(): PrepareOptions::composite with "
                           "Settings::output = OutputMode::Radiance, which composite() refuses");
    if (Status s = checkCompositeOptions(options.compositeOptions); !s) return s;
  }
  setArea(in);
  FramePlan base = planFrame(settings, constants, false);
  base.otherViews = std::move(otherViews);
  const std::uint64_t dispatchesBefore = dispatches;
  const int frameIndexBefore = frameIndex;
  // However prepare ends, the warm-up frames leave nothing behind.
  struct Reset {
    Impl& impl;
    std::uint64_t dispatches;
    int frameIndex;
    ~Reset() { impl.resetFrameState(dispatches, frameIndex); }
  } reset{*this, dispatchesBefore, frameIndexBefore};
  std::vector<FramePlan> variants;
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
      variants.push_back(f);
    }
  }
  // First every program of every variant is handed to the driver, then each is waited on: a
  // driver that compiles in parallel (GL_KHR_parallel_shader_compile) builds them at once. A
  // failure shows when the second round asks for the program.
  issueProgramsOnly = true;
  for (FramePlan f : variants) (void)buildPrograms(f, in, settings);
  for (bool overFallback : {false, true}) (void)compositeProgram(overFallback);
  issueProgramsOnly = false;
  for (FramePlan& f : variants) {
    if (Status s = buildPrograms(f, in, settings); !s) return s;
    warmUp(f, in);
    if (options.composite && !f.level1Pass && f.deferTraversal == base.deferTraversal)
      if (Status s = warmUpComposite(options); !s) return s;
  }
  for (bool overFallback : {false, true})
    if (auto p = compositeProgram(overFallback); !p) return p.status();
  gl.Finish();  // the driver's compiles happen here, not in the host's first frame
  return {};
}

// One frame of plan `f` on the host's inputs, its outputs discarded (prepare).
void Context::Impl::warmUp(FramePlan& f, const FrameInputs& in) {
  recordFrame(f, in, "sslr.prepare");
  temporal.valid = false;
}

// The frame's passes in order, under the state guard and a debug group of that name.
void Context::Impl::recordFrame(FramePlan& f, const FrameInputs& in, const char* debugGroup) {
  createFrameResources(f);
  detail::StateGuard guard(gl, false, views > 1);
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
  f.feedback = adaptiveWithTraversal && traversalPass == TraversalPass::Auto && softwareRenderer;
  if (f.pyramid) readFeedback();
  // This frame's counts go to the feedback buffer unless an earlier frame's are still unread there.
  f.feedbackWritten = f.pyramid && feedback.fence == nullptr;
  // After a frame that listed no tile, classification does not write level 1: a pass of its own
  // does, dispatched only if this frame lists one (an empty frame's classification then reads the
  // G-buffer and nothing more).
  f.level1Pass = f.pyramid && feedback.lastFrameListedNoTile;
  f.deferTraversal = adaptiveWithTraversal && (traversalPass == TraversalPass::Deferred ||
                                               (f.feedback && !feedback.traversalInline));
  // Inline under Auto: the trace (at half resolution the quad pass) counts the pixels (quads) that
  // needed the traversal, as deferred would have listed them.
  f.countTraversal = f.feedback && !f.deferTraversal;
  f.countQuads = f.feedback && settings.halfResolution;
  f.retracePass = settings.halfResolution || f.deferTraversal;
  f.quadRetracePass = settings.halfResolution && f.deferTraversal;
  f.blur = settings.blur.maxRadiusPx > 0.0f;
  f.stochasticFilter = settings.glossy.mode == GlossyMode::Stochastic && f.blur && f.temporal;
  f.wideClassify = !softwareRenderer;
  // History of the previous frame only if it stored one (else its keys may be older: cleared).
  f.useHistory = settings.temporal.enabled && hadHistory;
  return f;
}

// What FrameStats' traffic model needs of this frame: the input formats, which passes and paths
// the plan runs and the pyramid's cell counts.
TrafficModel Context::Impl::trafficModel(const FramePlan& f, TrafficModel formats, const Settings& settings) const {
  TrafficModel m = formats;
  // Every view's pixels: N views are counted as one frame N times as high.
  m.width = area.rect.width;
  m.height = area.rect.height * views;
  m.pyramid = f.pyramid;
  m.classifyLevels01 = f.pyramid && !f.level1Pass;
  m.levels01Pass = f.level1Pass;
  if (f.curvedSolids) m.normalGathers = f.frame.surface.normalEncoding == SSLR_NORMALS_OCTAHEDRAL ? 2 : 3;
  auto cells = [&](int level) {
    const std::uint64_t side = std::uint64_t(1) << level;
    return ((std::uint64_t(area.rect.width) + side - 1) / side) * ((std::uint64_t(area.rect.height) + side - 1) / side);
  };
  m.level1Cells = f.pyramid ? cells(1) * views : 0;
  for (int level = 2; f.pyramid && level <= area.levels; ++level) m.upperCells += cells(level) * views;
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
  m.stochasticFilter = f.stochasticFilter;
  m.blurTaps = f.blur ? static_cast<int>(std::ceil(std::min(settings.blur.maxRadiusPx, 32.0f))) : 0;
  return m;
}

// Every program the plan runs, built (or found in the cache) before any state is touched. The
// optional inputs, the normal encoding, the material channels and the tracer's role are compiled
// in or out rather than branched on: a CPU rasterizer runs an untaken branch under a lane mask.
Status Context::Impl::buildPrograms(FramePlan& f, const FrameInputs& in, const Settings& settings) {
  const shared::SslrSurface& surface = f.frame.surface;
  inputDefines = (views > 1 ? "#define SSLR_VIEWS " + std::to_string(views) + "\n" : std::string()) +
                 std::string(in.maskTexture != 0 ? "#define SSLR_HAS_MASK 1\n" : "") +
                 "#define SSLR_BACK_DEPTH " + (in.backDepthTexture != 0 ? "1\n" : "0\n") +
                 (in.materialTexture != 0 ? "#define SSLR_SEPARATE_MATERIAL 1\n" : "") +
                 (in.baseColorTexture != 0 ? "#define SSLR_COLORED_F0 1\n" : "") +
                 "#define SSLR_NORMAL_ENCODING " + std::to_string(surface.normalEncoding) + "\n" +
                 "#define SSLR_WORLD_NORMALS " + (surface.normalFromStored0.w != 0.0f ? "1" : "0") + "\n" +
                 "#define SSLR_NORMAL_UNSIGNED " + (shared::sslrUnsignedNormalUnpack(surface) ? "1" : "0") + "\n" +
                 "#define SSLR_ROUGHNESS_CHANNEL " + std::to_string(surface.roughnessChannel) + "\n" +
                 "#define SSLR_REFLECTANCE_CHANNEL " + std::to_string(surface.reflectanceChannel) + "\n";
  inputDefines += projectionDefines(f.frame, f.otherViews);
  std::string methodDefines = "#define SSLR_HIZ_MODE " + std::to_string(f.frame.trace.hizMode) + "\n";
  const std::string curvedDefine = std::string("#define SSLR_CURVED_SOLIDS ") + (f.curvedSolids ? "1\n" : "0\n");
  methodDefines += curvedDefine;
  if (oneBodyTraversal) methodDefines += "#define SSLR_HIZ_ONE_BODY 1\n";
  if (occupancyExit)
    methodDefines += "#extension GL_ARB_shader_ballot : require\n#extension GL_ARB_gpu_shader_int64 : require\n"
                     "#define SSLR_HIZ_OCCUPANCY_EXIT 1\n";
  if (settings.method == Method::PositionBuffer) methodDefines += "#define SSLR_METHOD_POSITION_BUFFER 1\n";
  if (settings.method == Method::ScreenSpaceDDA) methodDefines += "#define SSLR_METHOD_DDA 1\n";
  if (settings.method == Method::FidelityFxSssr) methodDefines += "#define SSLR_METHOD_FFX 1\n";
  const std::string statsDefine = settings.debug.collectStats ? "#define SSLR_COLLECT_STATS 1\n" : "";
  std::string traceDefines = methodDefines + statsDefine;
  if (settings.debug.outputs) traceDefines += "#define SSLR_DEBUG_OUTPUTS 1\n";
  if (settings.temporal.enabled) traceDefines += "#define SSLR_TEMPORAL_HITS 1\n";
  if (settings.hitDistance) traceDefines += "#define SSLR_HIT_DISTANCE 1\n";
  if (settings.glossy.mode == GlossyMode::Stochastic) traceDefines += "#define SSLR_STOCHASTIC 1\n";
  const std::string stochasticFilter = f.stochasticFilter ? "#define SSLR_STOCHASTIC_FILTER 1\n" : "";
  traceDefines += stochasticFilter;
  // Under TraversalPass::Auto the tiles' whole tracer is compiled with the retrace role, so that an
  // inline frame's trace and a deferred frame's retrace are one program. The full-resolution trace
  // (at half resolution the shading from the quads' rays), and half resolution's quad rays, whose
  // retrace never takes SSLR_QUADS_WIDE (a group per tile's listed quads).
  const TraceRoleDefines pixels = traceRoleDefines(traceDefines, f.feedback && !settings.halfResolution);
  const TraceRoleDefines quads = traceRoleDefines(methodDefines + statsDefine, f.countQuads);
  f.programs.trace.retraceRole = !settings.halfResolution && !f.deferTraversal && f.feedback;
  f.programs.trace.quadRetraceRole = settings.halfResolution && !f.deferTraversal && f.feedback && !f.wideClassify;
  const char* traceEntry = settings.halfResolution ? "3_shade_from_quads.comp" : "3_trace.comp";
  if (!settings.halfResolution)
    traceDefines = f.deferTraversal ? pixels.firstStage : f.programs.trace.retraceRole ? pixels.retrace : pixels.whole;
  const std::string quadsDefines =
      (f.deferTraversal ? quads.firstStage : f.programs.trace.quadRetraceRole ? quads.retrace : quads.whole) +
      (f.wideClassify ? "#define SSLR_QUADS_WIDE 1\n" : "");
  // With the pyramid, classification (which reads every depth anyway) writes its levels 0 and 1,
  // unless the last frame listed no tile (then the levels-0-and-1 pass does, if this frame lists
  // one). Under DeviceProfile::Gpu it also does the clean-up's and the pyramid arguments' work.
  std::string classifyDefines = f.pyramid && !f.level1Pass ? "#define SSLR_CLASSIFY_LEVEL1 1\n" + curvedDefine : "";
  if (f.wideClassify && f.pyramid) classifyDefines += "#define SSLR_CLASSIFY_ARGS 1\n";
  const std::pair<GLuint*, Expected<GLuint>> built[] = {
      {&f.programs.classify.classify, computeProgram(f.wideClassify ? "1_classify_wide.comp" : "1_classify.comp", classifyDefines)},
      {&f.programs.classify.cleanup, optionalProgram(!f.wideClassify, "1_clear_untraced.comp", "")},
      {&f.programs.pyramid.arguments, optionalProgram(f.pyramid && !f.wideClassify, "2_pyramid_arguments.comp", curvedDefine)},
      {&f.programs.pyramid.level1, optionalProgram(f.level1Pass, "2_pyramid_levels01.comp", curvedDefine)},
      {&f.programs.pyramid.curved, optionalProgram(f.curvedSolids, "2_pyramid_curved.comp", curvedDefine)},
      {&f.programs.pyramid.block, optionalProgram(f.pyramid, "2_pyramid_levels2to7.comp", "")},
      {&f.programs.pyramid.single, optionalProgram(f.pyramid && area.levels > kHizBlockTop, "2_pyramid_top_level.comp", "")},
      {&f.programs.trace.trace, computeProgram(traceEntry, traceDefines)},
      {&f.programs.trace.quads, optionalProgram(settings.halfResolution, "3_trace_quads.comp", quadsDefines)},
      {&f.programs.trace.quadRetrace, optionalProgram(f.quadRetracePass, "3_trace_quads.comp", quads.retrace)},
      {&f.programs.trace.retrace, optionalProgram(f.retracePass, "3_trace.comp", pixels.retrace)},
      {&f.programs.blur.horizontal, optionalProgram(f.blur, "4_blur.comp", "#define SSLR_BLUR_AXIS ivec2(1, 0)\n")},
      {&f.programs.blur.vertical, optionalProgram(f.blur, "4_blur.comp", "#define SSLR_BLUR_AXIS ivec2(0, 1)\n#define SSLR_BLUR_VERTICAL 1\n")},
      {&f.programs.temporal.blend,
       optionalProgram(settings.temporal.enabled, "5_temporal_blend.comp",
                       (f.historyConfidence ? "#define SSLR_HISTORY_CONFIDENCE 1\n" : "") + stochasticFilter)},
      {&f.programs.temporal.store, optionalProgram(settings.temporal.enabled, "5_temporal_store.comp", "")},
      {&f.programs.temporal.cleanup, optionalProgram(settings.temporal.enabled, "5_clear_untraced_history.comp", "")}};
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
  if (f.pyramid && feedback.buffer == 0) {
    gl.CreateBuffers(1, &feedback.buffer);
    gl.NamedBufferStorage(feedback.buffer, 4 * sizeof(GLuint), nullptr, 0);
    label(GL_BUFFER, feedback.buffer, "sslr.feedback");
  }
  createPyramidResources(f);
  createTraceResources(f);
  createTemporalResources(f);
}

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

// The frame's constants, the tile list's header, the debug images and the stats slot.
void Context::Impl::beginFrame(FramePlan& f) {
  const float zero[4] = {0, 0, 0, 0};
  if (f.temporal && !f.useHistory) clearTexImage(temporal.key, GL_RED, GL_FLOAT, zero);
  frameIndex = frameIndex == 0x7fffffff ? 1 : frameIndex + 1;
  f.frame.temporal.history = f.useHistory ? 1 : 0;
  f.frame.trace.frameIndex = frameIndex;
  // Temporal reuse without a history (the first frame, a reset, a new viewport): one lobe sample
  // a pixel would be all it shows, so every pixel traces its mirror ray and the cone blur smooths
  // it; the frames after it draw from the lobe and accumulate (docs/results/glossy.md, "0.10.1").
  if (f.temporal && !f.useHistory) f.frame.trace.stochasticFrom = SSLR_NO_STOCHASTIC_RAYS;
  bufferSubData(frameUbo, 0, sizeof(f.frame), &f.frame);
  for (size_t v = 0; v < f.otherViews.size(); ++v) {  // views 1.. (ContextDesc::views)
    f.otherViews[v].temporal.history = f.frame.temporal.history;
    f.otherViews[v].trace.frameIndex = frameIndex;
    f.otherViews[v].trace.stochasticFrom = f.frame.trace.stochasticFrom;
    bufferSubData(frameUbo, static_cast<GLintptr>((v + 1) * sizeof(shared::SslrFrame)), sizeof(shared::SslrFrame),
                  &f.otherViews[v]);
  }
  writeTileHeader();
  if (area.changed) startNewArea();
  // reflection and resolved are not cleared: the clean-up pass (1_clear_untraced.comp)
  // zeroes the tiles the previous frame traced and this one does not. The debug images are
  // cleared whole (debug only).
  if (f.debugOutputs) {
    clearTexImage(trace.hit, GL_RGBA, GL_FLOAT, zero);
    clearTexImage(trace.iterations, GL_RED, GL_FLOAT, zero);
  }
  // The hit distance is cleared whole too (0: no hit), so that tiles not traced read 0.
  if (f.hitDistance) clearTexImage(trace.hitDistance, GL_RED, GL_FLOAT, zero);
  if (f.historyConfidence) clearTexImage(temporal.confidence, GL_RED, GL_FLOAT, zero);
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
  const GLsizeiptr capacity = static_cast<GLsizeiptr>(area.tilesX) * area.tilesY * views;  // every view's tiles
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
    real[2] = static_cast<GLuint>(views);  // (z: one a view)
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
    gl.ClearTexSubImage(t, 0, lastRect.x, lastRect.y, 0, lastRect.width, lastRect.height, views, GL_RGBA, GL_FLOAT, zero);
    ++recording[recordingPass].uploads;
  }
  const GLuint zeroWord = 0;
  const GLsizeiptr arrays = static_cast<GLsizeiptr>(kTileArrays) * tilesX() * tilesY() * views;  // (allocated for the context)
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

// The end of a frame: every write made visible to the host, the feedback and the stats copied on
// the GPU (no read-back) and fenced.
void Context::Impl::finishFrame(const FramePlan& f) {
  beginPass(f, 5);
  memoryBarrier(GL_ALL_BARRIER_BITS);
  if (f.feedbackWritten) {  // (listed tiles, -, -, pixels or quads that needed the traversal)
    copyBufferSubData(tileBuffer, feedback.buffer, 0, 0, sizeof(GLuint));
    if (f.feedback && !f.halfResolution)  // (half resolution copied its quads' count in runQuads)
      copyBufferSubData(trace.retraceList, feedback.buffer, 3 * sizeof(GLuint), 3 * sizeof(GLuint), sizeof(GLuint));
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
