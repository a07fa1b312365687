// sslr-render as a user runs it: help, exit codes, messages, files written (or not).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <csignal>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "common/gltf_writer.hpp"
#include "common/shell.hpp"
#include "gl/gl_fixture.hpp"
#include "sslr_host/ground_truth.hpp"
#include "sslr_host/image_io.hpp"

namespace fs = std::filesystem;

namespace {

using Result = sslr::test::ShellResult;

// `prefix` runs before the program in the same shell (limits, traps).
Result run(const std::string& args, const std::string& prefix = "") {
  return sslr::test::runShell(prefix.empty() ? std::string(SSLR_RENDER_EXE) + " " + args
                                             : "bash -c '" + prefix + "; exec " + std::string(SSLR_RENDER_EXE) +
                                                   " " + args + "'");
}

fs::path freshDir(const std::string& name) {
  const fs::path p = fs::path(SSLR_TEST_TMP) / "cli" / name;
  fs::remove_all(p);
  return p;
}

class RenderCli : public sslr::test::GlTest {};

TEST(RenderCliNoGl, HelpExitsZero) {
  const Result r = run("--help");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.output.find("--scene"), std::string::npos);
  EXPECT_NE(r.output.find("--dump"), std::string::npos);
}

TEST(RenderCliNoGl, BadArgumentsExitTwoWithAMessageAndWriteNothing) {
  const struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"--size 10by10", "--size expects WxH"},
      {"--size 0x10", "--size expects WxH"},
      {"--scene no-such-scene", "unknown scene 'no-such-scene'"},
      {"--scene /nonexistent/file.gltf", "/nonexistent/file.gltf: file not found"},
      {"--preset extreme", "--preset must be"},
      {"--depth sideways", "--depth must be"},
      {"--eye 1,2", "--eye expects three finite numbers"},
      {"--fovy -5", "--fovy expects a positive number"},
      {"--eye 0,1,0 --target 0,1,0", "camera eye and target coincide"},
      {"--near 10 --far 1", "far plane must be"},
      {"--iterations 0", "adaptiveL.maxIterations"},
      {"--iterations abc", "iterations"},
      {"--hiz-steps 1025", "traversal.maxSteps"},
      {"--method hiz --hiz-steps 0", "for Method::HierarchicalDepth"},
      {"--hidden-guess 2", "traversal.hiddenGuess"},
      {"--method dda --dda-stride 0.5", "dda.stride"},
      {"--method dda --dda-stride wide", "--dda-stride expects a number"},
      {"--method dda --dda-thickness -1", "dda.objectDepth"},
      {"--max-luminance -1", "radianceClamp.maxLuminance"},
      {"--max-luminance bright", "--max-luminance expects a number"},
      {"--hiz-steps many", "--hiz-steps expects an integer"},
      {"--traversal-pass sideways", "--traversal-pass must be"},
      {"--hidden-guess far", "--hidden-guess expects a number"},
      {"--error-k -1", "fades.errorK"},
      {"--error-k strong", "--error-k expects a number"},
      {"--stage sideways", "--stage must be on-mirror or as-mirror"},
      {"--no-such-option", "no-such-option"},
      {"--method raymarch", "--method must be"},
      // Checked before any GL work (they used to exit 1 after starting GL, or render nothing).
      {"--fovy 1e-320", "vertical field of view must be in [0.001, 180)"},
      {"--near 1e-300 --far 1e300", "near plane must be >= 1e-20"},
      {"--near 1e-3 --far 1e7", "far / near is above 1e9"},
      {"--near 1 --far 1.0000001", "near and far planes are too close"},
      {"--device bogus", "--device: EGL device 'bogus' is not one of"},
      {"--device 99", "--device: EGL device index 99 is out of range"},
      {"--views 0", "--views must be 1..4"},
      {"--views 5", "--views must be 1..4"},
      {"--views two", "--views must be 1..4"},
      {"--eye-separation 0.1", "--eye-separation needs --views 2 or more"},
      {"--views 2 --eye-separation -1", "--eye-separation expects a positive number"},
      {"--views 2 --dump", "--dump and --score need one view"},
      {"--views 2 --score", "--dump and --score need one view"},
      {"--views 2 --eye-separation 1e16", "--eye-separation 1e+16: an eye's camera: camera eye/target lie"},
      {"--hidden-guess nan", "traversal.hiddenGuess = nan"},
  };
  for (const auto& c : cases) {
    const fs::path out = freshDir("bad");
    const Result r = run(std::string(c.args) + " --out " + out.string());
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args << ": nothing may be written";
  }
}

TEST_F(RenderCli, MalformedGltfExitsTwoAndWritesNothing) {
  const fs::path dir = fs::path(SSLR_TEST_TMP) / "cli";
  fs::create_directories(dir);
  const fs::path bad = dir / "broken.gltf";
  std::ofstream(bad) << R"({"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":5}}]}],)"
                     << R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
  const fs::path out = freshDir("broken");
  const Result r = run("--scene " + bad.string() + " --out " + out.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(bad.string()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(RenderCli, DumpWritesEveryNamedBuffer) {
  const fs::path out = freshDir("dump");
  const Result r = run("--size 64x40 --dump --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* name : {"final.png", "color.exr", "normal.exr", "depth.exr", "position.exr", "hit.exr",
                           "reflection.exr", "iterations.exr", "resolved.exr"}) {
    ASSERT_TRUE(fs::exists(out / name)) << name;
    auto img = sslr::host::readImage((out / name).string());
    ASSERT_TRUE(img) << img.error();
    EXPECT_EQ(img.value().width, 64) << name;
    EXPECT_EQ(img.value().height, 40) << name;
    if (std::string(name) != "final.png") EXPECT_EQ(sslr::host::countNonFinite(img.value()), 0u) << name;
  }
  // hit.exr: uv in [0,1] and confidence in [0,1]; some pixels must have hits on the default scene.
  auto hit = sslr::host::readImage((out / "hit.exr").string());
  size_t hits = 0;
  for (size_t p = 0; p < hit.value().pixels.size() / 4; ++p) {
    const float* h = &hit.value().pixels[p * 4];
    ASSERT_GE(h[2], 0.0f);
    ASSERT_LE(h[2], 1.0f);
    if (h[2] > 0.0f) {
      ++hits;
      ASSERT_GE(h[0], 0.0f);
      ASSERT_LE(h[0], 1.0f);
    }
  }
  EXPECT_GT(hits, 100u);
  // The position-buffer comparison method renders through the same pipeline.
  const fs::path pb = freshDir("pb");
  const Result r3 = run("--size 48x32 --method position-buffer --out " + pb.string());
  ASSERT_EQ(r3.exitCode, 0) << r3.output;
  EXPECT_TRUE(fs::exists(pb / "final.png"));
  // Without reflections the reflection buffers are not written.
  const fs::path plain = freshDir("plain");
  const Result r2 = run("--size 32x20 --method none --dump --out " + plain.string());
  ASSERT_EQ(r2.exitCode, 0) << r2.output;
  EXPECT_TRUE(fs::exists(plain / "depth.exr"));
  EXPECT_FALSE(fs::exists(plain / "hit.exr"));
}

// --out naming a dangling link, and --export-gltf naming a directory or a file in no directory:
// bad arguments (exit 2) that say what is wrong, before any work.
TEST(RenderCliNoGl, OutputPathsThatCannotBeUsedAreBadArguments) {
  const fs::path dir = fs::path(SSLR_TEST_TMP) / "cli-paths";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path dangling = dir / "dangling";
  fs::create_symlink(dir / "no-such-target", dangling);
  Result r = run("--size 32x20 --out " + dangling.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("is a link to"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("which does not exist"), std::string::npos) << r.output;
  r = run("--export-gltf /");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--export-gltf / is a directory"), std::string::npos) << r.output;
  r = run("--export-gltf " + (dir / "missing" / "scene.gltf").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("does not exist"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "missing"));
}

// A 34 KB glTF whose 585 primitives share one 65k-vertex grid in a 2.4 MB .bin (triangles, or a
// strip that expands to 3 indices a triangle): every copy the tools would make is budgeted from the
// accessors, so the file is refused (exit 2, the limit named) before any is made. It once reached
// 4.6 GB resident and died of std::bad_alloc.
TEST(RenderCliNoGl, ASmallFileOfSharedGeometryIsRefusedByItsBudget) {
  const fs::path dir = fs::path(SSLR_TEST_TMP) / "cli-geometry-budget";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const int n = 256;
  std::vector<float> pos;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) pos.insert(pos.end(), {x / float(n - 1), 0.0f, y / float(n - 1)});
  for (const bool strip : {false, true}) {
    std::vector<std::uint32_t> idx;
    if (strip) {
      for (std::uint32_t i = 0; i < std::uint32_t(n * n); ++i) idx.push_back(i);
    } else {
      for (int y = 0; y + 1 < n; ++y)
        for (int x = 0; x + 1 < n; ++x) {
          const std::uint32_t a = std::uint32_t(y * n + x);
          idx.insert(idx.end(), {a, a + n, a + 1, a + 1, a + n, a + n + 1});
        }
    }
    const std::string name = strip ? "strip" : "triangles";
    const std::string bytes = sslr::test::bytesOf(pos) + sslr::test::bytesOf(idx);
    { std::ofstream(dir / (name + ".bin"), std::ios::binary) << bytes; }
    std::ostringstream j;
    j << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[)";
    for (int p = 0; p < 585; ++p)
      j << (p ? "," : "") << R"({"attributes":{"POSITION":0},"indices":1,"mode":)" << (strip ? 5 : 4) << "}";
    j << R"(]}],"buffers":[{"byteLength":)" << bytes.size() << R"(,"uri":")" << name << R"(.bin"}],)"
      << R"("bufferViews":[{"buffer":0,"byteLength":)" << pos.size() * 4 << R"(},{"buffer":0,"byteOffset":)"
      << pos.size() * 4 << R"(,"byteLength":)" << idx.size() * 4 << R"(}],"accessors":[{"bufferView":0,)"
      << R"("componentType":5126,"count":)" << n * n << R"(,"type":"VEC3","min":[0,0,0],"max":[1,0,1]},)"
      << R"({"bufferView":1,"componentType":5125,"count":)" << idx.size() << R"(,"type":"SCALAR"}]})";
    const fs::path file = dir / (name + ".gltf");
    { std::ofstream(file) << j.str(); }
    const Result r = run("--scene " + file.string() + " --size 64x36 --out " + (dir / "out").string());
    EXPECT_EQ(r.exitCode, 2) << name << ": " << r.output;
    EXPECT_NE(r.output.find("the tools load up to 1280 MiB"), std::string::npos) << name << ": " << r.output;
  }
  struct rusage children {};
  ::getrusage(RUSAGE_CHILDREN, &children);
  EXPECT_LT(children.ru_maxrss, 2L << 20) << "KiB: the largest child's peak must stay under 2 GiB";
}

TEST(RenderCliNoGl, OutputThatCannotBeWrittenIsRefusedBeforeRendering) {
  const fs::path dir = fs::path(SSLR_TEST_TMP) / "cli";
  fs::create_directories(dir);
  const fs::path file = dir / "not-a-directory";
  std::ofstream(file) << "x";
  Result r = run("--size 32x20 --out " + file.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("exists and is not a directory"), std::string::npos) << r.output;
  r = run("--size 32x20 --out /proc/sslr-no-such-place/out");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("cannot create the directory"), std::string::npos) << r.output;
}

TEST_F(RenderCli, FailedWritesExitOneAndLeaveNothing) {
  // A file size limit makes every write past 4 KiB fail as a full disk would (SIGXFSZ ignored:
  // the write returns EFBIG). Nothing partial may be left behind, and the exit code says so.
  const fs::path out = freshDir("full");
  const Result r = run("--size 160x90 --dump --out " + out.string(), "trap \"\" XFSZ; ulimit -f 8");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("write failed"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::is_directory(out));
  EXPECT_TRUE(fs::is_empty(out)) << "no partial or temporary file may remain";
}

TEST_F(RenderCli, ASignalDuringWritingLeavesNoTemporary) {
  // The same limit with SIGXFSZ left to its default: the signal ends the process in the middle of a
  // write. Its handler removes the temporaries before the process ends as the signal says.
  const fs::path out = freshDir("killed");
  const Result r = run("--size 160x90 --dump --out " + out.string(), "ulimit -f 8");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.exitCode, 1) << "killed by the signal, not a reported failure: " << r.output;
  ASSERT_TRUE(fs::is_directory(out));
  EXPECT_TRUE(fs::is_empty(out)) << "no partial or temporary file may remain";
}

// SIGINT or SIGTERM sent the moment a temporary appears (llvmpipe's threads are running, and the
// writer may be between creating a temporary and finishing it): 20 runs, and none may leave a
// temporary. The signal thread removes them while no writer can create or rename one.
TEST_F(RenderCli, ASignalTheMomentATemporaryAppearsLeavesNone) {
  int signalled = 0;
  for (int runIndex = 0; runIndex < 20; ++runIndex) {
    const fs::path out = freshDir("race-" + std::to_string(runIndex));
    fs::create_directories(out);
    const std::string outArg = out.string();
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      const int devnull = ::open("/dev/null", O_WRONLY);
      ::dup2(devnull, 1);
      ::dup2(devnull, 2);
      ::execl(SSLR_RENDER_EXE, SSLR_RENDER_EXE, "--size", "256x144", "--dump", "--out", outArg.c_str(),
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
    const int sig = runIndex % 2 == 0 ? SIGINT : SIGTERM;
    bool sent = false;
    int status = 0;
    // Bounded by the child's own end: it writes its files and exits if no temporary is seen.
    while (::waitpid(pid, &status, WNOHANG) == 0) {
      std::error_code ec;
      for (const auto& entry : fs::directory_iterator(out, ec)) {
        const std::string name = entry.path().filename().string();
        // (The start-up probe of --out is a temporary too, written before any other thread runs.)
        if (!sent && name.ends_with(".partial") && name.find("sslr-write-probe") == std::string::npos) {
          ::kill(pid, sig);
          sent = true;
        }
      }
    }
    if (sent && WIFSIGNALED(status)) {
      ++signalled;
      EXPECT_EQ(WTERMSIG(status), sig) << "run " << runIndex << " ends as the signal says";
    } else {
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "run " << runIndex << ": status " << status;
    }
    for (const auto& entry : fs::directory_iterator(out))
      EXPECT_FALSE(entry.path().filename().string().ends_with(".partial"))
          << "run " << runIndex << " left " << entry.path();
  }
  // How many signals land mid-write depends on the machine's speed (4 of 20 under ASan, 13 in a
  // release build): at least one must, or the race was not tried.
  EXPECT_GE(signalled, 1) << "no run was interrupted while writing";
}

TEST_F(RenderCli, ScoreAndHierarchicalMethod) {
  const fs::path out = freshDir("score");
  const Result r = run("--size 96x54 --scene facing-mirror --method hiz --score --stats --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("recall@1px"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("hierarchical traversal on"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "error.png"));
}

// --score --dump writes the truth beside hit.exr; recomputing the recall from the two files must
// give the printed one (the files are what a user inspects a score with).
TEST_F(RenderCli, ScoreWithDumpWritesTheTruthTheRecallComesFrom) {
  const fs::path out = freshDir("score-dump");
  const Result r = run("--size 96x54 --scene mirror-walls --score --dump --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto truth = sslr::host::readImage((out / "truth.exr").string());
  auto hit = sslr::host::readImage((out / "hit.exr").string());
  ASSERT_TRUE(truth) << truth.error();
  ASSERT_TRUE(hit) << hit.error();
  ASSERT_EQ(truth.value().channels, 4);
  ASSERT_EQ(truth.value().width, 96);
  ASSERT_EQ(truth.value().height, 54);
  size_t visible = 0, found = 0;
  for (int y = 0; y < 54; ++y)
    for (int x = 0; x < 96; ++x) {
      const float cls = truth.value().at(x, y, 2);
      ASSERT_TRUE(cls == 0.0f || cls == 1.0f || cls == 2.0f || cls == 3.0f || cls == 4.0f) << cls;
      ASSERT_TRUE(truth.value().at(x, y, 3) == 0.0f || truth.value().at(x, y, 3) == 1.0f);
      if (cls != 1.0f) continue;
      ++visible;
      const glm::vec2 errPx = (glm::vec2(hit.value().at(x, y, 0), hit.value().at(x, y, 1)) -
                               glm::vec2(truth.value().at(x, y, 0), truth.value().at(x, y, 1))) *
                              glm::vec2(96.0f, 54.0f);
      if (hit.value().at(x, y, 2) > sslr::host::kReportedConfidence && glm::length(errPx) <= 1.0f) ++found;
    }
  ASSERT_GT(visible, 100u);
  const size_t at = r.output.find("recall@1px ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const double printed = std::stod(r.output.substr(at + 11));
  EXPECT_NEAR(double(found) / double(visible), printed, 1e-4) << r.output;
  // Without --dump, no truth file.
  const fs::path plain = freshDir("score-only");
  ASSERT_EQ(run("--size 48x32 --scene mirror-walls --score --out " + plain.string()).exitCode, 0);
  EXPECT_FALSE(fs::exists(plain / "truth.exr"));
}

// ... and the two images the composite error compares (reference.exr, final.exr: linear RGB, A = 1 on
// the compared pixels); the RMSE recomputed from them must be the printed one.
TEST_F(RenderCli, ScoreWithDumpWritesTheImagesTheCompositeErrorComesFrom) {
  const fs::path out = freshDir("score-dump-composite");
  const Result r = run("--size 96x54 --scene mirror-walls --score --dump --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto reference = sslr::host::readImage((out / "reference.exr").string());
  auto shown = sslr::host::readImage((out / "final.exr").string());
  ASSERT_TRUE(reference) << reference.error();
  ASSERT_TRUE(shown) << shown.error();
  ASSERT_EQ(reference.value().channels, 4);
  ASSERT_EQ(shown.value().channels, 4);
  ASSERT_EQ(reference.value().width, 96);
  ASSERT_EQ(shown.value().height, 54);
  double squared = 0.0;
  size_t compared = 0;
  for (int y = 0; y < 54; ++y)
    for (int x = 0; x < 96; ++x) {
      const float a = reference.value().at(x, y, 3);
      ASSERT_TRUE(a == 0.0f || a == 1.0f) << a;
      ASSERT_EQ(shown.value().at(x, y, 3), a);
      if (a == 0.0f) continue;
      ++compared;
      for (int c = 0; c < 3; ++c) {
        const double d = double(shown.value().at(x, y, c)) - double(reference.value().at(x, y, c));
        squared += d * d;
      }
    }
  ASSERT_GT(compared, 100u);
  const std::string label = "against the ray-traced reference: RMSE ";
  const size_t at = r.output.find(label);
  ASSERT_NE(at, std::string::npos) << r.output;
  const double printed = std::stod(r.output.substr(at + label.size()));
  // 1e-4: the printed value has four decimals.
  EXPECT_NEAR(std::sqrt(squared / double(3 * compared)), printed, 1e-4) << r.output;
  EXPECT_NE(r.output.find("over " + std::to_string(compared) + " mirror pixels"), std::string::npos) << r.output;
}

TEST_F(RenderCli, EveryBuiltinSceneAndDepthConventionRenders) {
  for (const char* scene : {"mirror-room", "grazing-plane", "thin-objects", "sky-heavy", "facing-mirror",
                            "mirror-walls", "curved-mirror", "glossy"})
    for (const char* depth : {"reversed", "gl-default"}) {
      const fs::path out = freshDir(std::string(scene) + depth);
      const Result r = run(std::string("--size 48x32 --scene ") + scene + " --depth " + depth + " --out " + out.string());
      EXPECT_EQ(r.exitCode, 0) << scene << " " << depth << "\n" << r.output;
      EXPECT_TRUE(fs::exists(out / "final.png"));
    }
}

// ---- Cameras and extents (issue: defects a new user hit) ------------------------------------

// Two triangles of a 0.2-unit quad facing +z at the origin, plus `extra` vertices (unused unless
// `useExtra`).
std::string smallQuad(const std::vector<float>& extra = {}, bool useExtra = false) {
  std::vector<float> p = {-0.1f, -0.1f, 0, 0.1f, -0.1f, 0, 0.1f, 0.1f, 0, -0.1f, 0.1f, 0};
  p.insert(p.end(), extra.begin(), extra.end());
  std::vector<std::uint16_t> idx = {0, 1, 2, 0, 2, 3};
  if (useExtra) idx.insert(idx.end(), {0, 1, 4});
  return sslr::test::meshGltf(p, idx);
}

fs::path writeModel(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(SSLR_TEST_TMP) / "cli";
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << text;
  return dir / name;
}

// Share of pixels that differ from the corner pixel: 0 for a uniform (empty) picture.
double coverage(const fs::path& png) {
  auto img = sslr::host::readImage(png.string());
  if (!img) return -1.0;
  const auto& px = img.value().pixels;
  const int c = img.value().channels;
  size_t differ = 0, n = px.size() / c;
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      if (std::abs(px[i * c + k] - px[k]) > 0.02f) {
        ++differ;
        break;
      }
  return double(differ) / n;
}

// --views 2: one context traces both eyes; each view's final image is its own eye's frame, so the
// two differ by the eyes' parallax and both hold the reflection.
TEST_F(RenderCli, ViewsWriteEachViewsFinalImage) {
  const fs::path out = freshDir("views");
  const Result r = run("--scene mirror-room --size 96x64 --views 2 --eye-separation 0.3 --stats --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("2 views of 96x64"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("frame 2 + 7 / 9 / 9"), std::string::npos) << r.output;  // one view's commands
  EXPECT_FALSE(fs::exists(out / "final.png"));
  auto left = sslr::host::readImage((out / "final-view0.png").string());
  auto right = sslr::host::readImage((out / "final-view1.png").string());
  ASSERT_TRUE(left && right);
  ASSERT_EQ(left.value().pixels.size(), right.value().pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < left.value().pixels.size(); ++i)
    differing += std::abs(left.value().pixels[i] - right.value().pixels[i]) > 0.02f;
  EXPECT_GT(differing, left.value().pixels.size() / 20) << "the eyes see the room from 0.3 apart";
}

TEST_F(RenderCli, MovedCameraFitsItsClipPlanes) {
  // The default camera of a 0.2-unit quad framed from a larger model would keep a near plane
  // far beyond a close eye; the planes follow the new eye.
  const fs::path model = writeModel("small.gltf", smallQuad({0, 0, -50}, true));
  const fs::path out = freshDir("close");
  const Result r = run("--scene " + model.string() + " --eye 0,0,0.3 --target 0,0,0 --size 48x32 --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_GT(coverage(out / "final.png"), 0.3) << "the quad fills most of the view";
}

TEST_F(RenderCli, UnusedFarVertexDoesNotMoveTheFraming) {
  const fs::path model = writeModel("stray.gltf", smallQuad({1e30f, 0, 0}, false));
  const fs::path out = freshDir("stray");
  const Result r = run("--scene " + model.string() + " --size 48x32 --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_GT(coverage(out / "final.png"), 0.05) << "the quad is framed, not the unused vertex";
}

TEST(RenderCliNoGl, AbsurdExtentsAndCamerasAreRefused) {
  // A used vertex at 3e9 units: float rasterization turns it into NaN; refused with the reason.
  const fs::path far = writeModel("far.gltf", smallQuad({3e9f, 0, 0}, true));
  Result r = run("--scene " + far.string() + " --out " + freshDir("far").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("lose all precision"), std::string::npos) << r.output;
  r = run("--eye 1e300,0,0 --out " + freshDir("eye").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("1e+300 units from the origin"), std::string::npos) << r.output;
}

// MemAvailable of /proc/meminfo, in KiB (0 where it cannot be read): what sslr-render's estimate
// is held against.
double availableMemoryKiB() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  while (meminfo >> key)
    if (key == "MemAvailable:" && meminfo >> kib) break;
  return kib;
}

TEST(RenderCliNoGl, SizeThatCannotFitInMemoryIsRefusedWithAnEstimate) {
  // 16384x16384 with --dump needs about 98 GiB (sslr-render's estimate); it is refused where
  // that exceeds 80% of the available memory, and rightly rendered where it does not.
  const double availableGiB = availableMemoryKiB() / (1024.0 * 1024.0);
  if (0.8 * availableGiB >= 98.0) GTEST_SKIP() << "this machine has " << availableGiB << " GiB available: 16384x16384 fits";
  const Result r = run("--size 16384x16384 --dump --out " + freshDir("huge").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("GiB"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(fs::path(SSLR_TEST_TMP) / "cli" / "huge"));
}

// --views N: every view has its own layer of every target and its own read-back image, so the
// estimate is N times one view's. A size of which one view would need a third of the available
// memory is refused for four views (that run once peaked at 2.8x one view's memory, unchecked).
TEST(RenderCliNoGl, ViewsCountInTheMemoryEstimate) {
  const double availableKiB = availableMemoryKiB();
  ASSERT_GT(availableKiB, 0.0);
  const double onePixel = 16.0 + 16.0 + 16.0 + 51.0 + 30.0;  // sslr-render's estimate per pixel and view
  const int side = static_cast<int>(std::sqrt(availableKiB * 1024.0 / 3.0 / onePixel));
  if (side > 16384) GTEST_SKIP() << "this machine has " << availableKiB / 1048576.0 << " GiB available";
  const std::string size = std::to_string(side) + "x" + std::to_string(side);
  const Result r = run("--size " + size + " --views 4 --out " + freshDir("huge-views").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--size " + size + " x 4 views needs about"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(fs::path(SSLR_TEST_TMP) / "cli" / "huge-views"));
}
}  // namespace

namespace {

// Regular files under `dir` (hidden ones too), by name.
std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_F(RenderCli, OutputsReplaceLinksInsteadOfWritingThroughThem) {
  // A link planted where an output goes (final.png) must be replaced by the output, and the file
  // it points to, outside --out, left as it was; no temporary is left behind.
  const fs::path out = freshDir("links");
  fs::create_directories(out);
  const fs::path outside = fs::path(SSLR_TEST_TMP) / "cli" / "outside-target";
  { std::ofstream(outside) << "not to be touched"; }
  fs::create_symlink(outside, out / "final.png");
  const Result r = run("--size 32x18 --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(outside);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "not to be touched");
  EXPECT_FALSE(fs::is_symlink(out / "final.png"));
  EXPECT_TRUE(fs::is_regular_file(out / "final.png"));
  EXPECT_EQ(filesIn(out), std::vector<std::string>{"final.png"});
}

// A target that exists and is not a regular file (a fifo; a link to a character device) is refused
// with exit 2 and left as it was: --export-gltf and --out's final image before any work, a dumped
// buffer when the files are written (all of them refused then, none replaced), sslr-bench's
// results before it runs.
TEST_F(RenderCli, OutputsThatAreNotRegularFilesAreRefusedAndKept) {
  const fs::path dir = freshDir("not-regular");
  fs::create_directories(dir / "out");
  const fs::path fifo = dir / "scene.gltf", device = dir / "null.gltf";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink("/dev/null", device);
  auto untouched = [](const fs::path& p) { return fs::is_fifo(fs::symlink_status(p)); };
  Result r = run("--export-gltf " + fifo.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(fifo.string() + " exists and is a fifo"), std::string::npos) << r.output;
  EXPECT_TRUE(untouched(fifo));
  r = run("--export-gltf " + device.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("is a character device"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_symlink(device));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // final.png a fifo: refused before rendering.
  ASSERT_EQ(::mkfifo((dir / "out" / "final.png").c_str(), 0600), 0);
  r = run("--size 32x18 --out " + (dir / "out").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("final.png exists and is a fifo"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("sslr-render: mirror-room"), std::string::npos) << "nothing may be rendered: " << r.output;
  EXPECT_TRUE(untouched(dir / "out" / "final.png"));
  // depth.exr a fifo: refused when written, and final.png (a regular file now) not written either.
  fs::remove(dir / "out" / "final.png");
  ASSERT_EQ(::mkfifo((dir / "out" / "depth.exr").c_str(), 0600), 0);
  r = run("--size 32x18 --dump --out " + (dir / "out").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_TRUE(untouched(dir / "out" / "depth.exr"));
  EXPECT_EQ(filesIn(dir / "out"), std::vector<std::string>{"depth.exr"}) << "nothing else written, no temporary left";
  // sslr-bench's results.csv a fifo: refused before any run.
  fs::create_directories(dir / "bench");
  ASSERT_EQ(::mkfifo((dir / "bench" / "results.csv").c_str(), 0600), 0);
  r = sslr::test::runShell(std::string(SSLR_BENCH_EXE) + " --scenes mirror-room --size 32x18 --out " +
                           (dir / "bench").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("results.csv exists and is a fifo"), std::string::npos) << r.output;
  EXPECT_TRUE(untouched(dir / "bench" / "results.csv"));
}

TEST_F(RenderCli, ConcurrentRunsIntoOneFolderAllSucceed) {
  // Temporary names are unique per process and write: runs sharing --out never collide.
  const fs::path out = freshDir("concurrent");
  const std::string cmd = std::string(SSLR_RENDER_EXE) + " --size 32x18 --dump --out " + out.string();
  for (int round = 0; round < 3; ++round) {
    const Result r = sslr::test::runShell("bash -c '(" + cmd + " >/dev/null 2>&1; echo A$?) & (" + cmd +
                                          " >/dev/null 2>&1; echo B$?) & wait'");
    EXPECT_NE(r.output.find("A0"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("B0"), std::string::npos) << r.output;
  }
  for (const std::string& name : filesIn(out)) EXPECT_NE(name[0], '.') << "a temporary was left: " << name;
}

TEST(RenderCliNoGl, BenchRefusesAnUnwritableOutBeforeRunning) {
  const fs::path file = fs::path(SSLR_TEST_TMP) / "cli" / "bench-out-is-a-file";
  fs::create_directories(file.parent_path());
  { std::ofstream(file) << "x"; }
  const Result r = sslr::test::runShell(std::string(SSLR_BENCH_EXE) + " --out " + file.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--out " + file.string()), std::string::npos) << r.output;
}

namespace {

// A unit box with a vertex per face corner (no normals: the loader computes them), drawn by a
// node with the given scale; positions multiplied by `positionScale`.
std::string scaledBoxGltf(const std::string& nodeScale, float positionScale) {
  std::vector<float> pos;
  std::vector<std::uint16_t> idx;
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-0.5f, 0.5f}) {
      const auto base = static_cast<std::uint16_t>(pos.size() / 3);
      for (int corner = 0; corner < 4; ++corner) {
        float p[3];
        p[axis] = side;
        p[(axis + 1) % 3] = (corner & 1) ? 0.5f : -0.5f;
        p[(axis + 2) % 3] = (corner & 2) ? 0.5f : -0.5f;
        for (float v : p) pos.push_back(v * positionScale);
      }
      for (int k : {0, 1, 2, 2, 1, 3}) idx.push_back(static_cast<std::uint16_t>(base + k));
    }
  std::string text = sslr::test::meshGltf(pos, idx);
  text.replace(text.find(R"("nodes":[{"mesh":0}])"), 20, R"("nodes":[{"mesh":0,"scale":)" + nodeScale + "}]");
  return text;
}

}  // namespace

// A model that shows nothing (scaled by 1e-30, a zero node scale, one degenerate triangle) still
// renders (the background is a valid picture), but says so; a model that shows is not warned of.
TEST_F(RenderCli, AModelThatShowsNothingIsSaid) {
  const std::string degenerate = sslr::test::meshGltf({0, 0, 0, 1, 0, 0, 2, 0, 0}, {0, 1, 2});
  for (const auto& [name, text] : {std::pair{"tiny", scaledBoxGltf("[1e-30,1e-30,1e-30]", 1.0f)},
                                   std::pair{"zero-scale", scaledBoxGltf("[0,0,0]", 1.0f)},
                                   std::pair{"degenerate", degenerate}, std::pair{"visible", scaledBoxGltf("[1,1,1]", 1.0f)}}) {
    const fs::path out = freshDir(std::string("nothing-") + name);
    fs::create_directories(out);
    const fs::path file = out / "scene.gltf";
    { std::ofstream(file) << text; }
    const Result r = run("--scene " + file.string() + " --size 48x32 --out " + out.string());
    if (r.exitCode == 2) {  // the loader may refuse a scene of nothing outright, with its reason
      EXPECT_NE(std::string(name), "visible") << r.output;
      continue;
    }
    ASSERT_EQ(r.exitCode, 0) << name << "\n" << r.output;
    const bool warned = r.output.find("warning: no pixel of the 48x32 frame shows") != std::string::npos;
    EXPECT_EQ(warned, std::string(name) != "visible") << name << "\n" << r.output;
  }
}

TEST_F(RenderCli, SingularNodeTransformsRenderFiniteColour) {
  // A node scale of [1,1,0] made the inverse-transpose normal matrix NaN: the object came out
  // black (NaN lit colour) with exit 0. So did 1e30 on 1e-30 positions (the matrix overflowed).
  for (const auto& [name, text] : {std::pair{"flat", scaledBoxGltf("[1,1,0]", 1.0f)},
                                   std::pair{"tiny-scaled-up", scaledBoxGltf("[1e30,1e30,1e30]", 1e-30f)}}) {
    const fs::path out = freshDir(std::string("singular-") + name);
    fs::create_directories(out);
    const fs::path file = out / "scene.gltf";
    { std::ofstream(file) << text; }
    const Result r = run("--scene " + file.string() + " --size 48x32 --dump --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << name << "\n" << r.output;
    auto color = sslr::host::readImage((out / "color.exr").string());
    auto normal = sslr::host::readImage((out / "normal.exr").string());
    ASSERT_TRUE(color && normal);
    EXPECT_EQ(sslr::host::countNonFinite(color.value()), 0u) << name;
    EXPECT_EQ(sslr::host::countNonFinite(normal.value()), 0u) << name;
    size_t lit = 0;
    for (size_t p = 0; p < color.value().pixels.size() / 4; ++p)
      lit += color.value().pixels[p * 4] + color.value().pixels[p * 4 + 1] + color.value().pixels[p * 4 + 2] > 0.05f;
    EXPECT_GT(lit, 48u * 32u / 10) << name << ": the object must be lit, not black";
  }
}
