// sslr-view under Xvfb, as CI runs it: the window shows what sslr-render renders for the same
// camera, the panel is drawn, the error view and the split screen run, and the failures a user
// meets (no display, bad arguments) are clear errors.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>
#include <filesystem>
#include <map>
#include <regex>

#include "common/shell.hpp"
#include "gl/gl_fixture.hpp"
#include "sslr_host/image_io.hpp"

namespace fs = std::filesystem;
using namespace sslr::host;

namespace {

using Result = sslr::test::ShellResult;
Result sh(const std::string& cmd) { return sslr::test::runShell(cmd); }

fs::path freshDir(const std::string& name) {
  const fs::path p = fs::path(SSLR_TEST_TMP) / "viewer" / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// The viewer under a virtual X server (a GL 4.5 core context from Mesa's GLX, llvmpipe). Two
// xvfb-run -a started at once can pick the same display number: each test process starts its
// search at its own number. The viewer's own exit code is echoed and read back: xvfb-run
// sometimes fails to remove its temporary directory after the program ended and then exits 5
// whatever the program returned.
Result view(const std::string& args) {
  const std::string display = std::to_string(100 + getpid() % 800);
  Result r = sh("xvfb-run -a -n " + display + " -s '-screen 0 1280x720x24' sh -c '" + std::string(SSLR_VIEW_EXE) +
                " " + args + "; echo sslr-view-exit=$?'");
  const size_t at = r.output.rfind("sslr-view-exit=");
  if (at != std::string::npos) r.exitCode = std::atoi(r.output.c_str() + at + 15);
  return r;
}

class Viewer : public ::testing::Test {
 protected:
  void SetUp() override {
    if (sh("command -v xvfb-run").exitCode != 0) {
      const char* require = std::getenv("SSLR_REQUIRE_GL");
      if (require != nullptr && std::string(require) == "1") FAIL() << "xvfb-run is missing (.ci/install-deps installs xvfb)";
      GTEST_SKIP() << "xvfb-run is not installed";
    }
  }
};

double stddev(const Image& img) {
  double sum = 0, sum2 = 0;
  for (float v : img.pixels) sum += v, sum2 += double(v) * v;
  const double n = double(img.pixels.size()), mean = sum / n;
  return std::sqrt(std::max(sum2 / n - mean * mean, 0.0));
}

// Share of pixels whose channels differ by more than `threshold` (8-bit sRGB steps / 255).
double differing(const Image& a, const Image& b, float threshold) {
  return double(compareImages(a, b, threshold).pixelsOver) / (double(a.width) * a.height);
}

TEST_F(Viewer, WindowShowsWhatTheHeadlessRendererRenders) {
  const fs::path dir = freshDir("match");
  const Result v = view("--size 320x180 --frames 3 --hide-ui --screenshot " + (dir / "view.png").string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  const Result r = sh(std::string(SSLR_RENDER_EXE) + " --size 320x180 --out " + (dir / "render").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const Result none = sh(std::string(SSLR_RENDER_EXE) + " --size 320x180 --method none --out " + (dir / "none").string());
  ASSERT_EQ(none.exitCode, 0) << none.output;
  auto shot = readImage((dir / "view.png").string());
  auto render = readImage((dir / "render" / "final.png").string());
  auto plain = readImage((dir / "none" / "final.png").string());
  ASSERT_TRUE(shot && render && plain);
  ASSERT_EQ(shot.value().width, 320);
  ASSERT_EQ(shot.value().height, 180);
  EXPECT_GT(stddev(shot.value()), 0.05) << "the window is (nearly) uniform";
  // The same pipeline on the same rasterizer (GLX here, EGL there): measured 0 pixels over 3/255;
  // allow 1% over 8/255 for another Mesa.
  const double off = differing(shot.value(), render.value(), 8.0f / 255.0f);
  EXPECT_LE(off, 0.01) << "window and sslr-render differ";
  // Reflections are there: the mirror floor differs from the frame without them.
  EXPECT_GE(differing(shot.value(), plain.value(), 8.0f / 255.0f), 0.05) << "no reflections in the window";
}

// --stereo: one context of two views traces both eyes; the window's left half is the left eye's
// final image and its right half the right eye's, as sslr-render --views 2 writes them.
TEST_F(Viewer, StereoShowsEachEyeAsSslrRenderWritesIt) {
  const fs::path dir = freshDir("stereo");
  const Result v = view("--size 320x180 --frames 2 --hide-ui --stereo --screenshot " + (dir / "view.png").string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  const Result r = sh(std::string(SSLR_RENDER_EXE) + " --size 320x180 --views 2 --out " + (dir / "render").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto shot = readImage((dir / "view.png").string());
  auto left = readImage((dir / "render" / "final-view0.png").string());
  auto right = readImage((dir / "render" / "final-view1.png").string());
  ASSERT_TRUE(shot && left && right);
  ASSERT_EQ(shot.value().width, 320);
  // Each half against its eye (the tolerance of WindowShowsWhatTheHeadlessRendererRenders), and
  // against the other eye, which it must not be.
  size_t offOwn = 0, offOther = 0, pixels = 0;
  for (int y = 0; y < 180; ++y)
    for (int x = 0; x < 320; ++x) {
      const Image& own = x < 160 ? left.value() : right.value();
      const Image& other = x < 160 ? right.value() : left.value();
      bool ownOff = false, otherOff = false;
      for (int c = 0; c < 3; ++c) {
        ownOff |= std::abs(shot.value().at(x, y, c) - own.at(x, y, c)) > 8.0f / 255.0f;
        otherOff |= std::abs(shot.value().at(x, y, c) - other.at(x, y, c)) > 8.0f / 255.0f;
      }
      offOwn += ownOff;
      offOther += otherOff;
      ++pixels;
    }
  EXPECT_LE(double(offOwn) / double(pixels), 0.01) << "a half of the window is not its eye's frame";
  EXPECT_GE(double(offOther) / double(pixels), 0.02) << "the eyes show no parallax";
}

TEST_F(Viewer, PanelIsDrawnOverTheView) {
  const fs::path dir = freshDir("panel");
  ASSERT_EQ(view("--size 640x360 --frames 2 --screenshot " + (dir / "ui.png").string()).exitCode, 0);
  ASSERT_EQ(view("--size 640x360 --frames 2 --hide-ui --screenshot " + (dir / "bare.png").string()).exitCode, 0);
  auto ui = readImage((dir / "ui.png").string());
  auto bare = readImage((dir / "bare.png").string());
  ASSERT_TRUE(ui && bare);
  // The panel sits at the top left (GL rows: the top is the last row); the bottom right is untouched.
  auto region = [](const Image& img, int x0, int y0, int x1, int y1) {
    Image out{x1 - x0, y1 - y0, 3, {}};
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int k = 0; k < 3; ++k) out.pixels.push_back(img.at(x, y, k));
    return out;
  };
  EXPECT_GE(differing(region(ui.value(), 20, 300, 200, 350), region(bare.value(), 20, 300, 200, 350), 0.1f), 0.3);
  EXPECT_EQ(differing(region(ui.value(), 500, 0, 640, 100), region(bare.value(), 500, 0, 640, 100), 1.0f / 255.0f), 0.0);
}

TEST_F(Viewer, ErrorViewAndSplitScreenRun) {
  const fs::path dir = freshDir("error");
  const Result v = view("--size 320x180 --frames 2 --hide-ui --split dda --view error --screenshot " +
                        (dir / "error.png").string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  auto shot = readImage((dir / "error.png").string());
  ASSERT_TRUE(shot);
  // Left: adaptive L's error map (black where exact); right: the DDA's (green: within a pixel).
  double leftGreen = 0, rightGreen = 0;
  for (int y = 0; y < 180; ++y)
    for (int x = 0; x < 320; ++x) (x < 160 ? leftGreen : rightGreen) += shot.value().at(x, y, 1);
  EXPECT_GT(rightGreen, 2.0 * leftGreen) << "the DDA's pixel steps should show as more error";
  for (const char* name :
       {"reflection", "blur-weight", "coverage", "confidence", "length", "iterations", "hit-distance", "hit-uv"}) {
    const Result r = view("--size 96x54 --frames 1 --hide-ui --view " + std::string(name) + " --screenshot " +
                          (dir / (std::string(name) + ".png")).string());
    EXPECT_EQ(r.exitCode, 0) << name << ": " << r.output;
  }
}

// The image-error view: each side's composite against the ray-traced reference, as sslr-render
// --score maps and measures it for the same camera (the same numbers, printed by a scripted run;
// the same map, left of the split line).
TEST_F(Viewer, ImageErrorViewShowsWhatSslrRenderScores) {
  const fs::path dir = freshDir("image-error");
  const Result v = view("--size 320x180 --frames 2 --hide-ui --split dda --view image-error --screenshot " +
                        (dir / "image-error.png").string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  const std::regex printed("sslr-view: ([AB]) [a-z-]+: image RMSE ([0-9.]+) over ([0-9]+) mirror pixels; hits");
  std::map<std::string, std::pair<double, long>> viewer;
  for (std::sregex_iterator it(v.output.begin(), v.output.end(), printed), end; it != end; ++it)
    viewer[(*it)[1].str()] = {std::stod((*it)[2].str()), std::stol((*it)[3].str())};
  ASSERT_EQ(viewer.size(), 2u) << v.output;
  const std::regex scored("composite against the ray-traced reference: RMSE ([0-9.]+), PSNR [0-9.]+ dB over ([0-9]+)");
  const std::pair<const char*, const char*> sides[] = {{"A", "adaptive-l"}, {"B", "dda"}};
  for (const auto& [side, method] : sides) {
    const Result r = sh(std::string(SSLR_RENDER_EXE) + " --size 320x180 --score --method " + method + " --out " +
                        (dir / method).string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.output, m, scored)) << r.output;
    // Printed to 4 decimals; the window's pipeline matches sslr-render's image (test above), so
    // the two may differ by a rounding step.
    EXPECT_NEAR(viewer[side].first, std::stod(m[1].str()), 1.5e-4) << method;
    EXPECT_EQ(viewer[side].second, std::stol(m[2].str())) << method;
  }
  EXPECT_LT(viewer["A"].first, viewer["B"].first) << "the default is closer to the reference than the DDA here";
  // Left of the split line (2 px either side of x = 160 left out): adaptive L's map.
  auto shot = readImage((dir / "image-error.png").string());
  auto map = readImage((dir / "adaptive-l" / "composite-error.png").string());
  ASSERT_TRUE(shot && map);
  size_t over = 0;
  for (int y = 0; y < 180; ++y)
    for (int x = 0; x < 158; ++x)
      for (int k = 0; k < 3; ++k)
        if (std::abs(shot.value().at(x, y, k) - map.value().at(x, y, k)) > 8.0f / 255.0f) {
          ++over;
          break;
        }
  EXPECT_LE(over, 158u * 180u / 100u) << "the window's image-error map and sslr-render's composite-error.png differ";
}

// A model with nothing to reflect in gets a mirror floor with --mirror-floor (Debian's
// assimp-testmodels BoxTextured: the box's reflection appears below it).
TEST_F(Viewer, MirrorFloorUnderALoadedModel) {
  const fs::path model = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  if (!fs::exists(model)) GTEST_SKIP() << "assimp-testmodels not installed";
  const fs::path dir = freshDir("floor");
  const std::string common = "--scene " + model.string() + " --size 240x136 --frames 2 --hide-ui --screenshot ";
  ASSERT_EQ(view(common + (dir / "bare.png").string()).exitCode, 0);
  const Result floor = view("--mirror-floor " + common + (dir / "floor.png").string());
  ASSERT_EQ(floor.exitCode, 0) << floor.output;
  auto bare = readImage((dir / "bare.png").string());
  auto withFloor = readImage((dir / "floor.png").string());
  ASSERT_TRUE(bare && withFloor);
  // Below the box (the lower third of the frame, middle columns) the floor and its reflection.
  double reflected = 0;
  for (int y = 30; y < 60; ++y)
    for (int x = 100; x < 140; ++x)
      for (int k = 0; k < 3; ++k) reflected += std::abs(withFloor.value().at(x, y, k) - bare.value().at(x, y, k));
  EXPECT_GT(reflected, 30.0) << "no floor under the model";
}

TEST_F(Viewer, NoDisplayAndBadArgumentsAreClearErrors) {
  const Result noDisplay = sh("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(SSLR_VIEW_EXE) + " --frames 1");
  EXPECT_EQ(noDisplay.exitCode, 1) << noDisplay.output;
  EXPECT_NE(noDisplay.output.find("no display"), std::string::npos) << noDisplay.output;
  EXPECT_NE(noDisplay.output.find("xvfb-run"), std::string::npos) << noDisplay.output;
  for (const char* bad : {"--view bogus", "--split nothing", "--size 0x0", "--screenshot x.png", "--stereo --split dda",
                          "--stereo --view image-error"}) {
    const Result r = sh(std::string(SSLR_VIEW_EXE) + " " + bad);
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("sslr-view:"), std::string::npos) << r.output;
  }
  const Result stereoError = sh(std::string(SSLR_VIEW_EXE) + " --stereo --view image-error");
  EXPECT_NE(stereoError.output.find("--view image-error needs one view"), std::string::npos) << stereoError.output;
  // A screenshot that cannot be written is refused before any window opens (no display needed).
  const struct {
    const char* args;
    const char* message;
  } shots[] = {{"--frames 1 --screenshot /", "name a .png file"},
               {"--frames 1 --screenshot /tmp", "name a .png file"},
               {"--frames 1 --screenshot /nonexistent-dir/shot.png", "does not exist"}};
  for (const auto& shot : shots) {
    const Result r = sh("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(SSLR_VIEW_EXE) + " " + shot.args);
    EXPECT_EQ(r.exitCode, 2) << shot.args << ": " << r.output;
    EXPECT_NE(r.output.find(shot.message), std::string::npos) << shot.args << ": " << r.output;
  }
  const Result missing = view("--scene /nonexistent/model.gltf --frames 1");
  EXPECT_EQ(missing.exitCode, 2) << missing.output;
  EXPECT_NE(missing.output.find("model.gltf"), std::string::npos) << missing.output;
}

}  // namespace
