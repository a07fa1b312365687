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

// Hands one stage from an embedded entry, #defines prepended, to the compiler. Its result is read
// with the program's link (finishProgram): reading it here would wait for a driver that compiles
// in parallel.
Expected<GLuint> Context::Impl::compileStage(GLenum stage, const char* entry, const std::string& defines) const {
  const char* body = detail::embeddedShader(entry);
  if (body == nullptr) return Status::error(StatusCode::ShaderBuild, std::string("sslr: no embedded shader ") + entry);
  const std::string header = "#version 450 core\n" + defines;
  const char* sources[] = {header.c_str(), body};
  GLuint shader = gl.CreateShader(stage);
  gl.ShaderSource(shader, 2, sources, nullptr);
  gl.CompileShader(shader);
  return shader;
}

// Returns a linked program from the cache, building it on first use (only permutations that
// a frame needs are ever compiled). While issueProgramsOnly, a new program is compiled and linked
// without waiting on the driver, and checked when it is next asked for.
Expected<GLuint> Context::Impl::program(const std::vector<std::pair<GLenum, const char*>>& stages,
                                       const std::string& defines) {
  std::string key = defines;
  for (const auto& [stage, entry] : stages) key += std::string("|") + entry;
  if (auto it = programs.find(key); it != programs.end()) return it->second;
  if (auto it = pendingPrograms.find(key); it != pendingPrograms.end()) {
    if (issueProgramsOnly) return it->second.program;  // handed over already; not waited on yet
    const PendingProgram pending = std::move(it->second);
    pendingPrograms.erase(it);
    return finishProgram(key, pending);
  }
  PendingProgram pending;
  pending.program = gl.CreateProgram();
  for (const auto& [stage, entry] : stages) {
    auto shader = compileStage(stage, entry, defines);
    if (!shader) {
      for (const auto& [s, e] : pending.shaders) gl.DeleteShader(s);
      gl.DeleteProgram(pending.program);
      message(LogLevel::Error, shader.error());
      return shader.status();
    }
    gl.AttachShader(pending.program, shader.value());
    pending.shaders.emplace_back(shader.value(), entry);
  }
  gl.LinkProgram(pending.program);
  if (issueProgramsOnly) {
    const GLuint handedOver = pending.program;
    pendingPrograms.emplace(key, std::move(pending));
    return handedOver;
  }
  return finishProgram(key, pending);
}

// A handed-over program's result (this waits for the driver): cached and labelled, or its
// shaders' compile log (a stage that failed to compile) or its link log as the error.
Expected<GLuint> Context::Impl::finishProgram(const std::string& key, const PendingProgram& pending) {
  GLint linked = 0;
  gl.GetProgramiv(pending.program, GL_LINK_STATUS, &linked);
  Status failed;
  if (!linked) {
    for (const auto& [shader, entry] : pending.shaders) {
      GLint compiled = 0;
      gl.GetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
      if (!compiled) {
        failed = Status::error(StatusCode::ShaderBuild, std::string("sslr: compiling ") + entry + " failed:\n" +
                                                            infoLog(shader, gl.GetShaderiv, gl.GetShaderInfoLog));
        break;
      }
    }
    if (failed.ok()) {  // every stage compiled: the link itself failed
      failed = Status::error(StatusCode::ShaderBuild, "sslr: linking " + key + " failed:\n" +
                                                          infoLog(pending.program, gl.GetProgramiv, gl.GetProgramInfoLog));
    }
  }
  for (const auto& [shader, entry] : pending.shaders) gl.DeleteShader(shader);  // stays alive while attached
  if (!linked) {
    gl.DeleteProgram(pending.program);
    message(LogLevel::Error, failed.message());
    return failed;
  }
  // "sslr.program ENTRY... NAME VALUE,...": the entries first and the defines without "#define",
  // since a label is cut at 255 characters.
  std::string labelText = "sslr.program";
  for (const auto& [shader, entry] : pending.shaders) labelText += std::string(" ") + entry;
  const std::string defines = key.substr(0, key.find('|'));
  std::string compact = defines;
  for (size_t at; (at = compact.find("#define ")) != std::string::npos;) compact.erase(at, 8);
  std::replace(compact.begin(), compact.end(), '\n', ',');
  label(GL_PROGRAM, pending.program, labelText + " " + compact);
  message(LogLevel::Info, "sslr: compiled " + labelText + " " + compact);
  programs.emplace(key, pending.program);
  return pending.program;
}

Expected<GLuint> Context::Impl::computeProgram(const char* entry, const std::string& defines) {
  return program({{GL_COMPUTE_SHADER, entry}}, inputDefines + defines);
}

}  // namespace sslr
