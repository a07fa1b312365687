// What the glTF loader's files share (private to sslr_scene): its error type, the checked
// arithmetic and printable text, the folder jail and image budget tinygltf's callbacks use
// (gltf_files.cpp), and the checks made before and after parsing (gltf_checks.cpp).
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace sslr::host::gltf {

struct LoadError {
  std::string message;
};

// Sizes and offsets in a glTF file are untrusted 64-bit values: every sum and product of them is
// checked, so a wrapped value can never pass a bounds test.
inline bool addOverflows(size_t a, size_t b, size_t& sum) { return __builtin_add_overflow(a, b, &sum); }
inline bool mulOverflows(size_t a, size_t b, size_t& product) { return __builtin_mul_overflow(a, b, &product); }

// Text from a file (an error of the parser may quote it): printable ASCII only, and short, so the
// raw bytes of a binary file never reach the terminal.
std::string printable(const std::string& text, size_t limit = 240);

// ---- gltf_files.cpp: file access only inside the model's folder; image limits ----------------
constexpr std::uintmax_t kMaxExternalFileBytes = std::uintmax_t(2) << 30;  // 2 GiB

struct FolderJail {
  std::filesystem::path root;  // canonical folder of the model file
  std::string modelFile;       // canonical path of the model itself
};
// Reads `path` through one descriptor after checking it is a regular file inside the jail (when
// given) of at most `limit` bytes; "" or the reason it was not read.
std::string readChecked(const std::string& path, const FolderJail* jail, std::uintmax_t limit,
                        std::vector<unsigned char>& out);
bool jailFileExists(const std::string& path, void*);
std::string jailExpandFilePath(const std::string& path, void*);
bool jailReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user);
bool jailWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*);

struct ImageBudget {
  const tinygltf::Model* model = nullptr;  // its buffers are parsed when images are decoded
  std::uint64_t decodedBytes = 0;          // of the images decoded so far
};
// tinygltf's image callback: PNG or JPEG within the size limits, else left empty with a warning;
// images that together would decode past the budget refuse the file.
bool limitedImageLoader(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int, int,
                        const unsigned char* bytes, int size, void* user);

// ---- gltf_checks.cpp: before parsing (the file's structure), after it (the geometry budget) ----
// "" or why the file is refused before tinygltf parses it (GLB chunks, JSON nesting).
std::string precheck(const std::vector<unsigned char>& file, bool binary);
// Throws LoadError when the instanced meshes' copies would pass the geometry budget.
void checkGeometryBudget(const tinygltf::Model& model, const std::vector<std::pair<int, glm::dmat4>>& instances);

}  // namespace sslr::host::gltf
