// assets/scenes: every built-in scene as a glTF file. The files are current (written from the
// built-in definitions by gltfFromScene, byte for byte) and loading one gives the built-in
// scene's G-buffer.
#include <filesystem>
#include <fstream>

#include "gl/gl_fixture.hpp"
#include "sslr_host/gbuffer.hpp"
#include "sslr_host/gltf_loader.hpp"
#include "sslr_host/gltf_writer.hpp"
#include "sslr_host/scene.hpp"

namespace {

using namespace sslr::host;
namespace fs = std::filesystem;

fs::path assetPath(const std::string& name) { return fs::path(SSLR_SOURCE_DIR) / "assets" / "scenes" / (name + ".gltf"); }

TEST(Assets, SceneFilesAreCurrent) {
  for (const std::string& name : builtinSceneNames()) {
    auto scene = makeBuiltinScene(name);
    ASSERT_TRUE(scene);
    auto text = gltfFromScene(scene.value());
    ASSERT_TRUE(text) << text.error();
    std::ifstream in(assetPath(name), std::ios::binary);
    ASSERT_TRUE(in) << assetPath(name) << " is missing: run assets/scenes/generate.sh";
    const std::string onDisk((std::istreambuf_iterator<char>(in)), {});
    EXPECT_TRUE(onDisk == text.value()) << assetPath(name) << " is stale: run assets/scenes/generate.sh";
  }
}

class AssetsGl : public sslr::test::GlTest {};

TEST_F(AssetsGl, LoadedFileGivesTheBuiltInGBuffer) {
  for (const std::string& name : builtinSceneNames()) {
    auto builtin = makeBuiltinScene(name);
    auto loaded = loadGltf(assetPath(name).string());
    ASSERT_TRUE(builtin);
    ASSERT_TRUE(loaded) << loaded.error();
    ASSERT_TRUE(loaded.value().camera) << name;
    EXPECT_TRUE(loaded.value().warnings.empty()) << name << ": " << loaded.value().warnings.front();
    Image images[2][3];
    const Scene* scenes[2] = {&builtin.value(), &loaded.value()};
    for (int k = 0; k < 2; ++k) {
      GBufferOptions o;
      o.width = 96;
      o.height = 54;
      auto g = GBuffer::create(o);
      ASSERT_TRUE(g);
      GpuScene gpu(*scenes[k]);
      ASSERT_TRUE(g.value()->render(gpu, *scenes[k]->camera));
      images[k][0] = g.value()->readDepth();
      images[k][1] = g.value()->readNormalPacked();
      images[k][2] = g.value()->readColor();
    }
    // The same floats reach the rasterizer (node matrices are written as exact doubles, vertex
    // data as raw float bytes); the camera is rebuilt from its node matrix (eye, a unit view
    // direction, up), which moves the view by rounding only. Tolerances: depth 1e-6 (a few D32F
    // ulps), packed normals and colour 2e-3 (one 8-bit step on rare pixels).
    const double tolerance[3] = {1e-6, 2e-3, 2e-3};
    const char* what[3] = {"depth", "normal", "colour"};
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(images[0][i].pixels.size(), images[1][i].pixels.size());
      double worst = 0;
      size_t differing = 0;
      for (size_t p = 0; p < images[0][i].pixels.size(); ++p) {
        const double d = std::abs(double(images[0][i].pixels[p]) - images[1][i].pixels[p]);
        worst = std::max(worst, d);
        differing += d > tolerance[i];
      }
      // A pixel on a silhouette may flip between the two surfaces it straddles.
      EXPECT_LE(differing, images[0][i].pixels.size() / 500) << name << " " << what[i] << ": worst " << worst;
    }
  }
}

}  // namespace
