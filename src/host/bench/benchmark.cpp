// The benchmark's runner: per scene the Embree truth, each configuration's quality pass and the
// interleaved timing, then the cost curves and studies; and the summaries the report reads. The grid
// is in bench_grid.cpp, the report in bench_report.cpp.
#include "sslr_host/benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "bench_contexts.hpp"
#include "bench_timer.hpp"
#include "glossy_study.hpp"
#include "sslr_host/cost_model.hpp"
#include "temporal_study.hpp"
#include "views_study.hpp"
#include "sslr_host/embedded_shaders.hpp"
#include "sslr_host/cpu_tracer.hpp"
#include "sslr_host/egl_context.hpp"
#include "sslr_host/frame_renderer.hpp"
#include "sslr_host/reference_image.hpp"

namespace sslr::host {

namespace fs = std::filesystem;

namespace {

// The "physical limit" pass: reads depth, normal and colour once, writes one RGBA16F texel.
class BaselinePass {
 public:
  explicit BaselinePass(int w, int h) : w_(w), h_(h) {
    auto program = linkHostProgram({{GL_COMPUTE_SHADER, "host/baseline.comp"}});
    if (!program) std::fprintf(stderr, "sslr-bench: the baseline pass is unavailable: %s\n", program.error().c_str());
    program_ = program ? program.value() : 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &out_);
    glTextureStorage2D(out_, 1, GL_RGBA16F, w, h);
    glCreateSamplers(1, &sampler_);
    glSamplerParameteri(sampler_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(sampler_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  ~BaselinePass() {
    glDeleteProgram(program_);
    glDeleteTextures(1, &out_);
    glDeleteSamplers(1, &sampler_);
  }
  void run(const FrameInputs& in) {
    glUseProgram(program_);
    const GLuint textures[3] = {in.depthTexture, in.normalTexture, in.colorTexture};
    for (GLuint u = 0; u < 3; ++u) {
      glBindTextureUnit(u, textures[u]);
      glBindSampler(u, sampler_);
    }
    glBindImageTexture(0, out_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(static_cast<GLuint>((w_ + 7) / 8), static_cast<GLuint>((h_ + 7) / 8), 1);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    for (GLuint u = 0; u < 3; ++u) glBindSampler(u, 0);
    glUseProgram(0);
  }

 private:
  int w_, h_;
  GLuint program_ = 0, out_ = 0, sampler_ = 0;
};

// Image strips: the truth (colour at the true hit, classes tinted), each default method's
// reflection (colour at its reported hit) and its error heatmap; `colorOf` paints one pixel.
template <typename ColorOf>
Image paintImage(const GroundTruth& gt, ColorOf colorOf) {
  Image img{gt.width, gt.height, 3, std::vector<float>(static_cast<size_t>(gt.width) * gt.height * 3, 0.0f)};
  for (int y = 0; y < gt.height; ++y)
    for (int x = 0; x < gt.width; ++x) {
      const glm::vec3 c = colorOf(x, y, gt.pixels[static_cast<size_t>(y) * gt.width + x]);
      for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[k];
    }
  return img;
}

Image truthImage(const GroundTruth& gt, const Image& color) {
  return paintImage(gt, [&](int, int, const TruthPixel& t) -> glm::vec3 {
    switch (t.cls) {
      case TruthClass::Visible: return sampleBilinear(color, t.uvHit);
      case TruthClass::Occluded: return {0.25f, 0.02f, 0.02f};
      case TruthClass::OffScreen: return {0.02f, 0.02f, 0.25f};
      case TruthClass::Escaped: return {0.06f, 0.06f, 0.06f};
      case TruthClass::NotReflective: break;
    }
    return glm::vec3(0.0f);
  });
}

Image methodImage(const GroundTruth& gt, const Image& hit, const Image& color) {
  return paintImage(gt, [&](int x, int y, const TruthPixel& t) -> glm::vec3 {
    if (t.cls == TruthClass::NotReflective || !(hit.at(x, y, 2) > kReportedConfidence)) return glm::vec3(0.0f);
    return sampleBilinear(color, {hit.at(x, y, 0), hit.at(x, y, 1)});
  });
}

}  // namespace

namespace {

// The configurations the cost curves time: each method's default.
std::vector<BenchConfig> defaultConfigs(const std::vector<BenchConfig>& grid) {
  std::vector<BenchConfig> out;
  for (const BenchConfig& c : grid)
    if (c.isDefault) out.push_back(c);
  return out;
}

// A scene's G-buffer, rendered once: what every timed configuration reads.
struct SceneFrame {
  Scene scene;
  std::unique_ptr<FrameRenderer> renderer;
  FrameInputs inputs;             // without the back-face depth
  GLuint backDepthTexture = 0;    // the back-face depth (inputsFor)
};
Expected<SceneFrame> renderSceneFrame(const std::string& sceneName, int width, int height, bool withBackDepth) {
  auto scene = loadScene(sceneName);
  if (!scene) return Status::error(scene.error());
  GBufferOptions g;
  g.width = width;
  g.height = height;
  g.withPosition = true;  // the position-buffer method needs it; the depth-only ones ignore it
  g.withBackDepth = withBackDepth;  // for the configurations that measure thickness (BenchConfig::backDepth)
  auto renderer = FrameRenderer::create(g);
  if (!renderer) return Status::error(renderer.error());
  SceneFrame f{std::move(scene.value()), std::move(renderer.value()), {}, 0};
  GpuScene gpu(f.scene);
  const Camera camera = f.scene.camera ? *f.scene.camera : f.scene.defaultCamera();
  if (Status st = f.renderer->render(gpu, camera, nullptr); !st) return Status::error(st.message());
  f.inputs = f.renderer->gbuffer().frameInputs();
  f.backDepthTexture = f.inputs.backDepthTexture;
  f.inputs.backDepthTexture = 0;  // only the configurations that measure thickness get it
  return f;
}

FrameInputs inputsFor(const SceneFrame& f, const BenchConfig& c) {
  FrameInputs in = f.inputs;
  if (c.backDepth) in.backDepthTexture = f.backDepthTexture;
  return in;
}

// Times every configuration (method "baseline": the baseline pass) once per round, rounds
// interleaved (A B C A B C ...) so that all see the same machine state, each through its own
// context (ConfigContexts); the first `warmup` rounds are dropped. Returns the kept times per
// configuration; `afterEach` is called after each timing.
Expected<std::vector<std::vector<double>>> timeInterleaved(const std::vector<BenchConfig>& configs, SceneFrame& f,
                                                           ConfigContexts& contexts, const BenchOptions& options,
                                                           Timer& timer,
                                                           const std::function<void(int round)>& afterEach) {
  BaselinePass baseline(f.renderer->gbuffer().width(), f.renderer->gbuffer().height());
  // One untimed frame each first: its programs are built (also with --warmup 0) and its state is
  // this scene's.
  for (size_t i = 0; i < configs.size(); ++i) {
    if (configs[i].method == "baseline") continue;
    auto ctx = contexts.get(i, configs[i].shapes());
    if (!ctx) return Status::error(ctx.error());
    if (Status st = ctx.value()->dispatch(inputsFor(f, configs[i]), configs[i].settings); !st)
      return Status::error(st.message());
  }
  std::vector<std::vector<double>> times(configs.size());
  for (int round = 0; round < options.warmup + options.frames; ++round)
    for (size_t i = 0; i < configs.size(); ++i) {
      Status st;
      double ms = 0.0;
      if (configs[i].method == "baseline") {
        ms = timer.timeMs([&] { baseline.run(f.inputs); }, timer.repeats(options.batch));
      } else {
        auto ctx = contexts.get(i, configs[i].shapes());
        if (!ctx) return Status::error(ctx.error());
        const FrameInputs in = inputsFor(f, configs[i]);
        ms = timer.timeMs([&] { if (st) st = ctx.value()->dispatch(in, configs[i].settings); },
                          timer.repeats(options.batch));
      }
      if (!st) return Status::error(st.message());
      if (round >= options.warmup) times[i].push_back(ms);
      if (afterEach) afterEach(round);
    }
  return times;
}

// Times the defaults and the baseline on one scene at one size, interleaved; appends the points.
Status timeCurvePoint(const std::string& curve, const std::string& sceneName, int width, int height, int percent,
                      const std::vector<BenchConfig>& grid, const BenchOptions& options, Timer& timer,
                      std::vector<CurvePoint>& out) {
  auto frame = renderSceneFrame(sceneName, width, height, false);  // the defaults measure no thickness
  if (!frame) return Status::error(frame.error());
  SceneFrame& f = frame.value();
  std::vector<BenchConfig> configs = defaultConfigs(grid);
  if (configs.empty()) return {};  // --configs chose no method's default
  for (const BenchConfig& c : grid)
    if (c.method == "baseline") configs.push_back(c);
  // What the frame reflects, from the default's own count.
  Settings counting = configs.front().settings;
  counting.debug.collectStats = true;
  if (Status st = f.renderer->sslr().dispatch(f.inputs, counting); !st) return st;
  const double traced = double(f.renderer->sslr().waitForStats().tracedPixels) / (double(width) * height);
  ConfigContexts contexts(width, height);
  auto times = timeInterleaved(configs, f, contexts, options, timer, nullptr);
  if (!times) return Status::error(times.error());
  for (size_t i = 0; i < configs.size(); ++i) {
    CurvePoint p;
    p.curve = curve;
    p.method = configs[i].method;
    p.width = width;
    p.height = height;
    p.percent = percent;
    p.tracedFraction = traced;
    p.timeMedianMs = median(times.value()[i]);
    out.push_back(p);
  }
  return {};
}

}  // namespace

namespace {

// A scene's record: its reflective pixels by truth class.
SceneRecord sceneRecordOf(const std::string& sceneName, const GroundTruth& gt) {
  SceneRecord sr;
  sr.scene = sceneName;
  sr.reflective = gt.reflective();
  sr.visible = gt.count(TruthClass::Visible);
  sr.occluded = gt.count(TruthClass::Occluded);
  sr.offScreen = gt.count(TruthClass::OffScreen);
  sr.escaped = gt.count(TruthClass::Escaped);
  return sr;
}

// The two representations alone: the position rebuilt from depth against the stored one, and one
// tracer (adaptive L's CPU run) on both.
void measureRepresentations(SceneRecord& sr, const GroundTruth& gt, const SceneFrame& sf, const Image& depth,
                            const Image& normal, const Image& positions, const BenchOptions& options) {
  const FrameInputs& inputs = sf.inputs;
  const GBuffer& gb = sf.renderer->gbuffer();
  const Settings defaults;
  const Image rebuilt = reconstructPositions(depth, gb.clipFromView(), inputs.depth);
  std::vector<double> errs;
  for (size_t p = 0; p < gt.pixels.size(); ++p) {
    if (positions.pixels[p * 4 + 3] == 0.0f || rebuilt.pixels[p * 4 + 3] == 0.0f) continue;
    const glm::vec3 a(rebuilt.pixels[p * 4], rebuilt.pixels[p * 4 + 1], rebuilt.pixels[p * 4 + 2]);
    const glm::vec3 b(positions.pixels[p * 4], positions.pixels[p * 4 + 1], positions.pixels[p * 4 + 2]);
    const double e = glm::length(a - b);
    errs.push_back(e);
    sr.positionErrorMaxRelative = std::max(sr.positionErrorMaxRelative, e / std::max(1e-6, double(glm::length(b))));
  }
  if (!errs.empty()) {
    sr.positionErrorMax = *std::max_element(errs.begin(), errs.end());
    sr.positionErrorMedian = median(errs);
  }
  const CpuGBuffer cg{&depth, &normal, &positions};
  const Image hitDepth = traceOnCpu(cg, inputs, defaults, SurfaceSource::Depth);
  const Image hitStored = traceOnCpu(cg, inputs, defaults, SurfaceSource::StoredPositions);
  size_t traced = 0, agree = 0;
  for (size_t p = 0; p < gt.pixels.size(); ++p) {
    if (gt.pixels[p].cls == TruthClass::NotReflective) continue;
    ++traced;
    const bool a = hitDepth.pixels[p * 4 + 2] > kReportedConfidence,
               b = hitStored.pixels[p * 4 + 2] > kReportedConfidence;
    const float du = (hitDepth.pixels[p * 4] - hitStored.pixels[p * 4]) * options.width;
    const float dv = (hitDepth.pixels[p * 4 + 1] - hitStored.pixels[p * 4 + 1]) * options.height;
    agree += a == b && (!a || std::hypot(du, dv) <= 1.0f);
  }
  sr.hitAgreement = traced ? double(agree) / traced : 1.0;
  sr.recallDepth = compareHits(gt, hitDepth).recall1px;
  sr.recallStored = compareHits(gt, hitStored).recall1px;
}

// One configuration's untimed quality pass on a scene: hits scored against the truth, the frame's
// stats, and for a method's default its image and error map in the report.
Expected<RunRecord> qualityRun(const BenchConfig& c, size_t i, const std::string& sceneName, SceneFrame& sf,
                               const GroundTruth& gt, const ReferenceImage& reference, const Image& color,
                               ConfigContexts& contexts,
                               const BenchOptions& options, const std::string& renderer,
                               const std::string& timingMethod, const std::string& reportDir, SceneRecord& sr) {
  FrameRenderer& fr = *sf.renderer;
  GBuffer& gb = fr.gbuffer();
  const std::string prefix = fileSlug(sceneName);
  RunRecord r;
  r.scene = sceneName;
  r.method = c.method;
  r.label = c.label;
  r.config = c;
  r.width = options.width;
  r.height = options.height;
  r.renderer = renderer;
  r.timingMethod = timingMethod;
  r.extraBytesPerPixel = c.method == "baseline" ? 8 : 24;  // 3 x RGBA16F
  r.gbufferBytesPerPixel = gb.bytesPerPixel() + (c.method == "position-buffer" ? 16 : 0);
  if (c.method != "baseline") {
    Settings s = c.settings;
    s.debug.outputs = true;
    s.debug.collectStats = true;
    // The scene's renderer's context, unless the config asks for pass shapes of its own (then
    // its timing context: the commands counted are those shapes').
    Context* ctx = &fr.sslr();
    if (c.ownShapes()) {
      auto own = contexts.get(i, c.shapes());
      if (!own) return Status::error(own.error());
      ctx = own.value();
    }
    if (Status st = ctx->dispatch(inputsFor(sf, c), s); !st) return Status::error(st.message());
    const Image hit = readTexture(ctx->hitTexture(), options.width, options.height, 4);
    r.metrics = compareHits(gt, hit, kReportedConfidence, &color);
    if (Status st = fr.compositeFrom(*ctx); !st) return Status::error(st.message());
    const Image final = fr.readFinal();
    const ImageError composite = compositeError(reference, final);
    r.compositeRmse = composite.rmse;
    r.compositePsnr = composite.psnr;
    r.compositeBreakdown = compositeBreakdown(reference, final, gt, hit, color);  // a miss shows the colour
    const FrameStats stats = ctx->waitForStats();
    r.tracedPixels = stats.tracedPixels;
    r.fetches = stats.fetches;
    r.commands = stats.totalCommands();
    r.traffic = stats.totalTraffic();
    r.frameStats = stats;
    r.fetchesPerTracedPixel = stats.tracedPixels ? double(stats.fetches) / stats.tracedPixels : 0.0;
    r.predictedH100Ms =
        predictedH100FrameMs(frameShapeOf(c.settings, ctx->device(), c.shapes(), stats), stats.totalRayWork()).value_or(NAN);
    r.nonFiniteOutputs = countNonFinite(readTexture(ctx->reflectionTexture(), options.width, options.height, 4)) +
                         countNonFinite(readTexture(ctx->resolvedTexture(), options.width, options.height, 4));
    if (c.isDefault) {
      const std::string m = prefix + "-" + fileSlug(c.method);
      if (Status st = writeImage((fs::path(reportDir) / (m + ".png")).string(), methodImage(gt, hit, color)); !st)
        return Status::error(st.message());
      if (Status st = writeImage((fs::path(reportDir) / (m + "-error.png")).string(), hitErrorImage(gt, hit)); !st)
        return Status::error(st.message());
      sr.images.push_back(m + ".png");
      sr.images.push_back(m + "-error.png");
    }
  }
  return r;
}

// The studies after the scenes: cost curves, temporal reuse, several views, glossy reflections.
Status runStudies(const BenchOptions& options, const std::vector<BenchConfig>& grid, Timer& timer,
                  const std::string& reportDir, BenchResult& result, int done, int total,
                  const std::function<void(int, int, const std::string&)>& progress) {
  // Cost curves: time against resolution (mirror-room) and against reflective fraction.
  for (const auto& [w, h] : options.curveSizes) {
    progress(done, total, "cost curve: " + std::to_string(w) + "x" + std::to_string(h));
    if (Status s = timeCurvePoint("resolution", "mirror-room", w, h, -1, grid, options, timer, result.curves); !s)
      return s;
  }
  for (int percent : options.curveFractions) {
    progress(done, total, "cost curve: reflective-" + std::to_string(percent));
    if (Status s = timeCurvePoint("fraction", "reflective-" + std::to_string(percent), options.width, options.height,
                                  percent, grid, options, timer, result.curves);
        !s)
      return s;
  }
  for (const std::string& sceneName : options.temporalScenes) {
    progress(done, total, "temporal study: " + sceneName);
    if (Status s = runTemporalStudy(sceneName, options, timer, result.temporal); !s)
      return Status::error("temporal study on " + sceneName + ": " + s.message());
  }
  for (const std::string& sceneName : options.viewsScenes) {
    progress(done, total, "views study: " + sceneName);
    if (Status s = runViewsStudy(sceneName, options, timer, result.views); !s)
      return Status::error("views study on " + sceneName + ": " + s.message());
  }
  for (const std::string& sceneSpec : options.glossyScenes) {
    progress(done, total, "glossy study: " + sceneSpec);
    if (Status s = runGlossyStudy(sceneSpec, options, timer, reportDir, result.glossy); !s)
      return Status::error("glossy study on " + sceneSpec + ": " + s.message());
  }
  return Status{};
}

}  // namespace

namespace {

// The grid's configurations that --configs selects, each in the pass shapes --device-profile gives
// where it names none of its own.
Expected<std::vector<BenchConfig>> configsToRun(const BenchOptions& options) {
  auto selected = selectConfigs(benchGrid(options.grid), options.configs);
  if (!selected) return Status::error(selected.error());
  for (BenchConfig& c : selected.value())
    if (c.device == DeviceProfile::Auto) c.device = options.device;
  // ContextDesc::occupancyExit needs subgroup ballots: where the driver has none, its
  // configurations are left out (said on stderr) rather than failing the run.
  std::vector<BenchConfig>& v = selected.value();
  if (std::any_of(v.begin(), v.end(), [](const BenchConfig& c) { return c.occupancyExit; })) {
    ContextDesc probe;
    probe.width = probe.height = 8;
    probe.getProcAddress = HeadlessContext::getProcAddress();
    probe.occupancyExit = true;
    if (auto ctx = Context::create(probe); !ctx) {
      std::fprintf(stderr, "sslr-bench: leaving out the occupancy exit's configurations: %s\n", ctx.error().c_str());
      v.erase(std::remove_if(v.begin(), v.end(), [](const BenchConfig& c) { return c.occupancyExit; }), v.end());
    }
  }
  return selected;
}

}  // namespace

Expected<BenchResult> runBenchmark(const BenchOptions& options, bool software, const std::string& renderer,
                                   const std::string& reportDir,
                                   const std::function<void(int, int, const std::string&)>& progress) {
  BenchResult result;
  result.options = options;
  result.renderer = renderer;
  std::vector<std::string> scenes = options.scenes;
  if (scenes.empty())
    scenes = defaultBenchScenes();
  auto selected = configsToRun(options);
  if (!selected) return Status::error(selected.error());
  const std::vector<BenchConfig>& grid = selected.value();
  // The back-face depth pass only when a configuration reads it.
  const bool anyBackDepth = std::any_of(grid.begin(), grid.end(), [](const BenchConfig& c) { return c.backDepth; });
  Timer timer(software);
  const int repeats = timer.repeats(options.batch);
  result.timingMethod = timer.method() + (repeats > 1 ? ", mean of " + std::to_string(repeats) + " dispatches back to back" : "");
  std::error_code ec;
  fs::create_directories(reportDir, ec);
  if (ec) return Status::error("cannot create " + reportDir + ": " + ec.message());

  const int total = static_cast<int>(scenes.size() * (grid.size() * (1 + options.frames + options.warmup) + 1));
  int done = 0;
  // The grid's contexts serve every scene (one size): each scene's untimed first frames absorb
  // the state the previous scene left.
  ConfigContexts contexts(options.width, options.height);
  for (const std::string& sceneName : scenes) {
    auto frame = renderSceneFrame(sceneName, options.width, options.height, anyBackDepth);
    if (!frame) return Status::error(frame.error());
    SceneFrame& sf = frame.value();
    FrameRenderer& fr = *sf.renderer;
    GBuffer& gb = fr.gbuffer();
    const Image depth = gb.readDepth(), normal = gb.readNormalPacked(), positions = gb.readPosition(),
                color = gb.readColor();

    // Ground truth (Embree), once per scene, and what a perfect mirror tracer would composite.
    progress(done, total, sceneName + ": ground truth");
    auto tracer = RayTracer::create(sf.scene, gb.viewFromWorld());
    if (!tracer) return Status::error(tracer.error());
    const GroundTruth gt = groundTruthFor(*tracer.value(), gb, Settings{});
    const ReferenceImage reference = referenceComposite(sf.scene, *tracer.value(), gb, gt);

    SceneRecord sr = sceneRecordOf(sceneName, gt);
    sr.showsNothing = gb.showsNothing(depth);
    measureRepresentations(sr, gt, sf, depth, normal, positions, options);
    const std::string prefix = fileSlug(sceneName);
    if (Status s = writeImage((fs::path(reportDir) / (prefix + "-truth.png")).string(), truthImage(gt, color)); !s)
      return Status::error(s.message());
    sr.images.push_back(prefix + "-truth.png");

    // Quality pass per config (debug outputs + stats, untimed).
    std::vector<RunRecord> runs;
    for (size_t i = 0; i < grid.size(); ++i) {
      const BenchConfig& c = grid[i];
      auto r = qualityRun(c, i, sceneName, sf, gt, reference, color, contexts, options, renderer,
                          result.timingMethod, reportDir, sr);
      if (!r) return Status::error(r.error());
      runs.push_back(r.value());
      progress(++done, total, sceneName + ": quality " + c.method + " " + c.label);
    }
    // Timing, interleaved (timeInterleaved).
    auto timed = timeInterleaved(grid, sf, contexts, options, timer, [&](int round) {
      progress(++done, total, sceneName + ": timing round " + std::to_string(round + 1));
    });
    if (!timed) return Status::error(timed.error());
    const std::vector<std::vector<double>>& times = timed.value();
    for (size_t i = 0; i < grid.size(); ++i) {
      runs[i].frames = static_cast<int>(times[i].size());
      runs[i].timeMedianMs = median(times[i]);
      runs[i].timeMinMs = times[i].empty() ? 0.0 : *std::min_element(times[i].begin(), times[i].end());
      runs[i].timeMaxMs = times[i].empty() ? 0.0 : *std::max_element(times[i].begin(), times[i].end());
    }
    result.runs.insert(result.runs.end(), runs.begin(), runs.end());
    result.scenes.push_back(sr);
  }
  if (Status s = runStudies(options, grid, timer, reportDir, result, done, total, progress); !s)
    return Status::error(s.message());
  return result;
}

std::vector<FastestRun> fastestReaching(const BenchResult& result, const std::string& scene, double minRecall) {
  std::vector<FastestRun> out;
  for (const RunRecord& r : result.runs) {
    if (r.scene != scene || r.method == "baseline") continue;
    auto it = std::find_if(out.begin(), out.end(), [&](const FastestRun& f) { return f.method == r.method; });
    if (it == out.end()) it = out.insert(out.end(), FastestRun{r.method, nullptr});
    const bool reaches = r.metrics.recall1px >= minRecall;
    if (reaches && (!it->run || r.timeMedianMs < it->run->timeMedianMs)) it->run = &r;
  }
  return out;
}

SceneDefaults defaultRuns(const BenchResult& result, const std::string& scene) {
  SceneDefaults d;
  for (const RunRecord& r : result.runs)
    if (r.scene == scene && r.config.isDefault) {
      d.runs.push_back(&r);
      if (r.method == "position-buffer") d.tutorial = &r;
    }
  return d;
}

}  // namespace sslr::host
