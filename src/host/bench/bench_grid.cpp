// The benchmark's grid: every configuration of each method (quick and full), the default scenes,
// and the selection --configs makes from them.
#include "sslr_host/benchmark.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <sstream>

namespace sslr::host {

std::string fileSlug(std::string name) {
  // Long names (a scene's full path) keep their first 64 characters and a hash of the whole, so
  // that a report file's name stays far below the file system's 255 bytes and unique.
  constexpr size_t kKept = 64;
  if (name.size() > kKept + 17) {
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
    for (unsigned char c : name) hash = (hash ^ c) * 1099511628211ull;
    char suffix[18];
    std::snprintf(suffix, sizeof suffix, "-%016llx", static_cast<unsigned long long>(hash));
    name = name.substr(0, kKept) + suffix;
  }
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '-';
  return name;
}

std::vector<std::string> defaultBenchScenes() {
  // The scenes built to break the tracer first (those nobody tuned for leading), then the rest;
  // every built-in and asset scene but the two analytic test scenes (mirror-box, tilted-mirror) and
  // bright-emitter, whose HDR emitters would outweigh every other pixel of a linear image error (the
  // glossy study scores it in display space too).
  return {"turned-mirror", "mirror-corridor", "mirrors-from-above", "spider-on-mirror", "wuson-as-mirror",
          "facing-mirror", "thin-objects",    "mirror-walls",       "curved-mirror",    "sphere-over-mirror-32",
          "sphere-over-mirror-128",           "objects-on-mirror",  "glossy",
          "mirror-room",   "grazing-plane",   "sky-heavy"};
}

namespace {

// The full grid's variants of the high preset: measured thickness, the guesses, each device
// profile's pass shapes, the second stage's pass.
void highVariants(std::vector<BenchConfig>& configs) {
  const Preset preset = Preset::High;
  // Measured thickness (a back-face depth input).
  BenchConfig measured{"adaptive-l", "high-back-depth", Settings::preset(preset), false, true};
  configs.push_back(measured);
  // A hidden ray's guess (the occluder's colour; the default weighs it 0.5): none, and at full weight.
  for (float weight : {0.0f, 1.0f}) {
    BenchConfig guess{"adaptive-l", weight < 1.0f ? "high-no-guess" : "high-guess1", Settings::preset(preset), false};
    guess.settings.traversal.hiddenGuess = weight;
    configs.push_back(guess);
  }
  // The pass shapes of each device profile (the Auto profile's is one of the two).
  // The traversal's walk and pixel tests in one loop body, in the Gpu profile's shapes: the same
  // hits; what a GPU's warps pay for the two phases (results/gpu-h100.md).
  BenchConfig oneBody{"adaptive-l", "high-gpu-one-body", Settings::preset(preset), false};
  oneBody.oneBodyTraversal = true;
  oneBody.device = DeviceProfile::Gpu;
  configs.push_back(oneBody);
  // FidelityFX SSSR's exit at low occupancy, in the Gpu profile's shapes, where the driver offers
  // subgroup ballots (ContextDesc::occupancyExit; other hits than the default's).
  BenchConfig occupancyExit{"adaptive-l", "high-gpu-occupancy-exit", Settings::preset(preset), false};
  occupancyExit.occupancyExit = true;
  occupancyExit.device = DeviceProfile::Gpu;
  configs.push_back(occupancyExit);
  for (auto [label, device] : {std::pair{"high-gpu-profile", DeviceProfile::Gpu},
                               std::pair{"high-software-profile", DeviceProfile::Software}}) {
    BenchConfig shaped{"adaptive-l", label, Settings::preset(preset), false};
    shaped.device = device;
    configs.push_back(shaped);
  }
  // Where the second stage (adaptive L after the walk) runs: ContextDesc::traversalPass.
  for (auto [label, pass] : {std::pair{"high-inline", TraversalPass::Inline},
                             std::pair{"high-deferred", TraversalPass::Deferred}}) {
    BenchConfig where{"adaptive-l", label, Settings::preset(preset), false};
    where.traversalPass = pass;
    configs.push_back(where);
  }
}

// sslr's method at each preset, and the high preset's variants.
void adaptiveLConfigs(std::vector<BenchConfig>& configs, bool full) {
  const std::pair<const char*, Preset> presets[] = {
      {"low", Preset::Low}, {"medium", Preset::Medium}, {"high", Preset::High}, {"ultra", Preset::Ultra}};
  for (const auto& [name, preset] : presets) {
    if (!full && preset == Preset::Ultra) continue;
    BenchConfig c{"adaptive-l", name, Settings::preset(preset), preset == Preset::High};
    configs.push_back(c);
    if (preset == Preset::High) {  // the article's tracer alone, without the hierarchical fallback
      BenchConfig alone{"adaptive-l", "high-no-fallback", Settings::preset(preset), false};
      alone.settings.traversal.maxSteps = 0;
      configs.push_back(alone);
      BenchConfig half{"adaptive-l", "high-half", Settings::preset(preset), false};  // one ray per quad
      half.settings.halfResolution = true;
      configs.push_back(half);
      if (full) highVariants(configs);
    }
  }
}

// The hierarchical traversal alone (Method::HierarchicalDepth) at the presets' step caps (medium,
// high) and at 256 (ultra's until 0.12.1).
void hizConfigs(std::vector<BenchConfig>& configs, bool full) {
  const int defaultSteps = Settings::preset(Preset::High).traversal.maxSteps;
  const std::vector<int> allSteps{Settings::preset(Preset::Medium).traversal.maxSteps, defaultSteps, 256};
  for (int steps : full ? allSteps : std::vector<int>{defaultSteps}) {
    BenchConfig c{"hiz", "steps" + std::to_string(steps), Settings::preset(Preset::High), steps == defaultSteps};
    c.settings.method = Method::HierarchicalDepth;
    c.settings.traversal.maxSteps = steps;
    configs.push_back(c);
  }
}

// McGuire & Mara's screen-space DDA over stride and thickness.
void ddaConfigs(std::vector<BenchConfig>& configs, bool full) {
  // McGuire & Mara's screen-space DDA: stride x thickness, each with steps enough to cross about
  // 1024 pixels (so that the stride, not the step cap, sets the reach).
  std::vector<float> strides = full ? std::vector<float>{1.0f, 2.0f, 4.0f, 8.0f} : std::vector<float>{2.0f, 8.0f};
  std::vector<float> thicknesses = full ? std::vector<float>{0.1f, 0.5f} : std::vector<float>{0.5f};
  for (float stride : strides)
    for (float thick : thicknesses) {
      Settings s;
      s.method = Method::ScreenSpaceDDA;
      s.dda.stride = stride;
      s.dda.objectDepth = thick;
      s.dda.maxSteps = static_cast<int>(1024.0f / stride);
      std::ostringstream label;
      label << "stride" << stride << "-thick" << thick;
      configs.push_back({"dda", label.str(), s, stride == 2.0f && thick == 0.5f});
    }
}

// FidelityFX SSSR at its sample's thickness and thicker.
void ffxConfigs(std::vector<BenchConfig>& configs, bool full) {
  // AMD FidelityFX SSSR's mirror-ray raymarch and hit validation: its sample's defaults (depth
  // buffer thickness 0.015, 128 intersections), then thicker (the thickness is its only tolerance).
  std::vector<float> ffxThicknesses = full ? std::vector<float>{0.015f, 0.05f, 0.15f, 0.5f} : std::vector<float>{0.015f};
  for (float thick : ffxThicknesses) {
    Settings s;
    s.method = Method::FidelityFxSssr;
    s.ffx.depthBufferThickness = thick;
    std::ostringstream label;
    label << "thick" << thick;
    configs.push_back({"ffx-sssr", label.str(), s, thick == 0.015f});
  }
}

// The tutorial's position-buffer march: its demo values, its text's, a sweep.
void positionBufferConfigs(std::vector<BenchConfig>& configs, bool full) {
  // The tutorial's method: its demo values first, then the values its text gives (maxDistance 15,
  // resolution 0.3, steps 10), then a sweep.
  std::vector<float> resolutions = full ? std::vector<float>{0.1f, 0.3f, 0.6f, 1.0f} : std::vector<float>{0.3f, 1.0f};
  std::vector<int> steps = full ? std::vector<int>{5, 10} : std::vector<int>{5};
  std::vector<float> distances = full ? std::vector<float>{8.0f, 32.0f} : std::vector<float>{8.0f, 32.0f};
  for (float dist : distances)
    for (float res : resolutions)
      for (int st : steps) {
        Settings s;
        s.method = Method::PositionBuffer;
        s.positionBuffer.maxDistance = dist;
        s.positionBuffer.resolution = res;
        s.positionBuffer.steps = st;
        std::ostringstream label;
        label << "res" << res << "-steps" << st << "-dist" << dist;
        const bool tutorial = dist == 8.0f && res == 0.3f && st == 5;
        configs.push_back({"position-buffer", tutorial ? "tutorial (res0.3-steps5-dist8)" : label.str(), s, tutorial});
      }
  {
    Settings s;
    s.method = Method::PositionBuffer;
    s.positionBuffer.maxDistance = 15.0f;
    s.positionBuffer.resolution = 0.3f;
    s.positionBuffer.steps = 10;
    configs.push_back({"position-buffer", "tutorial text (res0.3-steps10-dist15)", s, false});
  }
}

}  // namespace

std::vector<BenchConfig> benchGrid(const std::string& grid) {
  std::vector<BenchConfig> configs;
  const bool full = grid == "full";
  adaptiveLConfigs(configs, full);
  hizConfigs(configs, full);
  ddaConfigs(configs, full);
  ffxConfigs(configs, full);
  positionBufferConfigs(configs, full);
  BenchConfig baseline{"baseline", "read G-buffer, write 1 texel", Settings{}, false};
  configs.push_back(baseline);
  return configs;
}

Expected<std::vector<BenchConfig>> selectConfigs(const std::vector<BenchConfig>& grid,
                                                 const std::vector<std::string>& names) {
  if (names.empty()) return grid;
  auto selects = [](const std::string& name, const BenchConfig& c) {
    return name == c.method || name == c.method + "/" + c.label;
  };
  for (const std::string& name : names)
    if (std::none_of(grid.begin(), grid.end(), [&](const BenchConfig& c) { return selects(name, c); })) {
      std::string known;
      for (const BenchConfig& c : grid)
        if (c.method != "baseline") known += (known.empty() ? "" : ", ") + c.method + "/" + c.label;
      return Status::error("--configs: '" + name + "' is no configuration of this grid (" + known + ")");
    }
  std::vector<BenchConfig> out;
  for (const BenchConfig& c : grid)
    if (c.method == "baseline" ||
        std::any_of(names.begin(), names.end(), [&](const std::string& n) { return selects(n, c); }))
      out.push_back(c);
  return out;
}

}  // namespace sslr::host
