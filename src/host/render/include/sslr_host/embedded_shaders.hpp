// Host-side shaders embedded at build time (same tool as the library's).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sslr/sslr.hpp"
#include "sslr_host/gl.hpp"

namespace sslr::host {
const char* embeddedShader(std::string_view entry);
// Compiles the embedded entries (e.g. "host/gbuffer.vert") and links them; errors name the file.
Expected<GLuint> linkHostProgram(const std::vector<std::pair<GLenum, const char*>>& stages);
std::string annotateShaderLog(std::string_view log);
}  // namespace sslr::host
