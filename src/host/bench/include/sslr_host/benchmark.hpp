// sslr-bench's engine: methods x scenes x parameter grids, timed interleaved in one run, scored
// against Embree ground truth; results as JSON/CSV and a static HTML report.
#pragma once

#include <cmath>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sslr/sslr.hpp"
#include "sslr_host/ground_truth.hpp"
#include "sslr_host/reference_image.hpp"

namespace sslr::host {

struct BenchOptions {
  std::string grid = "quick";       // "quick" (CI) or "full" (docs)
  // Configurations of the grid to run, each "method" (all its configurations) or "method/label"
  // (selectConfigs); empty: the whole grid. The baseline pass always runs.
  std::vector<std::string> configs;
  std::vector<std::string> scenes;  // empty: every built-in scene but the analytic test scenes
  int width = 320, height = 180;
  int frames = 7;                   // timed frames per config (median reported)
  int warmup = 1;
  // Dispatches timed back to back per sample (the sample is their mean); 0: 8 on a GPU, 1 on a
  // software renderer. 1 times a lone dispatch, which on a GPU includes the CPU issuing it.
  int batch = 0;
  // Cost curves: each method's default and the baseline pass, timed against resolution (on
  // mirror-room) and against the reflective fraction of the frame (reflective-N scenes at
  // width x height). Empty: no resolution curve; fractions empty: no fraction curve.
  std::vector<std::pair<int, int>> curveSizes;
  std::vector<int> curveFractions;
  // Temporal reuse over a camera path (empty: not run), at temporalWidth x temporalHeight.
  std::vector<std::string> temporalScenes;
  int temporalWidth = 480, temporalHeight = 270;
  // Several views (ContextDesc::views; empty: not run): viewsCount eyes 0.064 units apart on each
  // scene at viewsWidth x viewsHeight, traced by one view's context, by a context a view and by one
  // context of every view, timed interleaved (frames samples after warmup).
  std::vector<std::string> viewsScenes;
  int viewsWidth = 480, viewsHeight = 270;
  int viewsCount = 2;
  // Glossy reflections against a GGX reference (empty: not run): scenes, each a scene name or
  // "name@roughR" (its mirrors, materials of roughness below 0.1, made R rough), at glossyWidth x
  // glossyHeight with glossySamples reference rays per pixel.
  std::vector<std::string> glossyScenes;
  int glossyWidth = 480, glossyHeight = 270;
  int glossySamples = 256;
  // Still frames each configuration runs before it is scored (temporal reuse accumulates over
  // them); the error after every one of them is kept (GlossyPoint::rmseByFrame). Fixed, so that
  // the score does not depend on how many frames the timer runs.
  int glossyFrames = 8;
  // The "clamp" configurations' Settings::radianceClamp.maxLuminance (display units, > 0).
  float glossyClampLuminance = 256.0f;
  // Pass shapes of the configurations that name none (ContextDesc::device); Auto: the renderer's.
  // DeviceProfile::Gpu on a CPU rasterizer counts a GPU's ray work there (predictedH100Ms).
  DeviceProfile device = DeviceProfile::Auto;
};

struct BenchConfig {
  std::string method;  // "adaptive-l", "hiz", "dda", "position-buffer" or "baseline"
  std::string label;   // e.g. "high", "res0.3-steps5-dist8"
  Settings settings;
  bool isDefault = false;  // the method's default configuration (image strips, summary)
  bool backDepth = false;  // hand sslr the back-face depth (FrameInputs::backDepthTexture)
  // The context's pass shapes (ContextDesc's device, traversalPass, oneBodyTraversal, occupancyExit).
  DeviceProfile device = DeviceProfile::Auto;
  TraversalPass traversalPass = TraversalPass::Auto;
  bool oneBodyTraversal = false;
  bool occupancyExit = false;
  // Those shapes as a ContextDesc (its size and loader for the caller to set).
  ContextDesc shapes() const {
    ContextDesc d;
    d.device = device;
    d.traversalPass = traversalPass;
    d.oneBodyTraversal = oneBodyTraversal;
    d.occupancyExit = occupancyExit;
    return d;
  }
  bool ownShapes() const {
    return device != DeviceProfile::Auto || traversalPass != TraversalPass::Auto || oneBodyTraversal || occupancyExit;
  }
};

struct RunRecord {
  std::string scene, method, label;
  BenchConfig config;
  int width = 0, height = 0;
  std::string renderer, timingMethod;
  double timeMedianMs = 0, timeMinMs = 0, timeMaxMs = 0;
  int frames = 0;
  HitMetrics metrics;
  std::uint32_t tracedPixels = 0, fetches = 0;
  PassCommands commands;  // recorded by one frame (FrameStats::totalCommands; with debug outputs on)
  PassTraffic traffic;    // that frame's texture memory (FrameStats::totalTraffic; debug images included)
  FrameStats frameStats;  // that frame's stats, pass by pass
  double fetchesPerTracedPixel = 0;
  int gbufferBytesPerPixel = 0;  // colour + normal + depth (+ position for the tutorial's method)
  int extraBytesPerPixel = 0;    // sslr's own textures (reflection, blur temp, resolved)
  size_t nonFiniteOutputs = 0;   // NaN/Inf pixels in reflection + resolved
  // The composite (over the fallback) against the ray-traced reference, over the mirror pixels
  // (reference_image.hpp): what the user sees. NaN where not measured (the baseline).
  double compositeRmse = NAN, compositePsnr = NAN;
  // Where that error comes from (hits, wrong hits, misses, unreachable; the wrong hits' pixels as
  // misses): the composite's pixels by what the method reported.
  CompositeBreakdown compositeBreakdown;
  // The frame's time on an NVIDIA H100 as the ray-work model predicts it (cost_model.hpp); NaN
  // where the model does not apply (a frame not shaped as the fitted ones, the baseline).
  double predictedH100Ms = NAN;
};

struct SceneRecord {
  std::string scene;
  size_t reflective = 0, visible = 0, occluded = 0, offScreen = 0, escaped = 0;
  // Depth-only vs stored positions: reconstruction error and the same tracer on both.
  double positionErrorMedian = 0, positionErrorMax = 0, positionErrorMaxRelative = 0;
  double hitAgreement = 0;  // pixels whose hit decision and uv (within 1 px) agree
  double recallDepth = 0, recallStored = 0;
  bool showsNothing = false;        // no pixel of the frame shows the scene (GBuffer::showsNothing)
  std::vector<std::string> images;  // image strip files, relative to the report folder
};

// One point of a cost curve: a method's default configuration (or the baseline pass) at one
// resolution or reflective fraction.
struct CurvePoint {
  std::string curve;   // "resolution" or "fraction"
  std::string method;  // as in RunRecord, "baseline" for the read-G-buffer-write-one-texel pass
  int width = 0, height = 0;
  int percent = -1;                // fraction curve: the reflective-N scene's N
  double tracedFraction = 0;       // traced pixels / all pixels (what the frame actually reflects)
  double timeMedianMs = 0;
};

// One frame of the temporal study: a camera path (still, then a slow and a fast orbit) rendered
// with each configuration; the resolved reflection against the ideal one (cpu_tracer.hpp's
// idealReflection: Embree truth, confidence 1) of the same frame.
struct TemporalPoint {
  std::string scene;
  std::string config;   // "full", "full+jitter", "full+jitter+temporal", "half", "half+temporal"
  std::string segment;  // "still", "slow" (0.25 degrees per frame), "fast" (2.5 degrees per frame)
  int frame = 0;
  double rmse = 0;         // resolved rgb against the ideal, over every reflective pixel
  double rmseVisible = 0;  // over the pixels whose true reflection is visible on screen (A)
  double rmseHidden = 0;   // over the others (B, C, D: the ideal is 0): ghosts and false hits
  double dispatchMs = 0;   // that frame's dispatch (noisy: one sample)
};

// One configuration of the glossy study on one scene: its Radiance-mode output (rgb / a) against
// the GGX reference (glossy_truth.hpp) over the glossy pixels whose lobe the screen shows.
struct GlossyPoint {
  std::string scene;         // "glossy", "mirror-room@rough0.3", ...
  std::string config;        // "cone blur" (the default), "cone blur x0.5", "cone blur x2", "no blur"
  double rmse = 0;           // linear colour, per channel
  double relativeRmse = 0;   // rmse / the reference's RMS
  double uncovered = 0;      // share of the scored pixels with no estimate
  double referenceNoise = 0; // the reference's own noise (RMS), the floor of any rmse
  double rmseAboveNoise = 0; // sqrt(rmse^2 - referenceNoise^2)
  double displayRmse = 0;    // after x / (1 + x) per channel: what a viewer sees of HDR radiance
  size_t scored = 0;
  double timeMedianMs = 0;   // dispatch, configurations interleaved
  // rmse after each of BenchOptions::glossyFrames still frames (the last one is `rmse`): the
  // convergence curve of temporal reuse, a single frame's noise elsewhere.
  std::vector<double> rmseByFrame;
};

// One configuration of the views study on one scene: the default settings on viewsCount eyes.
struct ViewsPoint {
  std::string scene;
  std::string config;  // "one view" (eye 0 alone), "a context a view", "one context of N views"
  int views = 1;       // eyes traced
  double timeMedianMs = 0;  // a frame of every eye it traces, configurations interleaved
  double ratioToOneView = 0;  // the median over rounds of this time / one view's in the same round
  // A frame's commands (dispatch(); every context's summed), its traced pixels and tiles.
  PassCommands commands;
  std::uint64_t tracedPixels = 0, tiles = 0;
};

struct BenchResult {
  BenchOptions options;
  std::string renderer, timingMethod;
  std::vector<RunRecord> runs;
  std::vector<SceneRecord> scenes;
  std::vector<CurvePoint> curves;
  std::vector<TemporalPoint> temporal;
  std::vector<GlossyPoint> glossy;
  std::vector<ViewsPoint> views;
};

// The temporal study per scene, configuration and segment: mean errors over the segment's frames
// (the still segment's second half only, once a history has built up), median dispatch time.
struct TemporalSummary {
  std::string scene, config, segment;
  double rmse = 0, rmseVisible = 0, rmseHidden = 0, dispatchMs = 0;
};
std::vector<TemporalSummary> summarizeTemporal(const std::vector<TemporalPoint>& points);

// A glossy study's scene: "name@roughR" -> the scene with its mirrors (materials of roughness
// below 0.1) made R rough; "name" as loadScene gives it.
Expected<Scene> loadGlossyScene(const std::string& sceneSpec);

// A name made safe for a file name: every character but letters and digits a '-'; past 81
// characters, its first 64 and a hash of the whole (16 hex digits).
std::string fileSlug(std::string name);

std::vector<BenchConfig> benchGrid(const std::string& grid);
// The scenes a run without --scenes measures, the hardest first.
std::vector<std::string> defaultBenchScenes();

// The configurations of `grid` that `names` select ("method" or "method/label", see
// BenchOptions::configs), in grid order, with the baseline; an error names a name that selects
// nothing and lists what the grid holds.
Expected<std::vector<BenchConfig>> selectConfigs(const std::vector<BenchConfig>& grid,
                                                 const std::vector<std::string>& names);

// Runs everything; `reportDir` receives the image strips while running. Needs a current GL
// context (HeadlessContext). `progress(done, total, what)` is called as work proceeds.
Expected<BenchResult> runBenchmark(const BenchOptions& options, bool isSoftwareRenderer, const std::string& renderer,
                                   const std::string& reportDir,
                                   const std::function<void(int, int, const std::string&)>& progress);

// Each method's default run on `scene`, and the tutorial's configuration (the position-buffer
// default) that summaries take time ratios to (nullptr if the run has none).
struct SceneDefaults {
  std::vector<const RunRecord*> runs;
  const RunRecord* tutorial = nullptr;
};
SceneDefaults defaultRuns(const BenchResult& result, const std::string& scene);

// Per method, its fastest configuration on `scene` whose recall@1px reaches `minRecall` (run is
// nullptr when none does), in the order the grid lists the methods.
inline constexpr double kParetoRecall = 0.95;  // "reaches the target" in reports and summaries
struct FastestRun {
  std::string method;
  const RunRecord* run = nullptr;
};
std::vector<FastestRun> fastestReaching(const BenchResult& result, const std::string& scene, double minRecall);

// results.json, results.csv and report/index.html under outDir.
Status writeBenchResults(const BenchResult& result, const std::string& outDir);

}  // namespace sslr::host
