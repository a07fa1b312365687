// The temporal study of sslr-bench: each configuration renders the same camera path (still, then
// a slow and a fast orbit about the scene's target, with a host's sub-pixel jitter where named),
// and every frame's resolved reflection is scored against the ideal one from Embree truth.
#include "temporal_study.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

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
  // Truth and the ideal reflection depend only on the frame (camera and jitter), not on the
  // configuration: computed once per frame for the jittered configurations and once for the rest.
  struct Reference {
    GroundTruth truth;
    Image ideal;
  };
  std::map<std::pair<int, bool>, Reference> references;
  for (const TemporalConfig& config : kConfigs) {
    GBufferOptions g;
    g.width = options.temporalWidth;
    g.height = options.temporalHeight;
    auto renderer = FrameRenderer::create(g);  // a fresh context: its own history
    if (!renderer) return Status::error(renderer.error());
    FrameRenderer& fr = *renderer.value();
    Settings settings;
    settings.halfResolution = config.half;
    settings.temporal.enabled = config.temporal;
    for (int frame = 0; frame < frames; ++frame) {
      const char* segment = "";
      const Camera camera = cameraAt(start, frame, &segment);
      const glm::dvec2 jitter =
          config.jitter ? glm::dvec2(halton(frame % 8 + 1, 2) - 0.5, halton(frame % 8 + 1, 3) - 0.5) : glm::dvec2(0.0);
      if (Status st = fr.render(gpu, camera, nullptr, jitter); !st) return st;  // G-buffer and matrices
      Status st;
      const double ms = timer.timeMs([&] { st = fr.sslr().dispatch(fr.inputs(), settings); });
      if (!st) return st;
      auto ref = references.find({frame, config.jitter});
      if (ref == references.end()) {
        // They read the frame alone (no previous matrices); the traced pixels do not depend on
        // half resolution.
        const Settings single;
        auto truth = groundTruthFor(scene.value(), fr.gbuffer(), single);
        if (!truth) return Status::error(truth.error());
        const Image depth = fr.gbuffer().readDepth(), normal = fr.gbuffer().readNormalPacked();
        const Image color = fr.gbuffer().readColor();
        Image ideal = idealReflection({&depth, &normal, nullptr}, color, truth.value(), fr.inputs(), single);
        ref = references.emplace(std::pair{frame, config.jitter}, Reference{std::move(truth.value()), std::move(ideal)})
                  .first;
      }
      const GroundTruth& truth = ref->second.truth;
      const Image& ideal = ref->second.ideal;
      const Image resolved = fr.readResolved();
      double sumAll = 0, sumVisible = 0, sumHidden = 0;
      size_t nAll = 0, nVisible = 0, nHidden = 0;
      for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
          const TruthClass cls = truth.pixels[static_cast<size_t>(y) * g.width + x].cls;
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
  struct Group {
    TemporalSummary sum;
    std::vector<double> times;
  };
  std::vector<Group> groups;  // in the order the points come (scene, configuration, segment)
  for (const TemporalPoint& p : points) {
    if (p.segment == std::string("still") && p.frame < kStillFrames / 2) continue;
    auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
      return g.sum.scene == p.scene && g.sum.config == p.config && g.sum.segment == p.segment;
    });
    if (it == groups.end()) it = groups.insert(groups.end(), Group{{p.scene, p.config, p.segment}, {}});
    it->sum.rmse += p.rmse;
    it->sum.rmseVisible += p.rmseVisible;
    it->sum.rmseHidden += p.rmseHidden;
    it->times.push_back(p.dispatchMs);
  }
  std::vector<TemporalSummary> out;
  for (Group& g : groups) {
    const double n = static_cast<double>(g.times.size());
    g.sum.rmse /= n;
    g.sum.rmseVisible /= n;
    g.sum.rmseHidden /= n;
    g.sum.dispatchMs = median(g.times);
    out.push_back(g.sum);
  }
  return out;
}

}  // namespace sslr::host
