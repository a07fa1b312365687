#include "sslr_host/gltf_writer.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

namespace sslr::host {

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    unsigned v = 0;
    for (size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? table[v >> (18 - 6 * k) & 63] : '=';
  }
  return out;
}

namespace {

using nlohmann::json;

json matrixJson(const glm::dmat4& m) {
  json a = json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a.push_back(m[c][r]);  // glTF: column-major, like glm
  return a;
}

json vec3Json(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }

// A material; emission above 1 (HDR emitters) as a factor in [0, 1] times
// KHR_materials_emissive_strength.
json materialJson(const Material& m) {
  const glm::vec3 emission = glm::max(m.baseColor * m.emissive + m.emissiveColor, glm::vec3(0.0f));
  const float strength = std::max(std::max(emission.r, emission.g), emission.b);
  json material = {{"pbrMetallicRoughness",
                    {{"baseColorFactor", {m.baseColor.r, m.baseColor.g, m.baseColor.b, 1.0f}},
                     {"metallicFactor", m.metallic},
                     {"roughnessFactor", m.roughness}}},
                   {"emissiveFactor", vec3Json(strength > 1.0f ? emission / strength : emission)}};
  if (strength > 1.0f) material["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", strength}}}};
  return material;
}

}  // namespace

Expected<std::string> gltfFromScene(const Scene& scene) {
  if (!scene.textures.empty())
    return Status::error("scene '" + scene.name + "' has textures, which the glTF writer does not write");
  json j;
  j["asset"] = {{"version", "2.0"},
                {"generator", "sslr gltfFromScene"},
                {"extras", {{"sslr", {{"background", vec3Json(scene.background)},
                                       {"lightDirection", vec3Json(scene.lightDirection)}}}}}};
  std::string bin;
  auto addView = [&](const void* data, size_t bytes, int target) {
    while (bin.size() % 4 != 0) bin.push_back('\0');  // accessors need aligned offsets
    const size_t offset = bin.size();
    bin.append(static_cast<const char*>(data), bytes);
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
    return static_cast<int>(j["bufferViews"].size() - 1);
  };
  auto addAccessor = [&](int view, int componentType, size_t count, const char* type) {
    j["accessors"].push_back({{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    return static_cast<int>(j["accessors"].size() - 1);
  };
  for (const Material& m : scene.materials) {
    j["materials"].push_back(materialJson(m));
    if (j["materials"].back().contains("extensions"))
      j["extensionsUsed"] = json::array({"KHR_materials_emissive_strength"});
  }
  json roots = json::array();
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& mesh = scene.meshes[i];
    if (mesh.positions.empty() || mesh.indices.empty()) continue;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : mesh.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    json attributes;
    const int pos = addAccessor(addView(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3), 34962), 5126,
                                mesh.positions.size(), "VEC3");
    j["accessors"][pos]["min"] = vec3Json(lo);  // required for POSITION
    j["accessors"][pos]["max"] = vec3Json(hi);
    attributes["POSITION"] = pos;
    if (mesh.normals.size() == mesh.positions.size())
      attributes["NORMAL"] = addAccessor(addView(mesh.normals.data(), mesh.normals.size() * sizeof(glm::vec3), 34962),
                                         5126, mesh.normals.size(), "VEC3");
    if (mesh.uvs.size() == mesh.positions.size())
      attributes["TEXCOORD_0"] = addAccessor(addView(mesh.uvs.data(), mesh.uvs.size() * sizeof(glm::vec2), 34962), 5126,
                                             mesh.uvs.size(), "VEC2");
    const int indices = addAccessor(addView(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t), 34963),
                                    5125, mesh.indices.size(), "SCALAR");
    json primitive = {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
    if (mesh.material >= 0 && static_cast<size_t>(mesh.material) < scene.materials.size())
      primitive["material"] = mesh.material;
    j["meshes"].push_back({{"name", scene.name + " mesh " + std::to_string(i)}, {"primitives", json::array({primitive})}});
    j["nodes"].push_back({{"mesh", j["meshes"].size() - 1}, {"matrix", matrixJson(mesh.worldFromModel)}});
    roots.push_back(j["nodes"].size() - 1);
  }
  if (scene.camera) {
    const Camera& c = *scene.camera;
    json cam;
    if (c.orthographic) {
      cam = {{"type", "orthographic"},
             {"orthographic", {{"xmag", c.orthoHeight / 2}, {"ymag", c.orthoHeight / 2}, {"znear", c.nearPlane}, {"zfar", c.farPlane}}}};
    } else {
      cam = {{"type", "perspective"},
             {"perspective", {{"yfov", glm::radians(c.fovyDegrees)}, {"znear", c.nearPlane}, {"zfar", c.farPlane}}}};
    }
    j["cameras"].push_back(cam);
    j["nodes"].push_back({{"camera", 0}, {"matrix", matrixJson(glm::inverse(c.viewFromWorld()))}});
    roots.push_back(j["nodes"].size() - 1);
  }
  j["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
  j["scenes"] = json::array({{{"name", scene.name}, {"nodes", roots}}});
  j["scene"] = 0;
  return j.dump(1) + "\n";
}

}  // namespace sslr::host
