// libFuzzer entry for the glTF/GLB loader: the input becomes a .glb (when it starts with the GLB
// magic) or a .gltf file in a private folder and goes through loadGltf, as sslr-render would
// read it. Besides ASan/UBSan findings, a loaded scene that breaks the loader's promises aborts:
// indices inside their mesh, one normal per position, finite data, materials that exist.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "sslr_host/gltf_loader.hpp"

namespace {

const std::string& workDir() {
  static const std::string dir = [] {
    std::string tmpl = (std::filesystem::temp_directory_path() / "sslr-fuzz-XXXXXX").string();
    if (mkdtemp(tmpl.data()) == nullptr) std::abort();
    return tmpl;
  }();
  return dir;
}

void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "loader promise broken: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = workDir() + (glb ? "/input.glb" : "/input.gltf");
  FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  auto scene = sslr::host::loadGltf(path);
  if (!scene) {
    require(!scene.error().empty(), "a refusal without a message");
    return 0;
  }
  const sslr::host::Scene& s = scene.value();
  for (const sslr::host::Mesh& m : s.meshes) {
    require(m.normals.size() == m.positions.size(), "one normal per position");
    require(m.uvs.empty() || m.uvs.size() == m.positions.size(), "one uv per position or none");
    require(m.indices.size() % 3 == 0, "whole triangles");
    for (std::uint32_t i : m.indices) require(i < m.positions.size(), "indices inside their mesh");
    for (const auto& p : m.positions) require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "finite positions");
    require(m.material >= 0 && static_cast<std::size_t>(m.material) < s.materials.size(), "materials that exist");
  }
  for (const sslr::host::Texture& t : s.textures)
    require(t.rgba8.size() == static_cast<std::size_t>(t.width) * t.height * 4, "texture sizes that match");
  // What the renderer and the ground truth do with a loaded scene before any GL call: frame it,
  // validate the camera, and carry every normal into view space (the normal matrix of each node's
  // transform, singular or extreme ones included) with a finite result.
  if (!s.checkExtent().empty()) return 0;  // refused by the tools with that message
  const sslr::host::Camera camera = s.camera ? *s.camera : s.defaultCamera();
  if (!camera.validate().empty()) return 0;
  const glm::dmat4 viewFromWorld = camera.viewFromWorld();
  for (const sslr::host::Mesh& m : s.meshes) {
    const glm::mat3 normalMatrix(sslr::host::normalMatrixOf(viewFromWorld * m.worldFromModel));
    for (const auto& n : m.normals) {
      const glm::vec3 v = normalMatrix * n;
      require(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), "finite view-space normals");
    }
  }
  return 0;
}
