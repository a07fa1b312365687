#include "sslr_host/gltf_loader.hpp"

#include "gltf_internal.hpp"

#include "sslr_host/image_decode.hpp"

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace sslr::host {

namespace {

using namespace gltf;

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
  size_t viewEnd = 0;
  if (addOverflows(bv.byteOffset, bv.byteLength, viewEnd) || viewEnd > buffer.data.size())
    throw LoadError{what + ": bufferView " + std::to_string(a.bufferView) + " (byteOffset " +
                    std::to_string(bv.byteOffset) + ", byteLength " + std::to_string(bv.byteLength) +
                    ") runs past the end of buffer " + std::to_string(bv.buffer) + " (" +
                    std::to_string(buffer.data.size()) + " bytes): the buffer is missing or short"};
  size_t span = 0, last = 0, end = 0;
  if (a.byteOffset > bv.byteLength ||
      (a.count > 0 && (mulOverflows(stride, a.count - 1, span) || addOverflows(span, elemSize, last) ||
                       addOverflows(a.byteOffset, last, end) || end > bv.byteLength)))
    throw LoadError{what + ": " + std::to_string(a.count) + " elements of " + std::to_string(elemSize) +
                    " bytes from byteOffset " + std::to_string(a.byteOffset) + " run past the end of bufferView " +
                    std::to_string(a.bufferView) + " (" + std::to_string(bv.byteLength) + " bytes)"};
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

// Features the tools do not render, each reported once per file.
using Ignored = std::set<std::string>;

// KHR_materials_emissive_strength: the factor that scales emissiveFactor past 1 (HDR emitters); 1
// without the extension.
float emissiveStrength(const tinygltf::Material& material, size_t index) {
  const auto ext = material.extensions.find("KHR_materials_emissive_strength");
  if (ext == material.extensions.end() || !ext->second.Has("emissiveStrength")) return 1.0f;
  const tinygltf::Value& v = ext->second.Get("emissiveStrength");
  const double strength = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
  // Bounded so that emission stays finite in the G-buffer's R11G11B10F colour (at most 65,000).
  if (!(strength >= 0.0 && strength <= 65000.0))
    throw LoadError{"material " + std::to_string(index) +
                    ": KHR_materials_emissive_strength's emissiveStrength must be a number in [0, 65000]"};
  return static_cast<float>(strength);
}

void loadMaterials(const tinygltf::Model& model, Scene& scene, Ignored& ignored) {
  std::map<int, int> textureOfImage;
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const auto& pbr = model.materials[i].pbrMetallicRoughness;
    Material m;
    if (pbr.baseColorFactor.size() >= 3)
      m.baseColor = glm::vec3(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
    m.metallic = static_cast<float>(pbr.metallicFactor);
    m.roughness = static_cast<float>(pbr.roughnessFactor);
    if (!std::isfinite(m.baseColor.r + m.baseColor.g + m.baseColor.b + m.metallic + m.roughness))
      throw LoadError{"material " + std::to_string(i) + ": factors are not finite"};
    const auto& e = model.materials[i].emissiveFactor;
    if (e.size() >= 3) m.emissiveColor = glm::vec3(e[0], e[1], e[2]);
    if (!std::isfinite(m.emissiveColor.r + m.emissiveColor.g + m.emissiveColor.b))
      throw LoadError{"material " + std::to_string(i) + ": emissiveFactor is not finite"};
    m.emissiveColor = glm::clamp(m.emissiveColor, 0.0f, 1.0f) * emissiveStrength(model.materials[i], i);
    if (model.materials[i].emissiveTexture.index >= 0) ignored.insert("emissive textures (the emissive factor is used)");
    if (model.materials[i].normalTexture.index >= 0) ignored.insert("normal maps");
    if (pbr.metallicRoughnessTexture.index >= 0)
      ignored.insert("metallic-roughness textures (the factors are used)");
    if (model.materials[i].alphaMode != "OPAQUE" && !model.materials[i].alphaMode.empty())
      ignored.insert("alpha modes MASK and BLEND (drawn opaque)");
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
          scene.warnings.push_back("material " + std::to_string(i) + ": base colour image '" + printable(img.uri) +
                                   "' was not decoded; using the factor only");
        } else if (auto shared = textureOfImage.find(model.textures[tex].source); shared != textureOfImage.end()) {
          m.baseColorTexture = shared->second;  // one texture per image, however many materials use it
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
          textureOfImage[model.textures[tex].source] = m.baseColorTexture;
        }
      }
    }
    scene.materials.push_back(m);
  }
  scene.materials.push_back(Material{});  // default material for primitives without one
}

// Triangle lists from TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN index sequences (glTF 2.0, 3.7.2.1:
// strip triangle i = (i, i+1, i+2) with every other one flipped to keep the winding; fan = (0, i+1, i+2)).
std::vector<std::uint32_t> triangleList(int mode, const std::vector<std::uint32_t>& seq) {
  if (mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) return seq;
  std::vector<std::uint32_t> out;
  for (size_t i = 0; i + 2 < seq.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) out.insert(out.end(), {seq[0], seq[i + 1], seq[i + 2]});
    else if (i % 2 == 0) out.insert(out.end(), {seq[i], seq[i + 1], seq[i + 2]});
    else out.insert(out.end(), {seq[i + 1], seq[i], seq[i + 2]});
  }
  return out;
}

// The primitive's normals (unit length; (0, 0, 1) where a stored one is degenerate), or without a
// NORMAL attribute area-weighted vertex normals from its triangles.
void loadNormals(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                 size_t vertexCount, Mesh& mesh) {
  auto nrm = prim.attributes.find("NORMAL");
  if (nrm != prim.attributes.end()) {
    AccessorView nv = viewAccessor(model, nrm->second, where + " NORMAL", TINYGLTF_TYPE_VEC3,
                                   {TINYGLTF_COMPONENT_TYPE_FLOAT});
    if (nv.count != vertexCount) throw LoadError{where + ": NORMAL count differs from POSITION count"};
    for (size_t i = 0; i < nv.count; ++i) {
      glm::vec3 n(nv.component(i, 0), nv.component(i, 1), nv.component(i, 2));
      const float len = glm::length(n);
      mesh.normals.push_back(std::isfinite(len) && len > 1e-12f ? n / len : glm::vec3(0, 0, 1));
    }
  } else {
    // No normals: area-weighted vertex normals from the triangles.
    mesh.normals.assign(vertexCount, glm::vec3(0.0f));
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
}

void loadPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                   const glm::dmat4& worldFromModel, Scene& scene, Ignored& ignored) {
  const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    ignored.insert("points and lines (primitive modes 0-3)");
    return;
  }
  if (!prim.targets.empty()) ignored.insert("morph targets (meshes drawn without them)");
  if (prim.attributes.count("JOINTS_0") != 0) ignored.insert("skins (meshes drawn in their bind pose)");
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
  mesh.indices = triangleList(mode, mesh.indices);
  if (mesh.indices.size() % 3 != 0) {
    scene.warnings.push_back(where + ": index count " + std::to_string(mesh.indices.size()) +
                             " is not a multiple of 3; trailing indices dropped");
    mesh.indices.resize(mesh.indices.size() / 3 * 3);
  }
  if (mesh.indices.empty()) {
    scene.warnings.push_back(where + ": no triangles; primitive skipped");
    return;
  }
  loadNormals(model, prim, where, pv.count, mesh);
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

// What sslr's glTF writer stores where glTF has no field (gltf_writer.hpp): asset.extras.sslr
// {background: [r,g,b], lightDirection: [x,y,z]}. Values that are not three finite numbers (or a
// zero light direction) are ignored with a warning.
void readSslrExtras(const tinygltf::Value& extras, Scene& scene) {
  if (!extras.IsObject() || !extras.Has("sslr")) return;
  const tinygltf::Value& x = extras.Get("sslr");
  auto vec3 = [&](const char* key, glm::vec3& out) {
    if (!x.IsObject() || !x.Has(key)) return false;
    const tinygltf::Value& a = x.Get(key);
    if (!a.IsArray() || a.ArrayLen() != 3) return false;
    glm::vec3 v;
    for (int i = 0; i < 3; ++i) {
      if (!a.Get(i).IsNumber()) return false;
      v[i] = static_cast<float>(a.Get(i).GetNumberAsDouble());
    }
    if (!std::isfinite(v.x + v.y + v.z)) return false;
    out = v;
    return true;
  };
  glm::vec3 background, light;
  if (vec3("background", background)) scene.background = glm::clamp(background, 0.0f, 1e4f);
  else if (x.IsObject() && x.Has("background")) scene.warnings.push_back("asset.extras.sslr.background ignored (not 3 finite numbers)");
  if (vec3("lightDirection", light) && glm::length(light) > 1e-6f) scene.lightDirection = glm::normalize(light);
  else if (x.IsObject() && x.Has("lightDirection"))
    scene.warnings.push_back("asset.extras.sslr.lightDirection ignored (not a finite non-zero vector)");
}


// The default scene's root nodes (every parentless node without a scene), after checking that each
// node has at most one parent and each root none: the walk below is then a forest walk.
std::vector<int> sceneRoots(const tinygltf::Model& model) {
  // glTF allows one parent per node and scene roots without parents: check it before instancing
  // (a node listed twice as a child turns 20 nodes into 2^20 instances) and so the traversal below
  // is a forest walk, iterative, whatever the file's depth.
  const size_t nodeCount = model.nodes.size();
  std::vector<int> parent(nodeCount, -1);
  for (size_t i = 0; i < nodeCount; ++i)
    for (int child : model.nodes[i].children) {
      if (child < 0 || static_cast<size_t>(child) >= nodeCount)
        throw LoadError{"node " + std::to_string(i) + " lists child " + std::to_string(child) + ", which does not exist"};
      if (parent[child] >= 0)
        throw LoadError{"node " + std::to_string(child) + " has more than one parent (nodes " +
                        std::to_string(parent[child]) + " and " + std::to_string(i) +
                        "); glTF allows one parent per node"};
      parent[child] = static_cast<int>(i);
    }
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 && model.defaultScene < static_cast<int>(model.scenes.size())
                      ? model.defaultScene : 0;
    roots = model.scenes[s].nodes;
    for (int r : roots) {
      if (r < 0 || static_cast<size_t>(r) >= nodeCount)
        throw LoadError{"scene " + std::to_string(s) + " lists node " + std::to_string(r) + ", which does not exist"};
      if (parent[r] >= 0)
        throw LoadError{"scene " + std::to_string(s) + " lists node " + std::to_string(r) +
                        " as a root, but node " + std::to_string(parent[r]) + " is its parent (a cycle or a shared node)"};
    }
  } else {
    // No scene: every node that is nobody's child is a root.
    for (size_t i = 0; i < nodeCount; ++i)
      if (parent[i] < 0) roots.push_back(static_cast<int>(i));
  }
  return roots;
}

// The glTF camera of a node (world: the node's transform), or none with a warning if invalid.
std::optional<Camera> nodeCamera(const tinygltf::Camera& gc, int cameraIndex, const glm::dmat4& world, Scene& scene) {
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
  if (std::string why = c.validate(); !why.empty()) {
    scene.warnings.push_back("camera " + std::to_string(cameraIndex) + " ignored: " + why);
    return std::nullopt;
  }
  return c;
}

// Walks the node forest from `roots`: each mesh instance with its world transform, and the first
// valid camera.
std::vector<std::pair<int, glm::dmat4>> walkNodes(const tinygltf::Model& model, const std::vector<int>& roots,
                                                  Scene& scene, Ignored& ignored, std::optional<Camera>& camera) {
  const size_t nodeCount = model.nodes.size();
  std::vector<std::pair<int, glm::dmat4>> instances;  // mesh, worldFromModel: one copy each
  std::vector<bool> visited(nodeCount, false);
  std::vector<std::pair<int, glm::dmat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::dmat4(1.0));
  while (!stack.empty()) {
    const auto [nodeIndex, parentWorld] = stack.back();
    stack.pop_back();
    // With one parent per node and parentless roots, a node is reached once; a repeated root
    // in the scene list is the only way back.
    if (visited[nodeIndex]) throw LoadError{"node " + std::to_string(nodeIndex) + " is listed twice in the scene"};
    visited[nodeIndex] = true;
    const tinygltf::Node& node = model.nodes[nodeIndex];
    const glm::dmat4 world = parentWorld * nodeMatrix(node);
    if (!finiteMatrix(world)) throw LoadError{"node " + std::to_string(nodeIndex) + ": transform is not finite"};
    if (node.skin >= 0) ignored.insert("skins (meshes drawn in their bind pose)");
    if (node.mesh >= 0) {
      if (node.mesh >= static_cast<int>(model.meshes.size()))
        throw LoadError{"node " + std::to_string(nodeIndex) + ": mesh " + std::to_string(node.mesh) + " does not exist"};
      instances.emplace_back(node.mesh, world);
    }
    if (node.camera >= 0 && !camera && node.camera < static_cast<int>(model.cameras.size()))
      camera = nodeCamera(model.cameras[node.camera], node.camera, world, scene);
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.emplace_back(*it, world);
  }
  return instances;
}

// Reads and parses the file at `path` into `model` (glTF 2.0, no unsupported required extension);
// external buffers and images only from the file's own folder. An error names the file.
Status parseModel(const std::string& path, tinygltf::Model& model, std::string& warn) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // The model is read once, through the descriptor that was checked; what follows parses those
  // bytes (tinygltf reads only the external buffers and images, through the jail below).
  std::vector<unsigned char> file;
  if (std::string why = readChecked(path, nullptr, kMaxExternalFileBytes, file); !why.empty())
    return Status::error(path + ": " + why);
  FolderJail jail;
  jail.modelFile = fs::weakly_canonical(fs::path(path), ec).string();
  jail.root = fs::path(jail.modelFile).parent_path();
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&jailFileExists, &jailExpandFilePath, &jailReadWholeFile, &jailWriteWholeFile, &jail});
  ImageBudget imageBudget{&model, 0};
  loader.SetImageLoader(&limitedImageLoader, &imageBudget);  // it checks views against model.buffers
  std::string err;
  // A GLB by its magic, whatever the file's name says.
  const bool binary = file.size() >= 4 && std::memcmp(file.data(), "glTF", 4) == 0;
  if (std::string why = precheck(file, binary); !why.empty()) return Status::error(path + ": " + why);
  const std::string baseDir = jail.root.string();
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, file.data(), static_cast<unsigned>(file.size()), baseDir)
                : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(file.data()),
                                             static_cast<unsigned>(file.size()), baseDir);
  } catch (const std::bad_alloc&) {
    return Status::error(path + ": out of memory while parsing (a buffer or image larger than memory?)");
  } catch (const std::exception& e) {
    return Status::error(path + ": malformed glTF: " + printable(e.what()));
  }
  file = {};
  if (!ok) {
    if (model.asset.version.rfind("1.", 0) == 0)
      return Status::error(path + ": glTF " + printable(model.asset.version, 16) + " is not supported (glTF 2.0 only)");
    return Status::error(path + ": cannot load glTF: " + (err.empty() ? "unknown error" : printable(err, 400)));
  }
  if (model.asset.version.rfind("2.", 0) != 0)
    return Status::error(path + ": glTF version '" + printable(model.asset.version, 16) + "' is not supported (glTF 2.0 only)");
  // Required extensions change what the data means (compressed geometry, quantized attributes):
  // a file that needs one the tools do not implement is refused, naming it.
  if (!model.extensionsRequired.empty()) {
    std::string names;
    for (const std::string& e : model.extensionsRequired) names += (names.empty() ? "" : ", ") + printable(e, 80);
    return Status::error(path + ": requires extension(s) " + names + ", which the tools do not support");
  }
  return Status{};
}

}  // namespace

Expected<Scene> loadGltf(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return Status::error(path + ": file not found");
  tinygltf::Model model;
  std::string warn;
  if (Status st = parseModel(path, model, warn); !st) return st;
  Scene scene;
  scene.name = fs::path(path).filename().string();
  if (!warn.empty()) scene.warnings.push_back(printable(warn, 400));
  readSslrExtras(model.asset.extras, scene);
  try {
    Ignored ignored;
    loadMaterials(model, scene, ignored);
    if (!model.skins.empty()) ignored.insert("skins (meshes drawn in their bind pose)");
    if (!model.animations.empty()) ignored.insert("animations (the scene is drawn at rest)");
    for (const std::string& ext : model.extensionsUsed)
      if (ext != "KHR_materials_emissive_strength" &&
          std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(), ext) ==
              model.extensionsRequired.end())
        ignored.insert("extension " + printable(ext, 80));
    const std::vector<int> roots = sceneRoots(model);
    std::optional<Camera> camera;
    const auto instances = walkNodes(model, roots, scene, ignored, camera);
    checkGeometryBudget(model, instances);
    for (const auto& [meshIndex, world] : instances) {
      const auto& prims = model.meshes[static_cast<size_t>(meshIndex)].primitives;
      for (size_t p = 0; p < prims.size(); ++p)
        loadPrimitive(model, prims[p], "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p),
                      world, scene, ignored);
    }
    for (const std::string& what : ignored) scene.warnings.push_back("ignored: " + what);
    if (scene.meshes.empty()) {
      std::string skipped;
      for (const std::string& what : ignored) skipped += (skipped.empty() ? " (ignored: " : "; ") + what;
      throw LoadError{"the scene has no triangle meshes" + (skipped.empty() ? std::string() : skipped + ")")};
    }
    scene.camera = camera;
  } catch (const LoadError& e) {
    return Status::error(path + ": " + e.message);
  } catch (const std::bad_alloc&) {
    return Status::error(path + ": out of memory while building the meshes");
  } catch (const std::exception& e) {
    return Status::error(path + ": " + printable(e.what()));
  }
  return scene;
}

}  // namespace sslr::host
