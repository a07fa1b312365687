// The glTF loader's checks: the file's structure before tinygltf parses it (GLB chunks, JSON
// nesting) and the geometry budget of the instanced meshes before anything is built.
#include "gltf_internal.hpp"

#include <cstring>
#include <limits>

#include <nlohmann/json.hpp>

namespace sslr::host::gltf {

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

}  // namespace sslr::host::gltf
