// Small glTF 2.0 files written by tests: a one-mesh file, with the tools' base64 for data: URIs.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "sslr_host/gltf_writer.hpp"

namespace sslr::test {

using sslr::host::base64;  // the tools' encoder (sslr_host/gltf_writer.hpp)

template <typename T>
std::string bytesOf(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// One mesh (float VEC3 positions, u16 indices) in one node, no camera, one grey material.
inline std::string meshGltf(const std::vector<float>& positions, const std::vector<std::uint16_t>& indices) {
  const std::string pos = bytesOf(positions), idx = bytesOf(indices);
  std::ostringstream j;
  j << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
    << R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.8,0.8,0.8,1],"metallicFactor":0,"roughnessFactor":0.8}}],)"
    << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],)"
    << R"("buffers":[{"byteLength":)" << pos.size() + idx.size() << R"(,"uri":"data:application/octet-stream;base64,)"
    << base64(pos + idx) << R"("}],)"
    << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" << pos.size() << R"(},)"
    << R"({"buffer":0,"byteOffset":)" << pos.size() << R"(,"byteLength":)" << idx.size() << R"(}],)"
    << R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" << positions.size() / 3
    << R"(,"type":"VEC3"},{"bufferView":1,"componentType":5123,"count":)" << indices.size()
    << R"(,"type":"SCALAR"}]})";
  return j.str();
}

}  // namespace sslr::test
