// sslr-bench: run time against error, depth-only adaptive L vs the screen-space DDA, the hierarchical traversal and the position-buffer method, on
// every built-in scene, with Embree ground truth. Writes DIR/results.json, DIR/results.csv and
// DIR/report/index.html. Exit codes: 0 success, 1 failure, 2 bad arguments.
#include <unistd.h>

#include <cxxopts.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "sslr_host/benchmark.hpp"
#include "sslr_host/egl_context.hpp"
#include "sslr_host/image_io.hpp"

using namespace sslr;
using namespace sslr::host;

namespace {

// Redraws one line on a terminal; prints a line every few seconds otherwise (CI logs).
class Progress {
 public:
  Progress() : tty_(isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {}
  void operator()(int done, int total, const std::string& what) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int pct = total > 0 ? 100 * done / total : 100;
    if (tty_) {
      std::fprintf(stderr, "\r[%3d%%] %6.1fs  %-70.70s", pct, elapsed, what.c_str());
      std::fflush(stderr);
    } else if (elapsed - lastPrint_ >= 5.0 || done == total) {
      std::fprintf(stderr, "[%3d%%] %6.1fs  %s\n", pct, elapsed, what.c_str());
      lastPrint_ = elapsed;
    }
  }
  void finish() {
    if (tty_) std::fprintf(stderr, "\n");
  }

 private:
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  double lastPrint_ = -1e9;
};


// Every option, with its help.
cxxopts::Options benchOptions() {
  cxxopts::Options options("sslr-bench", "Run time against error: depth-only SSLR vs position-buffer SSR.");
  std::string defaultScenes;
  for (const std::string& s : defaultBenchScenes()) defaultScenes += (defaultScenes.empty() ? "" : ",") + s;
  options.add_options()
      ("grid", "parameter grid: quick (CI) or full (docs)", cxxopts::value<std::string>()->default_value("quick"))
      ("scenes", "comma-separated scenes (default: " + defaultScenes + ")",
       cxxopts::value<std::string>()->default_value(""))
      ("configs", "run only these configurations of the grid, comma-separated, each a method (adaptive-l, hiz, dda, "
                  "ffx-sssr, position-buffer) or method/label (e.g. adaptive-l/high); the baseline pass always runs",
       cxxopts::value<std::string>())
      ("size", "resolution WxH", cxxopts::value<std::string>())
      ("frames", "timed frames per configuration (median reported)", cxxopts::value<std::string>())
      ("warmup", "untimed warm-up rounds", cxxopts::value<std::string>())
      ("batch", "dispatches timed back to back per sample, the sample being their mean (default 8 on a GPU, "
                "where a lone dispatch also times the CPU issuing it; 1 on a software renderer)",
       cxxopts::value<std::string>())
      ("curves", "also time the cost curves (the full grid always does): resolution 480x270, 960x540, 1920x1080 (full: and 3840x2160) and reflective fraction 0, 1, 10, 50, 100%")
      ("no-curves", "skip the cost curves")
      ("temporal", "also run the temporal study (the full grid always does): a camera path on mirror-room, curved-mirror and glossy with and without temporal reuse, jitter and half resolution")
      ("temporal-scenes", "scenes of the temporal study, comma-separated (implies --temporal)", cxxopts::value<std::string>())
      ("temporal-size", "size of the temporal study's frames, WxH", cxxopts::value<std::string>()->default_value("480x270"))
      ("no-temporal", "skip the temporal study")
      ("views", "also run the views study (the full grid always does): stereo eyes on mirror-room, glossy and "
                "sky-heavy traced by one view's context, by a context a view and by one context of every view")
      ("views-scenes", "scenes of the views study, comma-separated (implies --views)", cxxopts::value<std::string>())
      ("views-size", "size of the views study's frames, WxH", cxxopts::value<std::string>()->default_value("480x270"))
      ("views-count", "eyes of the views study (2..4)", cxxopts::value<std::string>()->default_value("2"))
      ("no-views", "skip the views study")
      ("glossy", "also run the glossy study (the full grid always does): the roughness blur against a GGX reference "
                 "traced by Embree, on glossy and rough variants of mirror scenes")
      ("glossy-scenes", "scenes of the glossy study, comma-separated, each a scene or NAME@roughR (its mirrors made R "
                        "rough; implies --glossy)", cxxopts::value<std::string>())
      ("glossy-size", "size of the glossy study's frames, WxH", cxxopts::value<std::string>()->default_value("480x270"))
      ("glossy-samples", "reference rays per glossy pixel (2..65536)", cxxopts::value<std::string>()->default_value("256"))
      ("glossy-frames", "still frames each glossy configuration runs before its score (1..1024; temporal reuse "
                        "accumulates over them, the error after each is in results.json)",
       cxxopts::value<std::string>()->default_value("8"))
      ("glossy-clamp", "Settings::radianceClamp.maxLuminance of the glossy study's \"clamp\" configurations (display "
                       "units, > 0)", cxxopts::value<std::string>()->default_value("256"))
      ("no-glossy", "skip the glossy study")
      ("curve-sizes", "resolutions of the resolution curve, WxH,WxH,... (implies --curves)", cxxopts::value<std::string>())
      ("curve-fractions", "reflective percentages of the fraction curve, N,N,... (implies --curves)", cxxopts::value<std::string>())
      ("out", "output directory", cxxopts::value<std::string>()->default_value("bench-out"))
      ("device", "EGL device: auto, hardware, software, surfaceless or an index", cxxopts::value<std::string>()->default_value(""))
      ("device-profile", "sslr's pass shapes for the configurations that name none: auto (software on a CPU "
                         "rasterizer, else gpu), gpu or software; gpu on a CPU rasterizer counts a GPU's ray work and "
                         "predicts its H100 time (predictedH100Ms)", cxxopts::value<std::string>()->default_value("auto"))
      ("h,help", "show this help");
  return options;
}

// A list option's items, comma-separated, empty ones skipped.
std::vector<std::string> listItems(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

// A scene list's items, each listed once: a scene named twice would be run (and reported) twice.
std::vector<std::string> uniqueItems(const std::string& text, const std::string& option) {
  std::vector<std::string> items = listItems(text);
  for (size_t i = 0; i < items.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (items[i] == items[j]) throw std::runtime_error("--" + option + " lists '" + items[i] + "' twice");
  return items;
}

// Whether all of `text` reads as one number of T (into value).
template <typename T>
bool wholeNumber(const std::string& text, T& value) {
  std::istringstream in(text);
  return (in >> value) && in.eof();
}

// WxH with each side in [lo, hi], or an error naming the option.
std::pair<int, int> parseSizeOption(const std::string& text, const std::string& option, int lo, int hi) {
  std::istringstream in(text);
  int w = 0, h = 0;
  char x = 0;
  if (!(in >> w >> x >> h) || x != 'x' || !in.eof() || w < lo || h < lo || w > hi || h > hi)
    throw std::runtime_error("--" + option + (option == "curve-sizes" ? " expects WxH,WxH,... with " : " expects WxH with ") + std::to_string(lo) + ".." + std::to_string(hi) +
                             " each (got '" + text + "')");
  return {w, h};
}

// The grid, the configurations, the size, the frame counts and the scenes.
void parseGrid(const cxxopts::ParseResult& args, BenchOptions& bo) {
  bo.grid = args["grid"].as<std::string>();
  if (bo.grid != "quick" && bo.grid != "full") throw std::runtime_error("--grid must be quick or full");
  if (bo.grid == "full") {
    bo.width = 960;
    bo.height = 540;
    bo.frames = 15;
    bo.warmup = 2;
  }
  const std::string profile = args["device-profile"].as<std::string>();
  if (profile == "gpu") bo.device = DeviceProfile::Gpu;
  else if (profile == "software") bo.device = DeviceProfile::Software;
  else if (profile != "auto") throw std::runtime_error("--device-profile must be auto, gpu or software (got '" + profile + "')");
  if (args.count("configs")) {
    bo.configs = listItems(args["configs"].as<std::string>());
    if (auto check = selectConfigs(benchGrid(bo.grid), bo.configs); !check) throw std::runtime_error(check.error());
  }
  auto positiveInt = [&](const char* name, int& value, int lo, int hi) {
    if (!args.count(name)) return;
    if (!wholeNumber(args[name].as<std::string>(), value) || value < lo || value > hi)
      throw std::runtime_error(std::string("--") + name + " expects an integer in " + std::to_string(lo) + ".." +
                               std::to_string(hi));
  };
  positiveInt("frames", bo.frames, 1, 1000);
  positiveInt("warmup", bo.warmup, 0, 100);
  positiveInt("batch", bo.batch, 1, 64);
  if (args.count("size")) std::tie(bo.width, bo.height) = parseSizeOption(args["size"].as<std::string>(), "size", 8, 8192);
  std::vector<std::string> identities;  // a file by its canonical path: two spellings, one scene
  for (const std::string& s : uniqueItems(args["scenes"].as<std::string>(), "scenes")) {
    if (auto check = loadScene(s); !check) throw std::runtime_error(check.error());
    std::error_code ec;
    const std::string identity = std::filesystem::exists(s, ec) ? std::filesystem::weakly_canonical(s, ec).string() : s;
    for (size_t j = 0; j < identities.size(); ++j)
      if (identities[j] == identity)
        throw std::runtime_error("--scenes lists '" + bo.scenes[j] + "' and '" + s + "', the same scene");
    identities.push_back(identity);
    bo.scenes.push_back(s);
  }
}

// The views study's options (checked whether or not it runs, as every study's).
void parseViewsStudy(const cxxopts::ParseResult& args, BenchOptions& bo) {
  const auto viewsSize = parseSizeOption(args["views-size"].as<std::string>(), "views-size", 8, 4096);
  const std::string countText = args["views-count"].as<std::string>();
  int viewsCount = 0;
  if (!wholeNumber(countText, viewsCount) || viewsCount < 2 || viewsCount > kMaxViews)
    throw std::runtime_error("--views-count expects an integer 2.." + std::to_string(kMaxViews) + " (got '" +
                             countText + "')");
  std::vector<std::string> viewsScenes = {"mirror-room", "glossy", "sky-heavy"};
  if (args.count("views-scenes")) {
    viewsScenes = uniqueItems(args["views-scenes"].as<std::string>(), "views-scenes");
    for (const std::string& s : viewsScenes)
      if (auto check = loadScene(s); !check) throw std::runtime_error("--views-scenes: " + check.error());
  }
  bool views = bo.grid == "full" || args.count("views") || args.count("views-scenes");
  if (args.count("no-views")) views = false;
  if (views) {
    std::tie(bo.viewsWidth, bo.viewsHeight) = viewsSize;
    bo.viewsCount = viewsCount;
    bo.viewsScenes = viewsScenes;
  }
}

// The cost curves, the glossy, the temporal and the views study, when asked for (the full grid
// runs them). Every study's options are checked whether or not it runs: a mistyped value is an
// error even beside --no-curves, --no-glossy, --no-temporal or --no-views.
void parseStudies(const cxxopts::ParseResult& args, BenchOptions& bo) {
  std::vector<std::pair<int, int>> sizes = {{480, 270}, {960, 540}, {1920, 1080}};
  if (bo.grid == "full") sizes.push_back({3840, 2160});
  std::vector<int> fractions = {0, 1, 10, 50, 100};
  if (args.count("curve-sizes")) {
    sizes.clear();
    for (const std::string& item : listItems(args["curve-sizes"].as<std::string>()))
      sizes.push_back(parseSizeOption(item, "curve-sizes", 8, 8192));
  }
  if (args.count("curve-fractions")) {
    fractions.clear();
    for (const std::string& item : listItems(args["curve-fractions"].as<std::string>())) {
      int n = -1;
      if (!wholeNumber(item, n) || n < 0 || n > 100)
        throw std::runtime_error("--curve-fractions expects percentages 0..100 (got '" + item + "')");
      fractions.push_back(n);
    }
  }
  bool curves = bo.grid == "full" || args.count("curves") || args.count("curve-sizes") || args.count("curve-fractions");
  if (args.count("no-curves")) curves = false;
  if (curves) {
    bo.curveSizes = sizes;
    bo.curveFractions = fractions;
  }

  const auto glossySize = parseSizeOption(args["glossy-size"].as<std::string>(), "glossy-size", 8, 4096);
  const std::string samples = args["glossy-samples"].as<std::string>();
  int glossySamples = 0;
  if (!wholeNumber(samples, glossySamples) || glossySamples < 2 || glossySamples > 65536)
    throw std::runtime_error("--glossy-samples expects an integer 2..65536 (got '" + samples + "')");
  const std::string framesText = args["glossy-frames"].as<std::string>();
  int glossyFrames = 0;
  if (!wholeNumber(framesText, glossyFrames) || glossyFrames < 1 || glossyFrames > 1024)
    throw std::runtime_error("--glossy-frames expects an integer 1..1024 (got '" + framesText + "')");
  const std::string clampText = args["glossy-clamp"].as<std::string>();
  float glossyClamp = 0.0f;
  if (!wholeNumber(clampText, glossyClamp) || !(glossyClamp > 0.0f) || !std::isfinite(glossyClamp))
    throw std::runtime_error("--glossy-clamp expects a finite luminance > 0 (got '" + clampText + "')");
  std::vector<std::string> glossyScenes = {"glossy", "mirror-room@rough0.25", "curved-mirror@rough0.3",
                                           "facing-mirror@rough0.3", "bright-emitter"};
  if (args.count("glossy-scenes")) {
    glossyScenes = uniqueItems(args["glossy-scenes"].as<std::string>(), "glossy-scenes");
    for (const std::string& s : glossyScenes)
      if (auto check = loadGlossyScene(s); !check) throw std::runtime_error("--glossy-scenes: " + check.error());
  }
  bool glossy = bo.grid == "full" || args.count("glossy") || args.count("glossy-scenes");
  if (args.count("no-glossy")) glossy = false;
  if (glossy) {
    std::tie(bo.glossyWidth, bo.glossyHeight) = glossySize;
    bo.glossySamples = glossySamples;
    bo.glossyFrames = glossyFrames;
    bo.glossyClampLuminance = glossyClamp;
    bo.glossyScenes = glossyScenes;
  }

  const auto temporalSize = parseSizeOption(args["temporal-size"].as<std::string>(), "temporal-size", 8, 4096);
  std::vector<std::string> temporalScenes = {"mirror-room", "curved-mirror", "glossy"};
  if (args.count("temporal-scenes")) {
    temporalScenes = uniqueItems(args["temporal-scenes"].as<std::string>(), "temporal-scenes");
    for (const std::string& s : temporalScenes)
      if (auto check = loadScene(s); !check) throw std::runtime_error("--temporal-scenes: " + check.error());
  }
  bool temporal = bo.grid == "full" || args.count("temporal") || args.count("temporal-scenes");
  if (args.count("no-temporal")) temporal = false;
  if (temporal) {
    std::tie(bo.temporalWidth, bo.temporalHeight) = temporalSize;
    bo.temporalScenes = temporalScenes;
  }

  parseViewsStudy(args, bo);
}

// The output directory, checked before any GL work: a typo or a read-only place costs no run.
void checkOutputDirectory(const std::string& outDir) {
  if (Status s = prepareOutputDirectory(outDir); !s) throw std::runtime_error("--out " + s.message());
  const std::string report = (std::filesystem::path(outDir) / "report").string();
  if (Status s = prepareOutputDirectory(report); !s) throw std::runtime_error("--out: " + s.message());
  for (const char* file : {"results.json", "results.csv", "report/index.html"})
    if (Status s = checkReplaceable((std::filesystem::path(outDir) / file).string()); !s)
      throw std::runtime_error("--out: " + s.message());
}

// The defaults per scene (with --configs: every configuration run), times as ratios to the
// tutorial's configuration. The method column fits the longest name shown.
void printRuns(const BenchResult& result, const BenchOptions& bo) {
  int nameWidth = 16;
  if (!bo.configs.empty())
    for (const RunRecord& r : result.runs) nameWidth = std::max(nameWidth, static_cast<int>(r.method.size() + 1 + r.label.size()));
  std::printf("%-14s %-*s %9s %8s %8s %8s %8s %9s %9s %9s %6s\n", "scene", nameWidth, "method", "time ms", "ratio",
              "rec@1px", "p95 px", "false", "fetch/px", "disp/barr", "simt32", "chain");
  for (const auto& sc : result.scenes) {
    const SceneDefaults defaults = defaultRuns(result, sc.scene);
    const RunRecord* p = defaults.tutorial;
    std::vector<const RunRecord*> shown = defaults.runs;
    if (!bo.configs.empty()) {
      shown.clear();
      for (const RunRecord& r : result.runs)
        if (r.scene == sc.scene && r.method != "baseline") shown.push_back(&r);
    }
    for (const RunRecord* r : shown)
      std::printf("%-14s %-*s %9.2f %8s %8.4f %8.3f %8.4f %9.1f %5u/%-3u %9llu %6u\n", sc.scene.c_str(), nameWidth,
                  (bo.configs.empty() ? r->method : r->method + "/" + r->label).c_str(), r->timeMedianMs,
                  p ? std::to_string(r->timeMedianMs / p->timeMedianMs).substr(0, 4).c_str() : "-", r->metrics.recall1px,
                  r->metrics.p95ErrorPx, r->metrics.falseHitRate, r->fetchesPerTracedPixel,
                  r->commands.dispatches + r->commands.indirectDispatches, r->commands.barriers,
                  static_cast<unsigned long long>(r->frameStats.totalRayWork().simt32),
                  r->frameStats.totalRayWork().longestChain);
  }
}

// The fastest configuration of each method reaching kParetoRecall, as a ratio to adaptive L's.
void printFastest(const BenchResult& result) {
  std::printf("\nfastest configuration per method reaching recall@1px >= %.2f (ratio to adaptive-l's):\n", kParetoRecall);
  for (const auto& sc : result.scenes) {
    const auto fastest = fastestReaching(result, sc.scene, kParetoRecall);
    const RunRecord* ours = nullptr;
    for (const FastestRun& f : fastest)
      if (f.method == "adaptive-l") ours = f.run;
    for (const FastestRun& f : fastest) {
      if (!f.run) {
        std::printf("%-14s %-16s none reaches it\n", sc.scene.c_str(), f.method.c_str());
        continue;
      }
      const std::string ratio = ours ? std::to_string(f.run->timeMedianMs / ours->timeMedianMs).substr(0, 4) : "-";
      std::printf("%-14s %-16s %9.2f %8s %8.4f  %s\n", sc.scene.c_str(), f.method.c_str(), f.run->timeMedianMs,
                  ratio.c_str(), f.run->metrics.recall1px, f.run->label.c_str());
    }
  }
}

// The cost curves, each point as a ratio to the baseline pass at the same point; the temporal study.
void printStudies(const BenchResult& result, const BenchOptions& bo) {
  for (const char* curve : {"resolution", "fraction"}) {
    bool header = false;
    for (const CurvePoint& p : result.curves) {
      if (p.curve != curve || p.method == "baseline") continue;
      if (!header) std::printf("\ncost against %s (median ms; ratio to the baseline pass):\n", curve);
      header = true;
      double base = 0;
      for (const CurvePoint& q : result.curves)
        if (q.curve == p.curve && q.method == "baseline" && q.width == p.width && q.height == p.height &&
            q.percent == p.percent)
          base = q.timeMedianMs;
      const std::string point = p.percent >= 0 ? "reflective-" + std::to_string(p.percent)
                                               : std::to_string(p.width) + "x" + std::to_string(p.height);
      std::printf("  %-16s %-15s traced %6.4f %9.2f ms  %6.2fx baseline\n", p.method.c_str(), point.c_str(),
                  p.tracedFraction, p.timeMedianMs, base > 0 ? p.timeMedianMs / base : 0.0);
    }
  }
  if (!result.glossy.empty()) {
    std::printf("\nglossy study (%dx%d, %d reference rays a pixel, scored after %d still frames; Radiance output "
                "against the GGX lobe's radiance; rmse@1: after the first frame):\n",
                bo.glossyWidth, bo.glossyHeight, bo.glossySamples, bo.glossyFrames);
    std::printf("  %-24s %-27s %8s %8s %8s %9s %9s %8s %10s %8s %9s\n", "scene", "configuration", "ms", "rmse",
                "rmse@1", "> noise", "relative", "display", "no estim.", "scored", "ref noise");
    for (const GlossyPoint& p : result.glossy)
      std::printf("  %-24s %-27s %8.2f %8.4f %8.4f %9.4f %9.3f %8.4f %10.3f %8zu %9.4f\n", p.scene.c_str(),
                  p.config.c_str(), p.timeMedianMs, p.rmse, p.rmseByFrame.empty() ? 0.0 : p.rmseByFrame.front(),
                  p.rmseAboveNoise, p.relativeRmse, p.displayRmse, p.uncovered, p.scored, p.referenceNoise);
  }
  if (!result.views.empty()) {
    std::printf("\nviews study (%dx%d, %d eyes; median ms of a frame of every eye it traces; ratio to one view, the "
                "median of each round's; a frame's commands):\n",
                bo.viewsWidth, bo.viewsHeight, bo.viewsCount);
    std::printf("  %-12s %-26s %9s %7s %10s %8s %8s %8s %8s %10s\n", "scene", "configuration", "ms", "ratio",
                "dispatches", "indirect", "barriers", "programs", "uploads", "traced px");
    for (const ViewsPoint& p : result.views) {
      std::printf("  %-12s %-26s %9.2f %6.2fx %10u %8u %8u %8u %8u %10llu\n", p.scene.c_str(), p.config.c_str(),
                  p.timeMedianMs, p.ratioToOneView, p.commands.dispatches,
                  p.commands.indirectDispatches, p.commands.barriers, p.commands.programs, p.commands.uploads,
                  static_cast<unsigned long long>(p.tracedPixels));
    }
  }
  if (result.temporal.empty()) return;
  std::printf("\ntemporal study (%dx%d; RMSE against the ideal reflection; still = its last 4 frames):\n",
              bo.temporalWidth, bo.temporalHeight);
  std::printf("  %-14s %-22s %-6s %8s %8s %8s %8s\n", "scene", "configuration", "segment", "rmse", "rmse A", "rmse B-D",
              "ms");
  for (const TemporalSummary& t : summarizeTemporal(result.temporal))
    std::printf("  %-14s %-22s %-6s %8.4f %8.4f %8.4f %8.2f\n", t.scene.c_str(), t.config.c_str(), t.segment.c_str(),
                t.rmse, t.rmseVisible, t.rmseHidden, t.dispatchMs);
}

}  // namespace

int main(int argc, char** argv) {
  removeTemporariesOnSignal();
  cxxopts::Options options = benchOptions();
  BenchOptions bo;
  std::string outDir, device;
  try {
    auto args = options.parse(argc, argv);
    if (args.count("help")) {
      std::cout << options.help() << "\nquick: 320x180, 7 frames; full: 960x540, 15 frames (defaults, overridable).\n";
      return 0;
    }
    if (!args.unmatched().empty()) throw std::runtime_error("unexpected argument '" + args.unmatched().front() + "'");
    parseGrid(args, bo);
    parseStudies(args, bo);
    outDir = args["out"].as<std::string>();
    device = args["device"].as<std::string>();
    if (Status st = HeadlessContext::checkDevice(device); !st) throw std::runtime_error("--device: " + st.message());
    checkOutputDirectory(outDir);
  } catch (const std::exception& e) {
    std::cerr << "sslr-bench: " << e.what() << "\n";
    return 2;
  }
  EglOptions eo;
  eo.device = device;
  eo.debug = false;  // timing: no synchronous debug output
  auto gl = HeadlessContext::create(eo);
  if (!gl) {
    std::cerr << "sslr-bench: cannot create an OpenGL 4.5 context: " << gl.error() << "\n";
    return 1;
  }
  const std::string renderer = gl.value()->renderer() + " | " + gl.value()->version();
  Progress progress;
  auto result = runBenchmark(bo, gl.value()->isSoftware(), renderer, outDir + "/report",
                             [&](int d, int t, const std::string& w) { progress(d, t, w); });
  progress.finish();
  if (!result) {
    std::cerr << "sslr-bench: " << result.error() << "\n";
    return 1;
  }
  if (Status s = writeBenchResults(result.value(), outDir); !s) {
    std::cerr << "sslr-bench: " << s.message() << "\n";
    return s.code() == StatusCode::InvalidInput ? 2 : 1;  // a target that is no regular file: refused
  }
  printRuns(result.value(), bo);
  printFastest(result.value());
  printStudies(result.value(), bo);
  for (const SceneRecord& sr : result.value().scenes)
    if (sr.showsNothing)
      std::fprintf(stderr, "sslr-bench: warning: no pixel of the %dx%d frame shows %s: the geometry projects to nothing "
                   "from its camera (a zero or tiny scale, degenerate triangles, or a camera looking away); its rows "
                   "score the background alone\n", bo.width, bo.height, sr.scene.c_str());
  std::printf("timing: %s on %s\nwrote %s/results.json, %s/results.csv, %s/report/index.html\n",
              result.value().timingMethod.c_str(), renderer.c_str(), outDir.c_str(), outDir.c_str(), outDir.c_str());
  return 0;
}
