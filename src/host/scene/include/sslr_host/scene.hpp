// Scenes the tools render: triangle meshes with metallic-roughness materials, a camera, a light.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sslr/sslr.hpp"
#include "sslr_host/camera.hpp"

namespace sslr::host {

struct Texture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba8;  // sRGB base colour, rows in file order (glTF uv v=0 = first row)
};

struct Material {
  glm::vec3 baseColor{0.8f};  // linear
  float metallic = 0.0f;
  float roughness = 0.8f;
  int baseColorTexture = -1;  // index into Scene::textures
  float emissive = 0.0f;      // adds baseColor * emissive to the lit colour (built-in scenes)
  glm::vec3 emissiveColor{0.0f};  // adds this colour (glTF emissiveFactor), linear
};

struct Mesh {
  std::vector<glm::vec3> positions;  // model space
  std::vector<glm::vec3> normals;    // model space, unit
  std::vector<glm::vec2> uvs;        // may be empty
  std::vector<std::uint32_t> indices;  // triangles
  int material = 0;
  glm::dmat4 worldFromModel{1.0};
};

struct Bounds {
  glm::dvec3 min{1e300}, max{-1e300};
  void add(glm::dvec3 p) { min = glm::min(min, p); max = glm::max(max, p); }
  bool empty() const { return min.x > max.x; }
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::optional<Camera> camera;
  glm::vec3 lightDirection = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));  // world, travel dir
  glm::vec3 background{0.0f};  // colour of background pixels in the lit colour buffer
  std::vector<std::string> warnings;  // non-fatal problems met while loading

  Bounds worldBounds() const;  // of the vertices that triangles use
  // "" if the scene can be rendered, else why not (non-finite or absurd extent).
  std::string checkExtent() const;
  // A camera framing the bounds from the front (+z), slightly above: for scenes without one.
  Camera defaultCamera() const;
  size_t triangleCount() const;
};

// Farthest a scene may reach from the origin (float rasterization: beyond this a vertex is
// off by whole units; at 3e9 the G-buffer gets NaN).
inline constexpr double kMaxSceneExtent = 1e8;

// Near and far planes that hold the whole box as seen from the camera's eye.
void fitClipPlanes(Camera& camera, const Bounds& bounds);

// The matrix that carries a model's normals into the space `spaceFromModel` maps to: the cofactor
// matrix of its upper 3x3 (the inverse transpose times the determinant, so it exists for a
// singular transform too: a node scaled to zero along one axis keeps the normals of its flat
// faces), its sign fixed so a mirroring transform keeps normals' orientation, and scaled so its
// largest element is 1 (finite in float whatever the transform's scale). Normals it maps to zero
// (faces a singular transform flattens to lines) are left to the caller's fallback.
glm::dmat3 normalMatrixOf(const glm::dmat4& spaceFromModel);

// F0 the G-buffer stores for a material: 0.04 for dielectrics, base colour for metals.
float reflectance(const Material& m);

// Built-in procedural scenes: mirror-room (default), grazing-plane, thin-objects, sky-heavy,
// the analytic test scenes mirror-box, tilted-mirror, and the scenes built to break the tracer:
// facing-mirror, mirror-walls, curved-mirror, glossy. Also reflective-N (N = 0..100): a floor
// whose bottom N% of screen rows is a mirror, for cost against reflective fraction.
std::vector<std::string> builtinSceneNames();
Expected<Scene> makeBuiltinScene(const std::string& name);

// Scenes kept as glTF files in assets/scenes because the code cannot build them alone: real models
// nobody here made (Debian's assimp-testmodels), staged on or as mirrors by stageModel
// (assets/scenes/generate.sh): spider-on-mirror, wuson-as-mirror.
std::vector<std::string> assetSceneNames();
// The file of an asset scene: $SSLR_ASSET_DIR/scenes/NAME.gltf, or the source tree's assets.
std::string assetScenePath(const std::string& name);

// A scene by built-in name, asset scene name or glTF path (.gltf/.glb).
Expected<Scene> loadScene(const std::string& nameOrPath);

// Adds a mirror floor under the scene (three times its size, just below its lowest point): most
// models have nothing to reflect in.
void addMirrorFloor(Scene& scene);

// A model staged for the reflection tests: scaled to a largest side of 3 units, standing on a
// mirror floor at the origin, a wall and four coloured boxes around it, and a camera. OnMirror
// keeps its materials and looks from low down; AsMirror makes every material of the model a sharp
// mirror (a curved mirror nobody here modelled) and looks from above.
enum class ModelStage { OnMirror, AsMirror };
Expected<Scene> stageModel(Scene model, ModelStage stage);

// Mesh building helpers (also used by tests).
Mesh makeBox(glm::dvec3 center, glm::dvec3 size, int material, double rotationYDegrees = 0.0);
Mesh makeQuad(glm::dvec3 center, glm::dvec2 size, glm::dvec3 normal, int material);
// Smooth (vertex-normal) sphere and capped cylinder standing on baseCenter along +y.
Mesh makeSphere(glm::dvec3 center, double radius, int material, int rings = 32, int segments = 64);
Mesh makeCylinder(glm::dvec3 baseCenter, double radius, double height, int material, int segments = 64);

}  // namespace sslr::host
