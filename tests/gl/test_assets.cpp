// assets/scenes: every built-in scene as a glTF file. The files are current (written from the
// built-in definitions by gltfFromScene, byte for byte) and loading one gives the built-in
// scene's G-buffer.
#include <cstdlib>
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

// The asset scenes (real models staged on or as mirrors) load by name, with their camera, no
// warnings, the model's own triangles and the stage's mirror floor.
TEST(Assets, AssetScenesLoadByName) {
  for (const std::string& name : assetSceneNames()) {
    auto scene = loadScene(name);
    ASSERT_TRUE(scene) << name << ": " << scene.error();
    EXPECT_TRUE(scene.value().camera) << name;
    EXPECT_TRUE(scene.value().warnings.empty()) << name << ": " << scene.value().warnings.front();
    EXPECT_GT(scene.value().triangleCount(), 1000u) << name << " must hold the model, not only the stage";
    const Bounds b = scene.value().worldBounds();
    EXPECT_NEAR(b.min.y, -1e-3, 1e-6) << name << ": the mirror floor is the lowest thing";
  }
}

// A moved asset folder is named in the error, with the variable that points elsewhere.
TEST(Assets, MissingAssetFolderIsNamed) {
  ::setenv("SSLR_ASSET_DIR", "/nonexistent-sslr-assets", 1);
  auto scene = loadScene("wuson-as-mirror");
  ::unsetenv("SSLR_ASSET_DIR");
  ASSERT_FALSE(scene);
  EXPECT_NE(scene.error().find("/nonexistent-sslr-assets/scenes/wuson-as-mirror.gltf"), std::string::npos) << scene.error();
  EXPECT_NE(scene.error().find("SSLR_ASSET_DIR"), std::string::npos) << scene.error();
}

// stageModel: the model's largest side becomes 3 units, centred on the origin in x and z and
// standing on y = 0; AsMirror turns every model material into a sharp mirror; an empty model is
// refused with its name.
TEST(Assets, StageModelScalesCentresAndStandsTheModel) {
  Scene box;
  box.name = "box";
  box.materials.push_back(Material{glm::vec3(0.2f, 0.4f, 0.6f), 0.0f, 0.7f});
  box.meshes.push_back(makeBox({10.0, 5.0, -3.0}, {2.0, 6.0, 1.0}, 0));
  for (ModelStage stage : {ModelStage::OnMirror, ModelStage::AsMirror}) {
    auto staged = stageModel(box, stage);
    ASSERT_TRUE(staged) << staged.error();
    Scene modelOnly = staged.value();
    modelOnly.meshes.resize(1);
    const Bounds b = modelOnly.worldBounds();
    EXPECT_NEAR(b.max.y - b.min.y, 3.0, 1e-5);
    EXPECT_NEAR(b.max.x - b.min.x, 1.0, 1e-5);
    EXPECT_NEAR(b.min.y, 0.0, 1e-5);
    EXPECT_NEAR(b.min.x + b.max.x, 0.0, 1e-5);
    EXPECT_NEAR(b.min.z + b.max.z, 0.0, 1e-5);
    const Material& m = staged.value().materials[0];
    if (stage == ModelStage::AsMirror) {
      EXPECT_EQ(m.metallic, 1.0f);
      EXPECT_EQ(m.roughness, 0.0f);
      EXPECT_EQ(staged.value().name, "box-as-mirror");
    } else {
      EXPECT_EQ(m.roughness, 0.7f);
      EXPECT_EQ(staged.value().name, "box-on-mirror");
    }
    ASSERT_TRUE(staged.value().camera);
    EXPECT_EQ(staged.value().camera->validate(), "");
  }
  Scene empty;
  empty.name = "nothing";
  auto refused = stageModel(empty, ModelStage::OnMirror);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().find("nothing"), std::string::npos) << refused.error();
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
