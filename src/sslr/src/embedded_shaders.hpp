// Shaders embedded at build time by src/build_tools/embed_shaders.cpp (no files at run time).
#pragma once

#include <string>
#include <string_view>

namespace sslr::detail {
const char* embeddedShader(std::string_view entry);  // expanded source or nullptr
std::string annotateShaderLog(std::string_view log);  // source numbers -> file names
}  // namespace sslr::detail
