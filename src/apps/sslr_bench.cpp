// sslr-bench: run time against error, depth-only adaptive L vs the position-buffer method, on
// every built-in scene, with Embree ground truth. Writes DIR/results.json, DIR/results.csv and
// DIR/report/index.html. Exit codes: 0 success, 1 failure, 2 bad arguments.
#include <unistd.h>

#include <cxxopts.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "sslr_host/benchmark.hpp"
#include "sslr_host/egl_context.hpp"

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

}  // namespace

int main(int argc, char** argv) {
  cxxopts::Options options("sslr-bench", "Run time against error: depth-only SSLR vs position-buffer SSR.");
  options.add_options()
      ("grid", "parameter grid: quick (CI) or full (docs)", cxxopts::value<std::string>()->default_value("quick"))
      ("scenes", "comma-separated scenes (default: mirror-room,grazing-plane,thin-objects,sky-heavy,facing-mirror,mirror-walls,curved-mirror,glossy)",
       cxxopts::value<std::string>()->default_value(""))
      ("size", "resolution WxH", cxxopts::value<std::string>())
      ("frames", "timed frames per configuration (median reported)", cxxopts::value<std::string>())
      ("warmup", "untimed warm-up rounds", cxxopts::value<std::string>())
      ("out", "output directory", cxxopts::value<std::string>()->default_value("bench-out"))
      ("device", "EGL device: auto, hardware, software, surfaceless or an index", cxxopts::value<std::string>()->default_value(""))
      ("h,help", "show this help");
  BenchOptions bo;
  std::string outDir, device;
  try {
    auto args = options.parse(argc, argv);
    if (args.count("help")) {
      std::cout << options.help() << "\nquick: 320x180, 7 frames; full: 960x540, 15 frames (defaults, overridable).\n";
      return 0;
    }
    if (!args.unmatched().empty()) throw std::runtime_error("unexpected argument '" + args.unmatched().front() + "'");
    bo.grid = args["grid"].as<std::string>();
    if (bo.grid != "quick" && bo.grid != "full") throw std::runtime_error("--grid must be quick or full");
    if (bo.grid == "full") {
      bo.width = 960;
      bo.height = 540;
      bo.frames = 15;
      bo.warmup = 2;
    }
    auto positiveInt = [&](const char* name, int& value, int lo, int hi) {
      if (!args.count(name)) return;
      std::istringstream in(args[name].as<std::string>());
      if (!(in >> value) || !in.eof() || value < lo || value > hi)
        throw std::runtime_error(std::string("--") + name + " expects an integer in " + std::to_string(lo) + ".." +
                                 std::to_string(hi));
    };
    positiveInt("frames", bo.frames, 1, 1000);
    positiveInt("warmup", bo.warmup, 0, 100);
    if (args.count("size")) {
      std::istringstream in(args["size"].as<std::string>());
      char x = 0;
      if (!(in >> bo.width >> x >> bo.height) || x != 'x' || !in.eof() || bo.width < 8 || bo.height < 8 ||
          bo.width > 8192 || bo.height > 8192)
        throw std::runtime_error("--size expects WxH with 8..8192 each");
    }
    std::stringstream scenes(args["scenes"].as<std::string>());
    for (std::string s; std::getline(scenes, s, ',');)
      if (!s.empty()) {
        auto check = loadScene(s);
        if (!check) throw std::runtime_error(check.error());
        bo.scenes.push_back(s);
      }
    outDir = args["out"].as<std::string>();
    device = args["device"].as<std::string>();
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
    return 1;
  }
  // A short summary on stdout: the defaults per scene.
  std::printf("%-14s %-16s %9s %8s %8s %8s %8s %9s\n", "scene", "method", "time ms", "ratio", "rec@1px", "p95 px",
              "false", "fetch/px");
  for (const auto& sc : result.value().scenes) {
    const SceneDefaults defaults = defaultRuns(result.value(), sc.scene);
    const RunRecord* p = defaults.tutorial;  // time ratios are to the tutorial's configuration
    for (const RunRecord* r : defaults.runs)
      std::printf("%-14s %-16s %9.2f %8.2f %8.4f %8.3f %8.4f %9.1f\n", sc.scene.c_str(), r->method.c_str(),
                  r->timeMedianMs, p ? r->timeMedianMs / p->timeMedianMs : 0.0, r->metrics.recall1px,
                  r->metrics.p95ErrorPx, r->metrics.falseHitRate, r->fetchesPerTracedPixel);
  }
  std::printf("timing: %s on %s\nwrote %s/results.json, %s/results.csv, %s/report/index.html\n",
              result.value().timingMethod.c_str(), renderer.c_str(), outDir.c_str(), outDir.c_str(), outDir.c_str());
  return 0;
}
