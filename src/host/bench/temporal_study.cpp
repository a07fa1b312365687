// The temporal study of sslr-bench: each configuration renders the same camera path (still, then
// a slow and a fast orbit about the scene's target, with a host's sub-pixel jitter where named),
// and every frame's resolved reflection is scored against the ideal one from Embree truth.
#include "temporal_study.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "sslr_host/cpu_tracer.hpp"
#include "sslr_host/frame_renderer.hpp"
#include "sslr_host/gbuffer.hpp"

namespace sslr::host {

namespace {

constexpr int kStillFrames = 8, kSlowFrames = 8, kFastFrames = 8;
constexpr double kSlowDegrees = 0.25, kFastDegrees = 2.5;

struct TemporalConfig {
  const char* name;
  bool jitter, half, temporal;
};
constexpr TemporalConfig kConfigs[] = {
    {"full", false, false, false},        {"full+jitter", true, false, false},
    {"full+jitter+temporal", true, false, true}, {"half", false, true, false},
    {"half+temporal", false, true, true},
};

double halton(int index, int base) {
  double f = 1.0, r = 0.0;
  for (int i = index; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}

// The path's camera at `frame`: the scene's camera orbited about the vertical through its target.
Camera cameraAt(const Camera& start, int frame, const char** segment) {
  double degrees = 0.0;
  *segment = "still";
  if (frame >= kStillFrames) {
    const int slow = std::min(frame - kStillFrames + 1, kSlowFrames);
    degrees = slow * kSlowDegrees;
    *segment = "slow";
  }
  if (frame >= kStillFrames + kSlowFrames) {
    degrees += (frame - kStillFrames - kSlowFrames + 1) * kFastDegrees;
    *segment = "fast";
  }
  Camera c = start;
  const glm::dmat4 turn = glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::dvec3(0.0, 1.0, 0.0));
  c.eye = start.target + glm::dvec3(turn * glm::dvec4(start.eye - start.target, 0.0));
  return c;
}

}  // namespace

Status runTemporalStudy(const std::string& sceneName, const BenchOptions& options, Timer& timer,
                        std::vector<TemporalPoint>& out) {
  auto scene = loadScene(sceneName);
  if (!scene) return Status::error(scene.error());
  const Camera start = scene.value().camera ? *scene.value().camera : scene.value().defaultCamera();
  GpuScene gpu(scene.value());
  const int frames = kStillFrames + kSlowFrames + kFastFrames;
  for (const TemporalConfig& config : kConfigs) {
    GBufferOptions g;
    g.width = options.temporalWidth;
    g.height = options.temporalHeight;
    auto renderer = FrameRenderer::create(g);  // a fresh context: its own history
    if (!renderer) return Status::error(renderer.error());
    FrameRenderer& fr = *renderer.value();
    Settings settings;
    settings.halfResolution = config.half;
    settings.temporal = config.temporal;
    for (int frame = 0; frame < frames; ++frame) {
      const char* segment = "";
      const Camera camera = cameraAt(start, frame, &segment);
      const glm::dvec2 jitter =
          config.jitter ? glm::dvec2(halton(frame % 8 + 1, 2) - 0.5, halton(frame % 8 + 1, 3) - 0.5) : glm::dvec2(0.0);
      if (Status st = fr.render(gpu, camera, nullptr, jitter); !st) return st;  // G-buffer and matrices
      Status st;
      const double ms = timer.timeMs([&] { st = fr.sslr().dispatch(fr.inputs(), settings); });
      if (!st) return st;
      // Truth and the ideal reflection read the frame alone (no previous matrices).
      Settings single = settings;
      single.temporal = false;
      auto truth = groundTruthFor(scene.value(), fr.gbuffer(), single);
      if (!truth) return Status::error(truth.error());
      const Image depth = fr.gbuffer().readDepth(), normal = fr.gbuffer().readNormalPacked();
      const Image color = fr.gbuffer().readColor(), resolved = fr.readResolved();
      const Image ideal = idealReflection({&depth, &normal, nullptr}, color, truth.value(), fr.inputs(), single);
      double sumAll = 0, sumVisible = 0, sumHidden = 0;
      size_t nAll = 0, nVisible = 0, nHidden = 0;
      for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
          const TruthClass cls = truth.value().pixels[static_cast<size_t>(y) * g.width + x].cls;
          if (cls == TruthClass::NotReflective) continue;
          double e = 0;
          for (int k = 0; k < 3; ++k) {
            const double d = double(resolved.at(x, y, k)) - ideal.at(x, y, k);
            e += d * d / 3.0;
          }
          sumAll += e, ++nAll;
          if (cls == TruthClass::Visible) sumVisible += e, ++nVisible;
          else sumHidden += e, ++nHidden;
        }
      auto rms = [](double sum, size_t n) { return n ? std::sqrt(sum / double(n)) : 0.0; };
      out.push_back({sceneName, config.name, segment, frame, rms(sumAll, nAll), rms(sumVisible, nVisible),
                     rms(sumHidden, nHidden), ms});
    }
  }
  return {};
}

std::vector<TemporalSummary> summarizeTemporal(const std::vector<TemporalPoint>& points) {
  std::vector<TemporalSummary> out;
  std::vector<std::vector<double>> times;
  std::vector<int> counts;
  for (const TemporalPoint& p : points) {
    if (p.segment == std::string("still") && p.frame < kStillFrames / 2) continue;
    auto it = std::find_if(out.begin(), out.end(), [&](const TemporalSummary& s) {
      return s.scene == p.scene && s.config == p.config && s.segment == p.segment;
    });
    if (it == out.end()) {
      out.push_back({p.scene, p.config, p.segment});
      times.emplace_back();
      counts.push_back(0);
      it = out.end() - 1;
    }
    const size_t i = static_cast<size_t>(it - out.begin());
    it->rmse += p.rmse;
    it->rmseVisible += p.rmseVisible;
    it->rmseHidden += p.rmseHidden;
    times[i].push_back(p.dispatchMs);
    ++counts[i];
  }
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].rmse /= counts[i];
    out[i].rmseVisible /= counts[i];
    out[i].rmseHidden /= counts[i];
    out[i].dispatchMs = median(times[i]);
  }
  return out;
}

}  // namespace sslr::host
