// Host-side shaders embedded at build time (same tool as the library's).
#pragma once

#include <string>
#include <string_view>

namespace sslr::host {
const char* embeddedShader(std::string_view entry);
std::string annotateShaderLog(std::string_view log);
}  // namespace sslr::host
