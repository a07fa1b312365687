#include "sslr_host/gltf_loader.hpp"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace sslr::host {

namespace {

struct LoadError {
  std::string message;
};

// Bounds-checked view of one accessor's elements.
struct AccessorView {
  const unsigned char* data = nullptr;
  size_t count = 0, stride = 0;
  int componentType = 0, components = 0;
  bool normalized = false;

  double component(size_t element, int c) const {
    const unsigned char* p = data + element * stride;
    switch (componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p + 4 * c, 4); return v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { double v = p[c]; return normalized ? v / 255.0 : v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v; std::memcpy(&v, p + 2 * c, 2); return normalized ? v / 65535.0 : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t v; std::memcpy(&v, p + 4 * c, 4); return v; }
      default: return 0.0;
    }
  }
};

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    default: return "other";
  }
}

AccessorView viewAccessor(const tinygltf::Model& model, int index, const std::string& where,
                          int wantType, std::initializer_list<int> allowedComponents) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    throw LoadError{where + ": accessor " + std::to_string(index) + " does not exist"};
  const tinygltf::Accessor& a = model.accessors[index];
  const std::string what = where + " (accessor " + std::to_string(index) + ")";
  if (a.type != wantType)
    throw LoadError{what + ": type is " + typeName(a.type) + ", expected " + typeName(wantType)};
  bool allowed = false;
  for (int c : allowedComponents) allowed = allowed || c == a.componentType;
  if (!allowed)
    throw LoadError{what + ": unsupported component type " + std::to_string(a.componentType)};
  if (a.sparse.isSparse) throw LoadError{what + ": sparse accessors are not supported"};
  if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model.bufferViews.size()))
    throw LoadError{what + ": has no valid bufferView"};
  const tinygltf::BufferView& bv = model.bufferViews[a.bufferView];
  if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size()))
    throw LoadError{what + ": bufferView " + std::to_string(a.bufferView) + " names a missing buffer"};
  const tinygltf::Buffer& buffer = model.buffers[bv.buffer];
  const int compSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  const int comps = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
  const size_t elemSize = static_cast<size_t>(compSize) * comps;
  const size_t stride = bv.byteStride != 0 ? bv.byteStride : elemSize;
  if (stride < elemSize) throw LoadError{what + ": byteStride is smaller than an element"};
  if (bv.byteOffset + bv.byteLength > buffer.data.size())
    throw LoadError{what + ": bufferView " + std::to_string(a.bufferView) + " runs past the end of buffer " +
                    std::to_string(bv.buffer) + " (" + std::to_string(bv.byteOffset + bv.byteLength) +
                    " > " + std::to_string(buffer.data.size()) + " bytes): the buffer is missing or short"};
  if (a.count > 0 && a.byteOffset + stride * (a.count - 1) + elemSize > bv.byteLength)
    throw LoadError{what + ": " + std::to_string(a.count) + " elements run past the end of bufferView " +
                    std::to_string(a.bufferView)};
  AccessorView v;
  v.data = buffer.data.data() + bv.byteOffset + a.byteOffset;
  v.count = a.count;
  v.stride = stride;
  v.componentType = a.componentType;
  v.components = comps;
  v.normalized = a.normalized;
  return v;
}

glm::dmat4 nodeMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::dmat4 m;
    for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = n.matrix[i];
    return m;
  }
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3) m = glm::translate(m, {n.translation[0], n.translation[1], n.translation[2]});
  if (n.rotation.size() == 4)
    m *= glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3) m = glm::scale(m, {n.scale[0], n.scale[1], n.scale[2]});
  return m;
}

bool finiteMatrix(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

void loadMaterials(const tinygltf::Model& model, Scene& scene) {
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const auto& pbr = model.materials[i].pbrMetallicRoughness;
    Material m;
    if (pbr.baseColorFactor.size() >= 3)
      m.baseColor = glm::vec3(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
    m.metallic = static_cast<float>(pbr.metallicFactor);
    m.roughness = static_cast<float>(pbr.roughnessFactor);
    if (!std::isfinite(m.baseColor.r + m.baseColor.g + m.baseColor.b + m.metallic + m.roughness))
      throw LoadError{"material " + std::to_string(i) + ": factors are not finite"};
    m.baseColor = glm::clamp(m.baseColor, 0.0f, 1.0f);
    m.metallic = glm::clamp(m.metallic, 0.0f, 1.0f);
    m.roughness = glm::clamp(m.roughness, 0.0f, 1.0f);
    const int tex = pbr.baseColorTexture.index;
    if (tex >= 0) {
      if (tex >= static_cast<int>(model.textures.size()) || model.textures[tex].source < 0 ||
          model.textures[tex].source >= static_cast<int>(model.images.size())) {
        scene.warnings.push_back("material " + std::to_string(i) + ": base colour texture " +
                                 std::to_string(tex) + " is missing; using the factor only");
      } else {
        const tinygltf::Image& img = model.images[model.textures[tex].source];
        if (img.width <= 0 || img.height <= 0 || img.bits != 8 || img.component < 1 ||
            img.image.size() < static_cast<size_t>(img.width) * img.height * img.component) {
          scene.warnings.push_back("material " + std::to_string(i) + ": base colour image '" + img.uri +
                                   "' could not be decoded (8-bit images only); using the factor only");
        } else {
          Texture t;
          t.width = img.width;
          t.height = img.height;
          t.rgba8.resize(static_cast<size_t>(img.width) * img.height * 4);
          // Grey (1-2 channels) is replicated; alpha is 255 unless the image has one.
          const int n = img.component;
          for (size_t p = 0; p < static_cast<size_t>(img.width) * img.height; ++p) {
            const unsigned char* src = &img.image[p * n];
            for (int c = 0; c < 3; ++c) t.rgba8[p * 4 + c] = src[n >= 3 ? c : 0];
            t.rgba8[p * 4 + 3] = n == 4 ? src[3] : (n == 2 ? src[1] : 255);
          }
          scene.textures.push_back(std::move(t));
          m.baseColorTexture = static_cast<int>(scene.textures.size() - 1);
        }
      }
    }
    scene.materials.push_back(m);
  }
  scene.materials.push_back(Material{});  // default material for primitives without one
}

void loadPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                   const glm::dmat4& worldFromModel, Scene& scene) {
  if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) {
    scene.warnings.push_back(where + ": mode " + std::to_string(prim.mode) +
                             " is not TRIANGLES; primitive skipped");
    return;
  }
  auto pos = prim.attributes.find("POSITION");
  if (pos == prim.attributes.end()) throw LoadError{where + ": has no POSITION attribute"};
  AccessorView pv = viewAccessor(model, pos->second, where + " POSITION", TINYGLTF_TYPE_VEC3,
                                 {TINYGLTF_COMPONENT_TYPE_FLOAT});
  Mesh mesh;
  mesh.worldFromModel = worldFromModel;
  mesh.positions.resize(pv.count);
  for (size_t i = 0; i < pv.count; ++i) {
    glm::dvec3 p(pv.component(i, 0), pv.component(i, 1), pv.component(i, 2));
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw LoadError{where + ": POSITION " + std::to_string(i) + " is NaN or infinite"};
    mesh.positions[i] = glm::vec3(p);
  }
  if (prim.indices >= 0) {
    AccessorView iv = viewAccessor(model, prim.indices, where + " indices", TINYGLTF_TYPE_SCALAR,
                                   {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    iv.normalized = false;
    for (size_t i = 0; i < iv.count; ++i) {
      const double idx = iv.component(i, 0);
      if (idx >= static_cast<double>(pv.count))
        throw LoadError{where + ": index " + std::to_string(static_cast<long long>(idx)) +
                        " (element " + std::to_string(i) + ") >= vertex count " + std::to_string(pv.count)};
      mesh.indices.push_back(static_cast<std::uint32_t>(idx));
    }
  } else {
    for (size_t i = 0; i < pv.count; ++i) mesh.indices.push_back(static_cast<std::uint32_t>(i));
  }
  if (mesh.indices.size() % 3 != 0) {
    scene.warnings.push_back(where + ": index count " + std::to_string(mesh.indices.size()) +
                             " is not a multiple of 3; trailing indices dropped");
    mesh.indices.resize(mesh.indices.size() / 3 * 3);
  }
  if (mesh.indices.empty()) {
    scene.warnings.push_back(where + ": no triangles; primitive skipped");
    return;
  }
  auto nrm = prim.attributes.find("NORMAL");
  if (nrm != prim.attributes.end()) {
    AccessorView nv = viewAccessor(model, nrm->second, where + " NORMAL", TINYGLTF_TYPE_VEC3,
                                   {TINYGLTF_COMPONENT_TYPE_FLOAT});
    if (nv.count != pv.count) throw LoadError{where + ": NORMAL count differs from POSITION count"};
    for (size_t i = 0; i < nv.count; ++i) {
      glm::vec3 n(nv.component(i, 0), nv.component(i, 1), nv.component(i, 2));
      const float len = glm::length(n);
      mesh.normals.push_back(std::isfinite(len) && len > 1e-12f ? n / len : glm::vec3(0, 0, 1));
    }
  } else {
    // No normals: area-weighted vertex normals from the triangles.
    mesh.normals.assign(pv.count, glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                      c = mesh.positions[mesh.indices[t + 2]];
      const glm::vec3 n = glm::cross(b - a, c - a);
      for (int k = 0; k < 3; ++k) mesh.normals[mesh.indices[t + k]] += n;
    }
    for (auto& n : mesh.normals) {
      const float len = glm::length(n);
      n = len > 1e-20f ? n / len : glm::vec3(0, 0, 1);
    }
  }
  auto uv = prim.attributes.find("TEXCOORD_0");
  if (uv != prim.attributes.end()) {
    AccessorView uvv = viewAccessor(model, uv->second, where + " TEXCOORD_0", TINYGLTF_TYPE_VEC2,
                                    {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
    if (uvv.count != pv.count) throw LoadError{where + ": TEXCOORD_0 count differs from POSITION count"};
    for (size_t i = 0; i < uvv.count; ++i) {
      glm::vec2 t(uvv.component(i, 0), uvv.component(i, 1));
      mesh.uvs.push_back(std::isfinite(t.x) && std::isfinite(t.y) ? t : glm::vec2(0.0f));
    }
  }
  const int defaultMaterial = static_cast<int>(scene.materials.size()) - 1;
  mesh.material = prim.material >= 0 && prim.material < defaultMaterial ? prim.material : defaultMaterial;
  if (prim.material >= defaultMaterial)
    scene.warnings.push_back(where + ": material " + std::to_string(prim.material) +
                             " does not exist; using the default material");
  scene.meshes.push_back(std::move(mesh));
}

}  // namespace

Expected<Scene> loadGltf(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return Status::error(path + ": file not found");
  if (!fs::is_regular_file(path, ec)) return Status::error(path + ": not a regular file");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = path.size() >= 4 && (path.substr(path.size() - 4) == ".glb" || path.substr(path.size() - 4) == ".GLB");
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  } catch (const std::exception& e) {
    return Status::error(path + ": malformed glTF: " + e.what());
  }
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    return Status::error(path + ": cannot load glTF: " + (err.empty() ? "unknown error" : err));
  }
  Scene scene;
  scene.name = fs::path(path).filename().string();
  if (!warn.empty()) scene.warnings.push_back(warn);
  try {
    loadMaterials(model, scene);
    std::optional<Camera> camera;
    std::vector<int> visiting;
    std::function<void(int, const glm::dmat4&)> visit = [&](int nodeIndex, const glm::dmat4& parent) {
      if (nodeIndex < 0 || nodeIndex >= static_cast<int>(model.nodes.size()))
        throw LoadError{"node " + std::to_string(nodeIndex) + " does not exist"};
      if (std::find(visiting.begin(), visiting.end(), nodeIndex) != visiting.end())
        throw LoadError{"node " + std::to_string(nodeIndex) + " is its own ancestor (cycle)"};
      visiting.push_back(nodeIndex);
      const tinygltf::Node& node = model.nodes[nodeIndex];
      const glm::dmat4 world = parent * nodeMatrix(node);
      if (!finiteMatrix(world)) throw LoadError{"node " + std::to_string(nodeIndex) + ": transform is not finite"};
      if (node.mesh >= 0) {
        if (node.mesh >= static_cast<int>(model.meshes.size()))
          throw LoadError{"node " + std::to_string(nodeIndex) + ": mesh " + std::to_string(node.mesh) + " does not exist"};
        const auto& prims = model.meshes[node.mesh].primitives;
        for (size_t p = 0; p < prims.size(); ++p)
          loadPrimitive(model, prims[p], "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p),
                        world, scene);
      }
      if (node.camera >= 0 && !camera && node.camera < static_cast<int>(model.cameras.size())) {
        const tinygltf::Camera& gc = model.cameras[node.camera];
        Camera c;
        c.eye = glm::dvec3(world * glm::dvec4(0, 0, 0, 1));
        c.target = c.eye + glm::normalize(glm::dvec3(world * glm::dvec4(0, 0, -1, 0)));
        c.up = glm::normalize(glm::dvec3(world * glm::dvec4(0, 1, 0, 0)));
        if (gc.type == "orthographic") {
          c.orthographic = true;
          c.orthoHeight = 2.0 * gc.orthographic.ymag;
          c.nearPlane = std::max(gc.orthographic.znear, 1e-4);
          c.farPlane = gc.orthographic.zfar;
        } else {
          c.fovyDegrees = glm::degrees(gc.perspective.yfov);
          c.nearPlane = gc.perspective.znear;
          // glTF allows an infinite far plane (zfar = 0); the tools need a finite one.
          c.farPlane = gc.perspective.zfar > 0.0 ? gc.perspective.zfar : gc.perspective.znear * 1e5;
        }
        if (std::string why = c.validate(); why.empty())
          camera = c;
        else
          scene.warnings.push_back("camera " + std::to_string(node.camera) + " ignored: " + why);
      }
      for (int child : node.children) visit(child, world);
      visiting.pop_back();
    };
    std::vector<int> roots;
    if (!model.scenes.empty()) {
      const int s = model.defaultScene >= 0 && model.defaultScene < static_cast<int>(model.scenes.size())
                        ? model.defaultScene : 0;
      roots = model.scenes[s].nodes;
    } else {
      // No scene: every node that is nobody's child is a root.
      std::vector<bool> isChild(model.nodes.size(), false);
      for (const auto& n : model.nodes)
        for (int c : n.children)
          if (c >= 0 && c < static_cast<int>(isChild.size())) isChild[c] = true;
      for (size_t i = 0; i < model.nodes.size(); ++i)
        if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    for (int r : roots) visit(r, glm::dmat4(1.0));
    if (scene.meshes.empty()) throw LoadError{"the scene has no triangle meshes"};
    scene.camera = camera;
  } catch (const LoadError& e) {
    return Status::error(path + ": " + e.message);
  }
  return scene;
}

}  // namespace sslr::host
