// The glossy study of sslr-bench: how far the roughness blur of the mirror reflection (the SSLR
// article's method, sslr's default) is from a physically based glossy reflection. Each scene's
// G-buffer is rendered once; Embree gathers the GGX lobe of every glossy pixel from what the
// screen shows (glossy_truth.hpp); each configuration runs in Radiance mode (no Fresnel term)
// and its rgb / a is scored against it.
#include "glossy_study.hpp"

#include <cstdlib>
#include <filesystem>
#include <memory>

#include "bench_contexts.hpp"
#include "sslr_host/frame_renderer.hpp"
#include "sslr_host/glossy_truth.hpp"

namespace sslr::host {

namespace fs = std::filesystem;

namespace {

struct GlossyConfig {
  const char* name;
  bool blur;
  float coneScale;  // x Settings' default
  GlossyMode mode;
  bool temporal;    // temporal reuse over the still frames before the score (BenchOptions::glossyFrames)
  bool clamp = false;  // Settings::radianceClamp at BenchOptions::glossyClampLuminance
};
constexpr GlossyConfig kConfigs[] = {{"cone blur", true, 1.0f, GlossyMode::ConeBlur, false},
                                     {"cone blur x0.5", true, 0.5f, GlossyMode::ConeBlur, false},
                                     {"cone blur x2", true, 2.0f, GlossyMode::ConeBlur, false},
                                     {"no blur", false, 1.0f, GlossyMode::ConeBlur, false},
                                     {"stochastic", true, 1.0f, GlossyMode::Stochastic, false},
                                     {"stochastic+temporal", true, 1.0f, GlossyMode::Stochastic, true},
                                     {"cone blur, clamp", true, 1.0f, GlossyMode::ConeBlur, false, true},
                                     {"stochastic, clamp", true, 1.0f, GlossyMode::Stochastic, false, true},
                                     {"stochastic+temporal, clamp", true, 1.0f, GlossyMode::Stochastic, true, true}};

}  // namespace

Expected<Scene> loadGlossyScene(const std::string& sceneSpec) {
  const size_t at = sceneSpec.find("@rough");
  auto scene = loadScene(sceneSpec.substr(0, at));
  if (!scene || at == std::string::npos) return scene;
  const std::string value = sceneSpec.substr(at + 6);
  char* end = nullptr;
  const float roughness = std::strtof(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size() || !(roughness > 0.0f && roughness <= 1.0f))
    return Status::error("glossy scene '" + sceneSpec + "': the roughness after @rough must be in (0, 1]");
  Scene s = std::move(scene.value());
  int changed = 0;
  for (Material& m : s.materials)
    if (m.roughness < 0.1f) {
      m.roughness = roughness;
      ++changed;
    }
  if (changed == 0) return Status::error("glossy scene '" + sceneSpec + "': it has no mirror (roughness below 0.1) to roughen");
  s.name = sceneSpec;
  return s;
}

Status runGlossyStudy(const std::string& sceneSpec, const BenchOptions& options, Timer& timer,
                      const std::string& reportDir, std::vector<GlossyPoint>& out) {
  auto scene = loadGlossyScene(sceneSpec);
  if (!scene) return Status::error(scene.error());
  const Camera camera = scene.value().camera ? *scene.value().camera : scene.value().defaultCamera();
  GpuScene gpu(scene.value());
  GBufferOptions g;
  g.width = options.glossyWidth;
  g.height = options.glossyHeight;
  auto renderer = FrameRenderer::create(g);
  if (!renderer) return Status::error(renderer.error());
  FrameRenderer& fr = *renderer.value();
  if (Status st = fr.render(gpu, camera, nullptr); !st) return st;  // the G-buffer and its matrices
  auto truth = glossyTruthFor(scene.value(), fr.gbuffer(), Settings{}, options.glossySamples);
  if (!truth) return Status::error(truth.error());
  const std::string prefix = fileSlug(sceneSpec) + "-glossy";
  if (Status s = writeImage((fs::path(reportDir) / (prefix + "-truth.png")).string(), glossyTruthImage(truth.value())); !s)
    return s;
  // Each configuration its own context. Scored first: exactly glossyFrames still frames (temporal
  // reuse accumulates over them), the error after each kept. Then timed in interleaved rounds,
  // whose frame count is the timer's (repeats per sample) and so changes no score.
  FrameInputs inputs = fr.inputs();
  inputs.previousClipFromView = inputs.clipFromView;
  const size_t n = std::size(kConfigs);
  ConfigContexts contexts(g.width, g.height);
  std::vector<Settings> settings;
  const size_t first = out.size();
  for (size_t i = 0; i < n; ++i) {
    const GlossyConfig& c = kConfigs[i];
    auto ctx = contexts.get(i);
    if (!ctx) return Status::error(ctx.error());
    Settings s;
    s.output = OutputMode::Radiance;
    if (!c.blur) s.blur.maxRadiusPx = 0.0f;
    s.blur.coneScale *= c.coneScale;
    s.glossy.mode = c.mode;
    s.temporal.enabled = c.temporal;
    s.radianceClamp.maxLuminance = c.clamp ? options.glossyClampLuminance : 0.0f;
    settings.push_back(s);
    GlossyPoint point;
    point.scene = sceneSpec;
    point.config = c.name;
    Image resolved;
    GlossyMetrics m;
    for (int frame = 0; frame < options.glossyFrames; ++frame) {
      if (Status st = ctx.value()->dispatch(inputs, s); !st) return st;
      resolved = readTexture(ctx.value()->resolvedTexture(), g.width, g.height, 4);
      m = compareGlossy(truth.value(), resolved);
      point.rmseByFrame.push_back(m.rmse);
    }
    point.rmse = m.rmse;
    point.relativeRmse = m.relativeRmse;
    point.uncovered = m.uncovered;
    point.referenceNoise = m.referenceNoise;
    point.rmseAboveNoise = m.rmseAboveNoise;
    point.displayRmse = m.displayRmse;
    point.scored = m.scored;
    out.push_back(std::move(point));
    const std::string file = prefix + "-" + fileSlug(c.name) + "-error.png";
    if (Status st = writeImage((fs::path(reportDir) / file).string(), glossyErrorImage(truth.value(), resolved)); !st)
      return st;
  }
  std::vector<std::vector<double>> times(n);
  for (int round = 0; round < options.warmup + options.frames; ++round)
    for (size_t i = 0; i < n; ++i) {
      Status st;
      Context& ctx = *contexts.get(i).value();  // (created above)
      const double ms = timer.timeMs([&] { st = ctx.dispatch(inputs, settings[i]); },
                                     timer.repeats(options.batch));
      if (!st) return st;
      if (round >= options.warmup) times[i].push_back(ms);
    }
  for (size_t i = 0; i < n; ++i) out[first + i].timeMedianMs = median(times[i]);
  return {};
}

}  // namespace sslr::host
