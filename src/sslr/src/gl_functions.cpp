#include "gl_functions.hpp"

namespace sslr::detail {

Status Gl::load(GetProcAddress getProcAddress) {
  if (getProcAddress == nullptr) return Status::error(StatusCode::GlUnavailable, "sslr: ContextDesc::getProcAddress is null");
  std::string missing;
#define SSLR_GL_LOAD(type, name)                                            \
  name = reinterpret_cast<type>(getProcAddress("gl" #name));                \
  if (name == nullptr) missing += (missing.empty() ? "gl" : ", gl") + std::string(#name);
  SSLR_GL_FUNCTIONS(SSLR_GL_LOAD)
#undef SSLR_GL_LOAD
  if (!missing.empty())
    return Status::error(StatusCode::GlUnavailable, "sslr: the GL context lacks entry points sslr needs (OpenGL 4.5 core): " +
                         missing);
  return {};
}

}  // namespace sslr::detail
