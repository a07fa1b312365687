#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "sslr_host/gltf_loader.hpp"
#include "sslr_host/scene.hpp"

namespace sslr::host {

Bounds Scene::worldBounds() const {
  Bounds b;
  for (const Mesh& m : meshes)
    for (const glm::vec3& p : m.positions) b.add(glm::dvec3(m.worldFromModel * glm::dvec4(glm::dvec3(p), 1.0)));
  return b;
}

Camera Scene::defaultCamera() const {
  Camera c;
  Bounds b = worldBounds();
  if (b.empty()) return c;
  const glm::dvec3 center = (b.min + b.max) * 0.5;
  const double radius = std::max(glm::length(b.max - b.min) * 0.5, 1e-3);
  c.fovyDegrees = 45.0;
  const double dist = radius / std::sin(glm::radians(c.fovyDegrees) * 0.5);
  c.target = center;
  c.eye = center + glm::normalize(glm::dvec3(0.0, 0.35, 1.0)) * dist;
  c.nearPlane = std::max(dist - radius, dist * 1e-3) * 0.5;
  c.farPlane = (dist + radius) * 1.5;
  return c;
}

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const Mesh& m : meshes) n += m.indices.size() / 3;
  return n;
}

float reflectance(const Material& m) {
  const float metalF0 = std::max({m.baseColor.r, m.baseColor.g, m.baseColor.b});
  return glm::mix(0.04f, metalF0, glm::clamp(m.metallic, 0.0f, 1.0f));
}

Mesh makeQuad(glm::dvec3 center, glm::dvec2 size, glm::dvec3 normal, int material) {
  Mesh m;
  m.material = material;
  const glm::dvec3 n = glm::normalize(normal);
  const glm::dvec3 helper = std::abs(n.y) < 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, -1);
  const glm::dvec3 u = glm::normalize(glm::cross(helper, n));
  const glm::dvec3 v = glm::cross(n, u);
  const glm::dvec2 h = size * 0.5;
  const glm::dvec3 corners[4] = {center - u * h.x - v * h.y, center + u * h.x - v * h.y,
                                 center + u * h.x + v * h.y, center - u * h.x + v * h.y};
  const glm::vec2 uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    m.positions.push_back(glm::vec3(corners[i]));
    m.normals.push_back(glm::vec3(n));
    m.uvs.push_back(uvs[i]);
  }
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Mesh makeBox(glm::dvec3 center, glm::dvec3 size, int material, double rotationYDegrees) {
  Mesh box;
  box.material = material;
  const glm::dvec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {-1.0, 1.0}) {
      const glm::dvec3 n = axes[axis] * s;
      glm::dvec2 faceSize;
      // makeQuad's u/v axes for this normal decide which box extents the face spans.
      const glm::dvec3 helper = std::abs(n.y) < 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, -1);
      const glm::dvec3 u = glm::normalize(glm::cross(helper, n));
      const glm::dvec3 v = glm::cross(n, u);
      faceSize = {std::abs(glm::dot(u, size)), std::abs(glm::dot(v, size))};
      Mesh face = makeQuad(n * (glm::dot(glm::abs(n), size) * 0.5), faceSize, n, material);
      const auto base = static_cast<std::uint32_t>(box.positions.size());
      box.positions.insert(box.positions.end(), face.positions.begin(), face.positions.end());
      box.normals.insert(box.normals.end(), face.normals.begin(), face.normals.end());
      box.uvs.insert(box.uvs.end(), face.uvs.begin(), face.uvs.end());
      for (auto i : face.indices) box.indices.push_back(base + i);
    }
  box.worldFromModel = glm::rotate(glm::translate(glm::dmat4(1.0), center),
                                   glm::radians(rotationYDegrees), glm::dvec3(0, 1, 0));
  return box;
}

namespace {

int addMaterial(Scene& s, glm::vec3 color, float metallic, float roughness, float emissive = 0.0f) {
  Material m;
  m.baseColor = color;
  m.metallic = metallic;
  m.roughness = roughness;
  m.emissive = emissive;
  s.materials.push_back(m);
  return static_cast<int>(s.materials.size() - 1);
}

Camera perspectiveCamera(glm::dvec3 eye, glm::dvec3 target, double fovyDegrees, double nearPlane, double farPlane) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.fovyDegrees = fovyDegrees;
  c.nearPlane = nearPlane;
  c.farPlane = farPlane;
  return c;
}

Scene mirrorRoom() {
  Scene s;
  s.name = "mirror-room";
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.0f);
  const int brushed = addMaterial(s, glm::vec3(0.85f, 0.8f, 0.7f), 1.0f, 0.3f);
  const int wall = addMaterial(s, glm::vec3(0.75f, 0.72f, 0.68f), 0.0f, 0.9f);
  const int red = addMaterial(s, glm::vec3(0.8f, 0.1f, 0.08f), 0.0f, 0.7f, 0.15f);
  const int green = addMaterial(s, glm::vec3(0.1f, 0.7f, 0.15f), 0.0f, 0.7f, 0.15f);
  const int blue = addMaterial(s, glm::vec3(0.1f, 0.2f, 0.85f), 0.0f, 0.7f, 0.15f);
  const int yellow = addMaterial(s, glm::vec3(0.9f, 0.75f, 0.1f), 0.0f, 0.7f, 0.15f);
  // Floor: a sharp mirror in front, a brushed (rough) strip at the back to show the blur.
  s.meshes.push_back(makeQuad({0, 0, 1.5}, {12, 9}, {0, 1, 0}, mirror));
  s.meshes.push_back(makeQuad({0, 0, -4.5}, {12, 3}, {0, 1, 0}, brushed));
  s.meshes.push_back(makeQuad({0, 3, -6}, {12, 6}, {0, 0, 1}, wall));   // back wall
  s.meshes.push_back(makeQuad({-6, 3, 0}, {12, 6}, {1, 0, 0}, wall));   // left wall
  s.meshes.push_back(makeQuad({6, 3, 0}, {12, 6}, {-1, 0, 0}, wall));   // right wall
  s.meshes.push_back(makeBox({-2.2, 0.75, -1.0}, {1.5, 1.5, 1.5}, red, 20.0));
  s.meshes.push_back(makeBox({0.4, 1.25, -2.2}, {1.2, 2.5, 1.2}, green, -10.0));
  s.meshes.push_back(makeBox({2.4, 0.5, -0.4}, {1.0, 1.0, 1.0}, blue, 35.0));
  s.meshes.push_back(makeBox({-0.2, 0.3, 1.2}, {0.6, 0.6, 0.6}, yellow, 0.0));
  s.camera = perspectiveCamera({0.0, 2.6, 7.5}, {0.0, 0.9, -1.0}, 55.0, 0.1, 100.0);
  s.background = glm::vec3(0.25f, 0.3f, 0.4f);
  return s;
}

Scene grazingPlane() {
  Scene s;
  s.name = "grazing-plane";
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.05f);
  const int stone = addMaterial(s, glm::vec3(0.7f, 0.6f, 0.5f), 0.0f, 0.9f, 0.1f);
  const int red = addMaterial(s, glm::vec3(0.8f, 0.15f, 0.1f), 0.0f, 0.8f, 0.2f);
  s.meshes.push_back(makeQuad({0, 0, -500}, {2000, 2000}, {0, 1, 0}, mirror));
  for (int i = 0; i < 12; ++i) {
    const double z = -8.0 - i * i * 4.0;
    const double x = (i % 2 == 0 ? -1.0 : 1.0) * (3.0 + i * 1.5);
    s.meshes.push_back(makeBox({x, 2.0 + i * 0.5, z}, {1.5, 4.0 + i, 1.5}, i % 3 == 0 ? red : stone));
  }
  s.camera = perspectiveCamera({0.0, 0.6, 5.0}, {0.0, 0.9, -30.0}, 50.0, 0.05, 3000.0);
  s.background = glm::vec3(0.45f, 0.55f, 0.7f);
  return s;
}

Scene thinObjects() {
  Scene s;
  s.name = "thin-objects";
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.0f);
  const int white = addMaterial(s, glm::vec3(0.9f), 0.0f, 0.8f, 0.2f);
  const int orange = addMaterial(s, glm::vec3(0.9f, 0.4f, 0.1f), 0.0f, 0.8f, 0.2f);
  const int wall = addMaterial(s, glm::vec3(0.3f, 0.35f, 0.45f), 0.0f, 0.9f);
  s.meshes.push_back(makeQuad({0, 0, 0}, {16, 16}, {0, 1, 0}, mirror));
  s.meshes.push_back(makeQuad({0, 3, -8}, {16, 6}, {0, 0, 1}, wall));
  for (int i = 0; i < 9; ++i)  // poles
    s.meshes.push_back(makeBox({-4.0 + i, 1.25, -2.0 - 0.3 * i}, {0.06, 2.5, 0.06}, i % 2 ? white : orange));
  for (int k = 0; k < 3; ++k)  // fence rails
    s.meshes.push_back(makeBox({0.0, 0.4 + 0.45 * k, -4.5}, {9.0, 0.05, 0.05}, white));
  for (int i = 0; i < 19; ++i)  // fence pickets
    s.meshes.push_back(makeBox({-4.5 + 0.5 * i, 0.75, -4.5}, {0.04, 1.5, 0.04}, white));
  s.camera = perspectiveCamera({0.0, 1.8, 5.0}, {0.0, 0.8, -3.0}, 50.0, 0.1, 100.0);
  s.background = glm::vec3(0.2f, 0.22f, 0.3f);
  return s;
}

Scene skyHeavy() {
  Scene s;
  s.name = "sky-heavy";
  const int mirror = addMaterial(s, glm::vec3(0.9f), 1.0f, 0.0f);
  const int teal = addMaterial(s, glm::vec3(0.1f, 0.6f, 0.6f), 0.0f, 0.7f, 0.2f);
  s.meshes.push_back(makeBox({0.0, 0.0, 0.0}, {2.0, 0.1, 2.0}, mirror));  // a small mirror slab
  s.meshes.push_back(makeBox({0.0, 0.7, -0.4}, {0.5, 1.2, 0.5}, teal, 30.0));
  s.camera = perspectiveCamera({0.0, 1.2, 6.0}, {0.0, 2.0, 0.0}, 60.0, 0.1, 100.0);
  s.background = glm::vec3(0.5f, 0.65f, 0.85f);
  return s;
}

// Analytic test scenes: simple enough that the tests compute the true reflection by hand.
Scene mirrorBox() {
  Scene s;
  s.name = "mirror-box";
  const int mirror = addMaterial(s, glm::vec3(1.0f), 1.0f, 0.0f);
  const int red = addMaterial(s, glm::vec3(0.9f, 0.2f, 0.1f), 0.0f, 1.0f, 0.3f);
  const int wall = addMaterial(s, glm::vec3(0.2f, 0.5f, 0.8f), 0.0f, 1.0f, 0.3f);
  s.meshes.push_back(makeQuad({0, 0, 0}, {10, 10}, {0, 1, 0}, mirror));
  s.meshes.push_back(makeQuad({0, 2.5, -5}, {10, 5}, {0, 0, 1}, wall));
  s.meshes.push_back(makeBox({0.5, 0.75, -1.5}, {1.5, 1.5, 1.5}, red, 25.0));
  s.camera = perspectiveCamera({0.0, 2.0, 5.0}, {0.0, 0.5, -1.0}, 50.0, 0.1, 50.0);
  return s;
}

Scene tiltedMirror() {
  Scene s;
  s.name = "tilted-mirror";
  const int mirror = addMaterial(s, glm::vec3(1.0f), 1.0f, 0.0f);
  const int floor = addMaterial(s, glm::vec3(0.6f, 0.6f, 0.2f), 0.0f, 1.0f, 0.3f);
  const int wall = addMaterial(s, glm::vec3(0.2f, 0.7f, 0.4f), 0.0f, 1.0f, 0.3f);
  s.meshes.push_back(makeQuad({0, 0, 0}, {12, 12}, {0, 1, 0}, floor));
  s.meshes.push_back(makeQuad({0, 3, -6}, {12, 6}, {0, 0, 1}, wall));
  // A mirror leaning forward by 30 degrees: it faces the camera and the floor in front of it.
  s.meshes.push_back(makeQuad({0, 1.5, -3}, {5, 3}, {0.0, -std::sin(glm::radians(30.0)),
                                                    std::cos(glm::radians(30.0))}, mirror));
  s.camera = perspectiveCamera({1.0, 2.5, 4.0}, {0.0, 1.2, -3.0}, 50.0, 0.1, 50.0);
  return s;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  return {"mirror-room", "grazing-plane", "thin-objects", "sky-heavy", "mirror-box", "tilted-mirror"};
}

Expected<Scene> makeBuiltinScene(const std::string& name) {
  if (name == "mirror-room") return mirrorRoom();
  if (name == "grazing-plane") return grazingPlane();
  if (name == "thin-objects") return thinObjects();
  if (name == "sky-heavy") return skyHeavy();
  if (name == "mirror-box") return mirrorBox();
  if (name == "tilted-mirror") return tiltedMirror();
  std::string known;
  for (const auto& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
  return Status::error("unknown scene '" + name + "' (built-in scenes: " + known +
                       "; or give a .gltf/.glb file)");
}

Expected<Scene> loadScene(const std::string& nameOrPath) {
  auto endsWith = [&](const char* suffix) {
    const std::string s(suffix);
    return nameOrPath.size() >= s.size() &&
           std::equal(s.rbegin(), s.rend(), nameOrPath.rbegin(),
                      [](char a, char b) { return std::tolower(a) == std::tolower(b); });
  };
  if (endsWith(".gltf") || endsWith(".glb")) return loadGltf(nameOrPath);
  return makeBuiltinScene(nameOrPath);
}

}  // namespace sslr::host
