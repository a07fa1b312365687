#include "sslr_host/gltf_loader.hpp"

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

struct LoadError {
  std::string message;
};

// Sizes and offsets in a glTF file are untrusted 64-bit values: every sum and product of them is
// checked, so a wrapped value can never pass a bounds test.
bool addOverflows(size_t a, size_t b, size_t& sum) { return __builtin_add_overflow(a, b, &sum); }
bool mulOverflows(size_t a, size_t b, size_t& product) { return __builtin_mul_overflow(a, b, &product); }

// Text from a file (an error of the parser may quote it): printable ASCII only, and short, so the
// raw bytes of a binary file never reach the terminal.
std::string printable(const std::string& text, size_t limit = 240) {
  std::string out;
  for (char ch : text) {
    if (out.size() >= limit) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(ch);
    out += (c >= 32 && c < 127) ? ch : (c == '\n' ? ' ' : '?');
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// ---- File access: only inside the model's folder ----------------------------------------------
// tinygltf reads external buffers and images through these callbacks. A URI may name any path
// ("/etc/passwd", "../../x"); a renderer run on files from elsewhere must not read outside the
// model's folder, nor try to read a directory or a huge file into memory.
constexpr std::uintmax_t kMaxExternalFileBytes = std::uintmax_t(2) << 30;  // 2 GiB

struct FolderJail {
  std::filesystem::path root;  // canonical folder of the model file
  std::string modelFile;       // canonical path of the model itself
};

std::string explainOutside(const std::string& path, const FolderJail& jail) {
  return "'" + printable(path) + "' is outside the model's folder " + jail.root.string() +
         " (external buffers and images must lie in that folder or below it)";
}

// Opens `path` and checks what was opened, not the name: a regular file (a FIFO or device is
// never read: the open does not block), of at most `limit` bytes, and, with a jail, inside its
// root (the descriptor's real path, read back from /proc/self/fd). Then reads it through the same
// descriptor, so a file swapped for a link after the check is never what is read. "" on success.
std::string readChecked(const std::string& path, const FolderJail* jail, std::uintmax_t limit,
                        std::vector<unsigned char>& out) {
  namespace fs = std::filesystem;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) return "'" + printable(path) + "': " + std::strerror(errno);
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return "'" + printable(path) + "': " + std::strerror(errno);
  if (!S_ISREG(st.st_mode)) return "'" + printable(path) + "' is not a regular file";
  if (jail != nullptr) {
    std::error_code ec;
    const fs::path opened = fs::read_symlink("/proc/self/fd/" + std::to_string(fd), ec);
    if (ec) return "'" + printable(path) + "': cannot tell where it lies (/proc/self/fd: " + ec.message() + ")";
    if (opened.string() != jail->modelFile) {
      const auto rel = opened.lexically_relative(jail->root);
      if (rel.empty() || *rel.begin() == "..") return explainOutside(path, *jail);
    }
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > limit)
    return "'" + printable(path) + "' is " + std::to_string(size >> 20) + " MiB (more than the " +
           std::to_string(limit >> 20) + " MiB limit)";
  out.resize(static_cast<size_t>(size));
  size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = ::read(fd, out.data() + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return "cannot read '" + printable(path) + "'" + (n < 0 ? std::string(": ") + std::strerror(errno) : "");
    done += static_cast<size_t>(n);
  }
  return {};
}

// Anything that exists "exists" here, so that the read below is attempted and its refusal says why.
bool jailFileExists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

std::string jailExpandFilePath(const std::string& path, void*) { return path; }  // no ~ or $VAR

bool jailReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  if (std::string why = readChecked(path, static_cast<FolderJail*>(user), kMaxExternalFileBytes, *out); !why.empty()) {
    if (err) *err += why + "\n";
    return false;
  }
  return true;
}

bool jailWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported\n";
  return false;
}

// ---- Images: size limits before decoding ---------------------------------------------------------
constexpr int kMaxImageSide = 16384;
// All images of a file together, decoded to RGBA8: a small PNG can stand for a large image, and a
// file can list one many times (each entry decodes on its own).
constexpr std::uint64_t kMaxDecodedImageBytes = std::uint64_t(1) << 30;  // 1 GiB

struct ImageBudget {
  const tinygltf::Model* model = nullptr;  // its buffers are parsed when images are decoded
  std::uint64_t decodedBytes = 0;          // of the images decoded so far
};

// Width and height from a PNG or JPEG header (false: another format or a short header).
bool imageSize(const unsigned char* bytes, int size, int& w, int& h) {
  auto be16 = [&](int at) { return (bytes[at] << 8) | bytes[at + 1]; };
  auto be32 = [&](int at) { return int((unsigned(bytes[at]) << 24) | (unsigned(bytes[at + 1]) << 16) | (unsigned(bytes[at + 2]) << 8) | bytes[at + 3]); };
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  if (size >= 24 && std::memcmp(bytes, png, 8) == 0) {
    w = be32(16);
    h = be32(20);
    return true;
  }
  if (size >= 4 && bytes[0] == 0xff && bytes[1] == 0xd8) {
    int at = 2;
    while (at + 9 < size && bytes[at] == 0xff) {
      const int marker = bytes[at + 1];
      const int length = be16(at + 2);
      // Start-of-frame markers (baseline, progressive, ...) carry the size.
      if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc) {
        h = be16(at + 5);
        w = be16(at + 7);
        return true;
      }
      at += 2 + length;
    }
  }
  return false;
}

// tinygltf's image callback: libpng or libjpeg (image_decode.hpp), never stb_image. An image larger
// than the tools load, or one that does not decode, is left empty with a warning; images that
// together would decode to more than kMaxDecodedImageBytes refuse the file (by their headers,
// before decoding).
bool limitedImageLoader(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int, int,
                        const unsigned char* bytes, int size, void* user) {
  // An image stored in a bufferView arrives as a pointer into the buffer and the view's byteLength:
  // tinygltf 2.7 (Debian 12) does not check that the view lies inside the buffer, so a view past its
  // end had the decoder read past the heap block (found by tests/fuzz). The model's buffers are
  // parsed by now: the view is checked against the bytes the buffer really holds.
  auto& budget = *static_cast<ImageBudget*>(user);
  if (image->bufferView >= 0) {
    const auto& model = *budget.model;
    const size_t viewIndex = static_cast<size_t>(image->bufferView);
    bool inside = viewIndex < model.bufferViews.size();
    if (inside) {
      const tinygltf::BufferView& view = model.bufferViews[viewIndex];
      size_t end = 0;
      inside = view.buffer >= 0 && static_cast<size_t>(view.buffer) < model.buffers.size() &&
               !addOverflows(view.byteOffset, view.byteLength, end) &&
               end <= model.buffers[static_cast<size_t>(view.buffer)].data.size() &&
               view.byteLength <= static_cast<size_t>(std::numeric_limits<int>::max());
    }
    if (!inside) {
      if (err)
        *err += "image " + std::to_string(index) + ": bufferView " + std::to_string(image->bufferView) +
                " runs past the end of its buffer\n";
      return false;
    }
  }
  auto notDecoded = [&](const std::string& why) {
    // The geometry is still good: the image is left empty and its materials keep their factors
    // (loadMaterials warns per material).
    if (warn) *warn += "image " + std::to_string(index) + " ('" + printable(image->uri) + "') not decoded: " + why + "\n";
    image->width = image->height = 0;
    image->image.clear();
    return true;
  };
  auto overBudget = [&](std::uint64_t bytesMore) {
    if (budget.decodedBytes + bytesMore <= kMaxDecodedImageBytes) return false;
    if (err)
      *err += "image " + std::to_string(index) + " ('" + printable(image->uri) + "') would bring the file's decoded images to " +
              std::to_string((budget.decodedBytes + bytesMore) >> 20) + " MiB: the tools load up to " +
              std::to_string(kMaxDecodedImageBytes >> 20) + " MiB of images (RGBA8) per file\n";
    return true;
  };
  int w = 0, h = 0;
  if (imageSize(bytes, size, w, h)) {
    if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide)
      return notDecoded("it is " + std::to_string(w) + "x" + std::to_string(h) + ": the tools load images up to " +
                        std::to_string(kMaxImageSide) + "x" + std::to_string(kMaxImageSide));
    // Counted from the header, before decoding: what the file claims is what it may cost.
    const std::uint64_t claimed = std::uint64_t(w) * std::uint64_t(h) * 4;
    if (overBudget(claimed)) return false;
    budget.decodedBytes += claimed;
  }
  // The decoder's own limit stays as the guard on what it allocates: the header sniff above may
  // miss a JPEG's frame marker.
  DecodedImage decoded;
  if (std::string why = decodePngOrJpeg(bytes, size > 0 ? static_cast<size_t>(size) : 0, kMaxImageSide, decoded);
      !why.empty())
    return notDecoded(printable(why));
  if (w <= 0) {  // a size the header sniff missed, counted once decoded
    if (overBudget(decoded.rgba8.size())) return false;
    budget.decodedBytes += decoded.rgba8.size();
  }
  image->width = decoded.width;
  image->height = decoded.height;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image = std::move(decoded.rgba8);
  return true;
}

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
    m.emissiveColor = glm::clamp(m.emissiveColor, 0.0f, 1.0f);
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

// Every node that draws a mesh gets a copy of its vertices: 65k vertices under 585 nodes come from
// a 2.4 MB buffer. The tools then hold each vertex and index three times: the scene's copy, the
// renderer's upload and the GL buffer (on llvmpipe in system memory too). Their size is known from
// the accessors' counts before anything is built, and a file whose copies would pass the budget
// is refused: the budget keeps a render's peak memory under 2 GB. (A --score run's Embree scene
// comes on top: about 1.5x the scene's copy.)
constexpr std::uint64_t kMaxGeometryBytes = std::uint64_t(5) << 28;  // 1.25 GiB, every copy counted
constexpr std::uint64_t kGeometryCopies = 3;

void checkGeometryBudget(const tinygltf::Model& model, const std::vector<std::pair<int, glm::dmat4>>& instances) {
  // An accessor's count as far as its bufferView could hold it: a count past that is left to
  // viewAccessor's message when the primitive loads.
  auto countOf = [&](int accessor) -> std::uint64_t {
    if (accessor < 0 || static_cast<size_t>(accessor) >= model.accessors.size()) return 0;
    const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(accessor)];
    if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= model.bufferViews.size()) return 0;
    const int elementBytes = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType)) *
                             tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    const size_t viewBytes = model.bufferViews[static_cast<size_t>(a.bufferView)].byteLength;
    return elementBytes > 0 && a.count <= viewBytes / static_cast<size_t>(elementBytes) ? a.count : 0;
  };
  std::uint64_t bytes = 0, vertices = 0, indices = 0;
  for (const auto& instance : instances)
    for (const tinygltf::Primitive& prim : model.meshes[static_cast<size_t>(instance.first)].primitives) {
      auto pos = prim.attributes.find("POSITION");
      const std::uint64_t v = pos == prim.attributes.end() ? 0 : countOf(pos->second);
      const std::uint64_t i = prim.indices >= 0 ? countOf(prim.indices) : v;
      vertices += v;
      indices += i;
      // Position, normal and uv per vertex; a strip or fan's index list grows to 3 per triangle.
      const bool expands = prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP || prim.mode == TINYGLTF_MODE_TRIANGLE_FAN;
      // (Counts are untrusted: each is bounded before it is multiplied.)
      bytes = v > kMaxGeometryBytes || i > kMaxGeometryBytes
                  ? kMaxGeometryBytes + 1
                  : bytes + kGeometryCopies * (v * (sizeof(glm::vec3) * 2 + sizeof(glm::vec2)) +
                                               i * (expands ? 3 : 1) * sizeof(std::uint32_t));
      if (bytes > kMaxGeometryBytes)
        throw LoadError{std::to_string(instances.size()) + " mesh instances (nodes that draw a mesh) with " +
                        std::to_string(vertices) + "+ vertices and " + std::to_string(indices) +
                        "+ indices need more than " + std::to_string(kMaxGeometryBytes >> 20) +
                        " MiB of geometry: the tools load up to " + std::to_string(kMaxGeometryBytes >> 20) +
                        " MiB, each node's copy of its mesh counted " + std::to_string(kGeometryCopies) +
                        " times (the scene's, the upload's and the GL buffer's)"};
    }
}

std::uint32_t le32(const unsigned char* p) { return p[0] | p[1] << 8 | p[2] << 16 | std::uint32_t(p[3]) << 24; }

// A GLB's second chunk (BIN) must lie inside the length its header states, its own 8-byte chunk
// header included. tinygltf 2.7 (Debian 12) forgets those 8 bytes when it checks, and then copies a
// buffer from up to 8 bytes past the end of the file it read (found by the fuzzer). "" when the
// layout is sound or is left to tinygltf's checks.
std::string checkBinChunk(const std::vector<unsigned char>& file, std::uint32_t glbLength, std::uint32_t jsonLength) {
  const std::uint64_t binStart = 20ull + jsonLength;  // where the BIN chunk's header starts
  if (binStart + 8 > glbLength || binStart + 8 > file.size()) return {};  // no BIN chunk, or tinygltf refuses it
  const std::uint64_t binEnd = binStart + 8 + le32(&file[binStart]);
  if (binEnd <= glbLength) return {};
  return "the GLB's BIN chunk (" + std::to_string(le32(&file[binStart])) + " bytes after its header at byte " +
         std::to_string(binStart) + ") ends at byte " + std::to_string(binEnd) + ", past the " +
         std::to_string(glbLength) + " bytes the GLB header states";
}

// Deepest nesting of arrays and objects a file may have. glTF itself needs about 8; tinygltf's
// parser converts JSON to its values recursively, one stack frame per level, and a 41 KB file
// nesting 20,000 deep overflows the stack.
constexpr int kMaxJsonNesting = 128;

// "" if the JSON text nests arrays and objects at most kMaxJsonNesting deep, else where it goes
// deeper. A scan of the bytes (strings and their escapes skipped), so it costs no memory and
// cannot recurse itself.
std::string checkNesting(const unsigned char* json, size_t size) {
  int depth = 0;
  bool inString = false, escaped = false;
  for (size_t i = 0; i < size; ++i) {
    const unsigned char c = json[i];
    if (inString) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonNesting)
        return "the JSON nests arrays and objects more than " + std::to_string(kMaxJsonNesting) +
               " deep (at byte " + std::to_string(i) + "); the tools read files nested up to " +
               std::to_string(kMaxJsonNesting) + " levels";
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return {};
}

// What must be known before tinygltf parses the file: that its JSON is not nested deeper than
// the parser's recursion bears, its glTF version and the extensions it requires (tinygltf rejects a
// Draco-compressed file with "accessor[0] invalid bufferView", and parses glTF 1.0 into an empty
// scene), and of a .glb its layout. `binary`: the file starts with the GLB magic. "" when the file
// may be parsed, else why not. Other malformed input is left to tinygltf's messages.
std::string precheck(const std::vector<unsigned char>& file, bool binary) {
  const unsigned char* json = file.data();
  size_t jsonLength = file.size();
  if (file.empty()) return "the file is empty";
  if (binary) {
    if (file.size() < 20)
      return "the file is " + std::to_string(file.size()) +
             " bytes, shorter than a GLB's 12-byte header and its JSON chunk's 8-byte header";
    jsonLength = le32(&file[12]);
    const bool jsonChunk = file[16] == 'J' && file[17] == 'S' && file[18] == 'O' && file[19] == 'N';
    if (!jsonChunk) return {};  // tinygltf refuses it
    // Whatever the JSON's size: tinygltf copies the BIN chunk either way.
    if (std::string why = checkBinChunk(file, le32(&file[8]), static_cast<std::uint32_t>(jsonLength)); !why.empty())
      return why;
    if (jsonLength > file.size() - 20) return {};  // tinygltf refuses it
    json = &file[20];
  }
  if (std::string why = checkNesting(json, jsonLength); !why.empty()) return why;
  const nlohmann::json j = nlohmann::json::parse(json, json + jsonLength, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return {};
  if (auto asset = j.find("asset"); asset != j.end() && asset->is_object()) {
    if (auto v = asset->find("version"); v != asset->end() && v->is_string()) {
      const std::string version = v->get<std::string>();
      if (version.rfind("2.", 0) != 0)
        return "glTF version '" + printable(version, 16) + "' is not supported (glTF 2.0 only)";
    }
  }
  if (auto req = j.find("extensionsRequired"); req != j.end() && req->is_array() && !req->empty()) {
    std::string names;
    for (const auto& e : *req) names += (names.empty() ? "" : ", ") + printable(e.is_string() ? e.get<std::string>() : e.dump(), 80);
    return "requires extension(s) " + names + ", which the tools do not support";
  }
  return {};
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
      if (std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(), ext) ==
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
