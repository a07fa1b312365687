// The views study of sslr-bench: a scene seen by N eyes side by side (stereo: 2, 0.064 apart and
// centred on the scene's camera), traced three ways with the default settings, timed interleaved:
// eye 0 alone by a one-view context (the unit), every eye by a context of its own (stereo without
// ContextDesc::views), and every eye by one context of N views over 2D-array G-buffers
// (ContextDesc::views, ViewsRenderer). Each also reports a frame's commands, the fixed costs that
// one context of N views pays once.
#include "views_study.hpp"

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "bench_contexts.hpp"
#include "sslr_host/gbuffer.hpp"
#include "sslr_host/scene.hpp"
#include "sslr_host/views_renderer.hpp"

namespace sslr::host {

namespace {

constexpr double kEyeSeparation = 0.064;  // view units between neighbouring eyes (a human's)

PassCommands& operator+=(PassCommands& a, const PassCommands& b) {
  a.dispatches += b.dispatches;
  a.indirectDispatches += b.indirectDispatches;
  a.barriers += b.barriers;
  a.programs += b.programs;
  a.uploads += b.uploads;
  return a;
}

// One way of tracing the eyes: a frame of it, and the contexts whose stats make up that frame.
struct ViewsConfig {
  std::string name;
  int views;
  std::function<Status(const Settings&)> frame;
  std::vector<const Context*> contexts;
};

// Warm-up, then rounds of every configuration back to back in alternating order (a machine's
// drift then weighs on each alike): each configuration's times and its ratios to the first's in
// the same round.
Status timeRounds(const std::vector<ViewsConfig>& configs, const BenchOptions& options, Timer& timer,
                  std::vector<std::vector<double>>& times, std::vector<std::vector<double>>& ratios) {
  const Settings settings;
  // At least two warm-up frames: the first compiles, the second follows the first's feedback
  // (TraversalPass::Auto).
  for (int k = 0; k < std::max(2, options.warmup); ++k)
    for (const ViewsConfig& c : configs)
      if (Status st = c.frame(settings); !st) return st;
  times.assign(configs.size(), {});
  ratios.assign(configs.size(), {});
  const int repeats = timer.repeats(options.batch);
  for (int sample = 0; sample < options.frames; ++sample) {
    std::vector<double> round(configs.size());
    for (size_t k = 0; k < configs.size(); ++k) {
      const size_t i = sample % 2 == 0 ? k : configs.size() - 1 - k;
      Status st;
      round[i] = timer.timeMs([&] { st = configs[i].frame(settings); }, repeats);
      if (!st) return st;
    }
    for (size_t i = 0; i < configs.size(); ++i) {
      times[i].push_back(round[i]);
      ratios[i].push_back(round[0] > 0.0 ? round[i] / round[0] : 0.0);
    }
  }
  return {};
}

}  // namespace

Status runViewsStudy(const std::string& sceneName, const BenchOptions& options, Timer& timer,
                     std::vector<ViewsPoint>& out) {
  auto scene = loadScene(sceneName);
  if (!scene) return Status::error(scene.error());
  const Camera start = scene.value().camera ? *scene.value().camera : scene.value().defaultCamera();
  GpuScene gpu(scene.value());
  const int w = options.viewsWidth, h = options.viewsHeight, n = options.viewsCount;
  GBufferOptions g;
  g.width = w;
  g.height = h;
  // Every eye's G-buffer and the layered inputs (ViewsRenderer, whose context traces every eye).
  ContextDesc shapes;
  shapes.device = options.device;
  auto views = ViewsRenderer::create(g, n, nullptr, shapes);
  if (!views) return Status::error(views.error());
  ViewsRenderer& layered = *views.value();
  if (Status s = layered.render(gpu, sideBySideCameras(start, n, kEyeSeparation), nullptr); !s) return s;
  std::vector<FrameInputs> eyeInputs;
  for (int v = 0; v < n; ++v) eyeInputs.push_back(layered.viewInputs(v));
  // One-view contexts: 0 for eye 0 alone, 1 + v for eye v.
  ConfigContexts oneView(w, h);
  std::vector<Context*> contexts;
  for (int c = 0; c <= n; ++c) {
    auto context = oneView.get(static_cast<size_t>(c), shapes);
    if (!context) return context.status();
    contexts.push_back(context.value());
  }
  const std::vector<ViewsConfig> configs = {
      {"one view", 1, [&](const Settings& s) { return contexts[0]->dispatch(eyeInputs[0], s); }, {contexts[0]}},
      {"a context a view", n,
       [&](const Settings& s) {
         for (int v = 0; v < n; ++v)
           if (Status st = contexts[1 + v]->dispatch(eyeInputs[v], s); !st) return st;
         return Status{};
       },
       {contexts.begin() + 1, contexts.end()}},
      {"one context of " + std::to_string(n) + " views", n,
       [&](const Settings& s) { return layered.sslr().dispatch(layered.layeredInputs(), s); }, {&layered.sslr()}},
  };
  std::vector<std::vector<double>> times, ratios;
  if (Status st = timeRounds(configs, options, timer, times, ratios); !st) return st;
  // A frame's commands and counts, from one frame with stats after the timed ones.
  Settings counted;
  counted.debug.collectStats = true;
  for (size_t i = 0; i < configs.size(); ++i) {
    if (Status st = configs[i].frame(counted); !st) return st;
    ViewsPoint p;
    p.scene = sceneName;
    p.config = configs[i].name;
    p.views = configs[i].views;
    p.timeMedianMs = median(times[i]);
    p.ratioToOneView = median(ratios[i]);
    for (const Context* c : configs[i].contexts) {
      const FrameStats stats = c->waitForStats();
      p.commands += stats.totalCommands();
      p.tracedPixels += stats.tracedPixels;
      p.tiles += stats.tiles;
    }
    out.push_back(p);
  }
  return {};
}

}  // namespace sslr::host
