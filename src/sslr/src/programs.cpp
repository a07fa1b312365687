// Shader programs: embedded GLSL compiled on first use, cached by entry files + #defines.
#include <algorithm>

#include "context_impl.hpp"
#include "embedded_shaders.hpp"

namespace sslr {

namespace {

// A shader's or program's info log, with source-string numbers replaced by file names.
template <typename GetIv, typename GetLog>
std::string infoLog(GLuint object, GetIv getIv, GetLog getLog) {
  GLint length = 0;
  getIv(object, GL_INFO_LOG_LENGTH, &length);
  std::string text(static_cast<size_t>(std::max(length, 1)), '\0');
  getLog(object, length, nullptr, text.data());
  return detail::annotateShaderLog(text.c_str());
}

}  // namespace

// Compiles one stage from an embedded entry with #defines prepended; logs name the file.
Expected<GLuint> Context::Impl::compileStage(GLenum stage, const char* entry, const std::string& defines) const {
  const char* body = detail::embeddedShader(entry);
  if (body == nullptr) return Status::error(StatusCode::ShaderBuild, std::string("sslr: no embedded shader ") + entry);
  const std::string header = "#version 450 core\n" + defines;
  const char* sources[] = {header.c_str(), body};
  GLuint shader = gl.CreateShader(stage);
  gl.ShaderSource(shader, 2, sources, nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string errors = infoLog(shader, gl.GetShaderiv, gl.GetShaderInfoLog);
    gl.DeleteShader(shader);
    return Status::error(StatusCode::ShaderBuild, std::string("sslr: compiling ") + entry + " failed:\n" + errors);
  }
  return shader;
}

// Returns a linked program from the cache, building it on first use (only permutations that
// a frame needs are ever compiled).
Expected<GLuint> Context::Impl::program(const std::vector<std::pair<GLenum, const char*>>& stages,
                                       const std::string& defines) {
  std::string key = defines;
  for (const auto& [stage, entry] : stages) key += std::string("|") + entry;
  if (auto it = programs.find(key); it != programs.end()) return it->second;
  GLuint prog = gl.CreateProgram();
  std::vector<GLuint> shaders;
  for (const auto& [stage, entry] : stages) {
    auto shader = compileStage(stage, entry, defines);
    if (!shader) {
      for (GLuint s : shaders) gl.DeleteShader(s);
      gl.DeleteProgram(prog);
      message(LogLevel::Error, shader.error());
      return shader.status();
    }
    gl.AttachShader(prog, shader.value());
    shaders.push_back(shader.value());
  }
  gl.LinkProgram(prog);
  for (GLuint s : shaders) gl.DeleteShader(s);  // stays alive while attached
  GLint ok = 0;
  gl.GetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string errors = infoLog(prog, gl.GetProgramiv, gl.GetProgramInfoLog);
    gl.DeleteProgram(prog);
    return Status::error(StatusCode::ShaderBuild, "sslr: linking " + key + " failed:\n" + errors);
  }
  // "sslr.program ENTRY... NAME VALUE,...": the entries first and the defines without "#define",
  // since a label is cut at 255 characters.
  std::string labelText = "sslr.program";
  for (const auto& [stage, entry] : stages) labelText += std::string(" ") + entry;
  std::string compact = defines;
  for (size_t at; (at = compact.find("#define ")) != std::string::npos;) compact.erase(at, 8);
  std::replace(compact.begin(), compact.end(), '\n', ',');
  label(GL_PROGRAM, prog, labelText + " " + compact);
  message(LogLevel::Info, "sslr: compiled " + labelText + " " + compact);
  programs.emplace(key, prog);
  return prog;
}

Expected<GLuint> Context::Impl::computeProgram(const char* entry, const std::string& defines) {
  return program({{GL_COMPUTE_SHADER, entry}}, inputDefines + defines);
}

}  // namespace sslr
