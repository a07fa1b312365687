// The views study of sslr-bench: a scene seen by N eyes side by side (stereo: 2, 0.064 apart and
// centred on the scene's camera), traced three ways with the default settings, timed interleaved:
// eye 0 alone by a one-view context (the unit), every eye by a context of its own (stereo before
// ContextDesc::views), and every eye by one context of N views over 2D-array G-buffers
// (ContextDesc::views, ViewsRenderer). Each also reports a frame's commands, the fixed costs that
// one context of N views pays once.
#include "views_study.hpp"

#include <algorithm>
#include <memory>
#include <utility>

#include <glm/glm.hpp>

#include "sslr_host/egl_context.hpp"
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

Expected<std::unique_ptr<Context>> makeContext(int w, int h, DeviceProfile device) {
  ContextDesc d;
  d.width = w;
  d.height = h;
  d.device = device;
  d.getProcAddress = HeadlessContext::getProcAddress();
  return Context::create(d);
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
  // Every eye's G-buffer and the layered inputs (ViewsRenderer), traced three ways below.
  auto views = ViewsRenderer::create(g, n, nullptr, options.device);
  if (!views) return Status::error(views.error());
  ViewsRenderer& layered = *views.value();
  if (Status s = layered.render(gpu, sideBySideCameras(start, n, kEyeSeparation), nullptr); !s) return s;
  std::vector<FrameInputs> eyeInputs;
  for (int v = 0; v < n; ++v) eyeInputs.push_back(layered.viewInputs(v));
  // Contexts: eye 0 alone, one an eye; the renderer's own traces every eye.
  auto alone = makeContext(w, h, options.device);
  if (!alone) return alone.status();
  std::vector<std::unique_ptr<Context>> perEye;
  for (int v = 0; v < n; ++v) {
    auto c = makeContext(w, h, options.device);
    if (!c) return c.status();
    perEye.push_back(std::move(c.value()));
  }
  Context* together = &layered.sslr();

  struct Config {
    std::string name;
    int views;
    std::function<Status(const Settings&)> frame;
  };
  const std::vector<Config> configs = {
      {"one view", 1, [&](const Settings& s) { return alone.value()->dispatch(eyeInputs[0], s); }},
      {"a context a view", n,
       [&](const Settings& s) {
         for (int v = 0; v < n; ++v)
           if (Status st = perEye[v]->dispatch(eyeInputs[v], s); !st) return st;
         return Status{};
       }},
      {"one context of " + std::to_string(n) + " views", n,
       [&](const Settings& s) { return together->dispatch(layered.layeredInputs(), s); }},
  };
  const Settings settings;
  // At least two warm-up frames: the first compiles, the second follows the first's feedback
  // (TraversalPass::Auto).
  for (int k = 0; k < std::max(2, options.warmup); ++k)
    for (const Config& c : configs)
      if (Status st = c.frame(settings); !st) return st;
  // Rounds of every configuration back to back, in alternating order (a machine's drift then
  // weighs on each alike); the ratio to one view is the median of each round's own ratio.
  std::vector<std::vector<double>> times(configs.size()), ratios(configs.size());
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
  // A frame's commands and counts, from one frame with stats after the timed ones.
  Settings counted = settings;
  counted.debug.collectStats = true;
  for (size_t i = 0; i < configs.size(); ++i) {
    if (Status st = configs[i].frame(counted); !st) return st;
    ViewsPoint p;
    p.scene = sceneName;
    p.config = configs[i].name;
    p.views = configs[i].views;
    p.timeMedianMs = median(times[i]);
    p.ratioToOneView = median(ratios[i]);
    std::vector<const Context*> used;
    if (i == 0) used = {alone.value().get()};
    if (i == 1)
      for (const auto& c : perEye) used.push_back(c.get());
    if (i == 2) used = {together};
    for (const Context* c : used) {
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
