// Scene: its bounds, extent check and default camera, and the geometry builders (quad, box, sphere,
// cylinder) the catalogue (scene_catalogue.cpp) builds its scenes from.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "sslr_host/scene.hpp"

namespace sslr::host {

Bounds Scene::worldBounds() const {
  // Only vertices that triangles use: an unused vertex far away must not move the framing.
  Bounds b;
  for (const Mesh& m : meshes)
    for (std::uint32_t i : m.indices)
      if (i < m.positions.size()) b.add(glm::dvec3(m.worldFromModel * glm::dvec4(glm::dvec3(m.positions[i]), 1.0)));
  return b;
}

std::string Scene::checkExtent() const {
  const Bounds b = worldBounds();
  if (b.empty()) return "";
  const double extent = std::max(maxAbsComponent(b.min), maxAbsComponent(b.max));
  if (!std::isfinite(extent))
    return "the scene's extent is not finite (a transform or vertex overflows)";
  if (extent > kMaxSceneExtent) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "the scene reaches %.3g units from the origin (limit %.0e): vertices are rasterized in float "
                  "and lose all precision there; scale or recentre the model",
                  extent, kMaxSceneExtent);
    return text;
  }
  return "";
}

void fitClipPlanes(Camera& c, const Bounds& b) {
  if (b.empty()) return;
  // Distances from the eye to the nearest and farthest points of the box.
  const glm::dvec3 nearest = glm::clamp(c.eye, b.min, b.max);
  double farthest = 0.0;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 corner((k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y, (k & 4) ? b.max.z : b.min.z);
    farthest = std::max(farthest, glm::length(corner - c.eye));
  }
  const double size = std::max(glm::length(b.max - b.min), 1e-6);
  c.farPlane = std::max(farthest, size * 1e-3) * 1.5;
  // Half the distance to the box; from inside it a fixed fraction of the far plane (reversed-Z
  // D32F keeps its precision over that ratio).
  c.nearPlane = std::max(glm::length(nearest - c.eye) * 0.5, c.farPlane * 1e-5);
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
  fitClipPlanes(c, b);
  return c;
}

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const Mesh& m : meshes) n += m.indices.size() / 3;
  return n;
}

glm::dmat3 normalMatrixOf(const glm::dmat4& spaceFromModel) {
  glm::dmat3 m(spaceFromModel);
  auto largestOf = [](const glm::dmat3& a) {
    double largest = 0.0;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) largest = std::max(largest, std::abs(a[c][r]));
    return largest;
  };
  // Scaled first, so the products below neither overflow nor underflow for any finite transform.
  const double scale = largestOf(m);
  if (!(scale > 0.0) || !std::isfinite(scale)) return glm::dmat3(1.0);
  m /= scale;
  // Cofactor matrix: column i is the cross product of the other two columns.
  glm::dmat3 cof(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
  const double det = glm::dot(m[0], cof[0]);
  const double largest = largestOf(cof);
  if (!(largest > 0.0)) return glm::dmat3(1.0);  // rank 1 or less: no face keeps an area
  return cof * ((det < 0.0 ? -1.0 : 1.0) / largest);
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


Mesh makeSphere(glm::dvec3 center, double radius, int material, int rings, int segments) {
  Mesh m;
  m.material = material;
  for (int r = 0; r <= rings; ++r) {
    const double theta = glm::pi<double>() * r / rings;  // from +y down
    for (int sgm = 0; sgm <= segments; ++sgm) {
      const double phi = 2.0 * glm::pi<double>() * sgm / segments;
      const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      m.positions.push_back(glm::vec3(n * radius));
      m.normals.push_back(glm::vec3(n));
      m.uvs.push_back(glm::vec2(float(sgm) / segments, 1.0f - float(r) / rings));
    }
  }
  const auto row = static_cast<std::uint32_t>(segments + 1);
  for (std::uint32_t r = 0; r < static_cast<std::uint32_t>(rings); ++r)
    for (std::uint32_t sgm = 0; sgm < static_cast<std::uint32_t>(segments); ++sgm) {
      const std::uint32_t a = r * row + sgm, b = a + row;
      // Counter-clockwise seen from outside; the poles' degenerate triangles are skipped.
      if (r != 0) m.indices.insert(m.indices.end(), {a, b, a + 1});
      if (r + 1 != static_cast<std::uint32_t>(rings)) m.indices.insert(m.indices.end(), {a + 1, b, b + 1});
    }
  m.worldFromModel = glm::translate(glm::dmat4(1.0), center);
  return m;
}

Mesh makeCylinder(glm::dvec3 baseCenter, double radius, double height, int material, int segments) {
  Mesh m;
  m.material = material;
  // Side: smooth normals; caps: flat, with their own vertices.
  for (int sgm = 0; sgm <= segments; ++sgm) {
    const double phi = 2.0 * glm::pi<double>() * sgm / segments;
    const glm::dvec3 n(std::cos(phi), 0.0, -std::sin(phi));
    for (double y : {0.0, height}) {
      m.positions.push_back(glm::vec3(n * radius + glm::dvec3(0, y, 0)));
      m.normals.push_back(glm::vec3(n));
      m.uvs.push_back(glm::vec2(float(sgm) / segments, float(y / height)));
    }
  }
  for (std::uint32_t sgm = 0; sgm < static_cast<std::uint32_t>(segments); ++sgm) {
    const std::uint32_t a = 2 * sgm;
    m.indices.insert(m.indices.end(), {a, a + 2, a + 1, a + 1, a + 2, a + 3});
  }
  for (double y : {0.0, height}) {
    const glm::vec3 n(0.0f, y > 0.0 ? 1.0f : -1.0f, 0.0f);
    const auto centre = static_cast<std::uint32_t>(m.positions.size());
    m.positions.push_back(glm::vec3(0.0f, float(y), 0.0f));
    m.normals.push_back(n);
    m.uvs.push_back(glm::vec2(0.5f));
    for (int sgm = 0; sgm <= segments; ++sgm) {
      const double phi = 2.0 * glm::pi<double>() * sgm / segments;
      m.positions.push_back(glm::vec3(float(radius * std::cos(phi)), float(y), float(-radius * std::sin(phi))));
      m.normals.push_back(n);
      m.uvs.push_back(glm::vec2(0.5f));
    }
    for (std::uint32_t sgm = 0; sgm < static_cast<std::uint32_t>(segments); ++sgm) {
      const std::uint32_t a = centre + 1 + sgm;
      if (y > 0.0) m.indices.insert(m.indices.end(), {centre, a, a + 1});
      else m.indices.insert(m.indices.end(), {centre, a + 1, a});
    }
  }
  m.worldFromModel = glm::translate(glm::dmat4(1.0), baseCenter);
  return m;
}

}  // namespace sslr::host
