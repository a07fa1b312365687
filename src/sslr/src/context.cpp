// sslr::Context: owns sslr's GL objects, validates the host's inputs and runs the passes:
//   classify (tile list) -> trace (adaptive L) -> blur H -> blur V -> [composite]
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <vector>

#include "embedded_shaders.hpp"
#include "gl_functions.hpp"
#include "gl_state.hpp"
#include "projection.hpp"
#include "sslr/reference.hpp"
#include "sslr/sslr.hpp"
#include "sslr_shared.h"

namespace sslr {

using detail::Gl;

// ---- Settings -----------------------------------------------------------------------------

Settings Settings::preset(Preset preset) {
  Settings s;
  switch (preset) {
    case Preset::Low:
      s.maxIterations = 8;  // 6 lost half the long reflections at 960x540 (docs/results.md)
      s.convergenceEps = 0.01f;
      s.blurMaxRadiusPx = 4.0f;
      s.roughnessCutoff = 0.3f;
      break;
    case Preset::Medium:
      s.maxIterations = 10;  // the article's fixed count
      s.convergenceEps = 0.005f;
      s.blurMaxRadiusPx = 6.0f;
      s.roughnessCutoff = 0.4f;
      break;
    case Preset::High:
      break;  // the defaults
    case Preset::Ultra:
      s.maxIterations = 32;
      s.convergenceEps = 0.0005f;
      s.blurMaxRadiusPx = 12.0f;
      s.roughnessCutoff = 0.6f;
      break;
  }
  return s;
}

std::string validate(const Settings& s) {
  std::ostringstream why;
  auto finite = [](float v) { return std::isfinite(v); };
  if (s.maxIterations < 1 || s.maxIterations > 256)
    why << "maxIterations = " << s.maxIterations << " (must be 1..256); ";
  if (s.hierarchicalMaxSteps < 1 || s.hierarchicalMaxSteps > 1024)
    why << "hierarchicalMaxSteps = " << s.hierarchicalMaxSteps << " (must be 1..1024); ";
  if (!finite(s.objectThickness) || s.objectThickness < 0.0f)
    why << "objectThickness = " << s.objectThickness << " (must be >= 0); ";
  if (!finite(s.convergenceEps) || s.convergenceEps < 0.0f)
    why << "convergenceEps = " << s.convergenceEps << " (must be >= 0); ";
  if (!finite(s.initialLengthScreen) || s.initialLengthScreen <= 0.0f || s.initialLengthScreen > 1.0f)
    why << "initialLengthScreen = " << s.initialLengthScreen << " (must be in (0, 1]); ";
  if (!finite(s.errorK) || s.errorK < 0.0f) why << "errorK = " << s.errorK << " (must be >= 0); ";
  if (!(s.maxDistance > 0.0f)) why << "maxDistance = " << s.maxDistance << " (must be > 0); ";
  if (!finite(s.thicknessRelative) || s.thicknessRelative < 0.0f)
    why << "thicknessRelative = " << s.thicknessRelative << " (must be >= 0); ";
  if (!finite(s.thicknessPixels) || s.thicknessPixels < 0.0f)
    why << "thicknessPixels = " << s.thicknessPixels << " (must be >= 0); ";
  if (s.thicknessRelative == 0.0f && s.thicknessPixels == 0.0f)
    why << "thicknessRelative and thicknessPixels are both 0 (no hit could validate); ";
  if (!finite(s.edgeFade) || s.edgeFade < 0.0f || s.edgeFade > 0.5f)
    why << "edgeFade = " << s.edgeFade << " (must be 0..0.5); ";
  if (!finite(s.cameraFadeStart) || !finite(s.cameraFadeEnd) || s.cameraFadeEnd < s.cameraFadeStart)
    why << "cameraFadeStart/End = " << s.cameraFadeStart << "/" << s.cameraFadeEnd
        << " (must be finite, start <= end); ";
  if (!finite(s.roughnessCutoff)) why << "roughnessCutoff is not finite; ";
  if (!finite(s.minReflectance)) why << "minReflectance is not finite; ";
  if (!finite(s.blurMaxRadiusPx) || s.blurMaxRadiusPx < 0.0f || s.blurMaxRadiusPx > 32.0f)
    why << "blurMaxRadiusPx = " << s.blurMaxRadiusPx << " (must be 0..32); ";
  if (!finite(s.blurConeScale) || s.blurConeScale < 0.0f)
    why << "blurConeScale = " << s.blurConeScale << " (must be >= 0); ";
  if (!finite(s.blurDepthSigma) || s.blurDepthSigma <= 0.0f)
    why << "blurDepthSigma = " << s.blurDepthSigma << " (must be > 0); ";
  if (!finite(s.blurNormalPower) || s.blurNormalPower < 0.0f)
    why << "blurNormalPower = " << s.blurNormalPower << " (must be >= 0); ";
  const PositionBufferSettings& pb = s.positionBuffer;
  if (!(pb.maxDistance > 0.0f) || !finite(pb.maxDistance))
    why << "positionBuffer.maxDistance = " << pb.maxDistance << " (must be > 0); ";
  if (!(pb.resolution > 0.0f && pb.resolution <= 1.0f))
    why << "positionBuffer.resolution = " << pb.resolution << " (must be in (0, 1]); ";
  if (pb.steps < 0 || pb.steps > 64) why << "positionBuffer.steps = " << pb.steps << " (must be 0..64); ";
  if (!(pb.thickness > 0.0f) || !finite(pb.thickness))
    why << "positionBuffer.thickness = " << pb.thickness << " (must be > 0); ";
  std::string text = why.str();
  if (!text.empty()) text = "sslr: invalid Settings: " + text.substr(0, text.size() - 2);
  return text;
}

// ---- Implementation -----------------------------------------------------------------------

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

constexpr GLsizeiptr kTileHeader = 12;               // uints before the tile lists
constexpr GLintptr kDrawArgsOffset = 3 * 4;           // DrawArraysIndirectCommand (composite)
constexpr GLintptr kBlurDispatchOffset = 8 * 4;       // DispatchIndirectCommand (blur)

// What sslr needs to know of a host texture's internal format.
struct FormatInfo {
  enum Kind { Unsupported, Color, Depth } kind = Unsupported;
  int channels = 0;
  const char* name = "unsupported";
};

FormatInfo formatInfo(GLint f) {
  switch (f) {
    case GL_DEPTH_COMPONENT16: return {FormatInfo::Depth, 1, "DEPTH_COMPONENT16"};
    case GL_DEPTH_COMPONENT24: return {FormatInfo::Depth, 1, "DEPTH_COMPONENT24"};
    case GL_DEPTH_COMPONENT32: return {FormatInfo::Depth, 1, "DEPTH_COMPONENT32"};
    case GL_DEPTH_COMPONENT32F: return {FormatInfo::Depth, 1, "DEPTH_COMPONENT32F"};
    case GL_DEPTH24_STENCIL8: return {FormatInfo::Depth, 1, "DEPTH24_STENCIL8"};
    case GL_DEPTH32F_STENCIL8: return {FormatInfo::Depth, 1, "DEPTH32F_STENCIL8"};
    case GL_R8: return {FormatInfo::Color, 1, "R8"};
    case GL_R16: return {FormatInfo::Color, 1, "R16"};
    case GL_R16F: return {FormatInfo::Color, 1, "R16F"};
    case GL_R32F: return {FormatInfo::Color, 1, "R32F"};
    case GL_RG8: return {FormatInfo::Color, 2, "RG8"};
    case GL_RG16: return {FormatInfo::Color, 2, "RG16"};
    case GL_RG16F: return {FormatInfo::Color, 2, "RG16F"};
    case GL_RG32F: return {FormatInfo::Color, 2, "RG32F"};
    case GL_RGB8: return {FormatInfo::Color, 3, "RGB8"};
    case GL_RGB16: return {FormatInfo::Color, 3, "RGB16"};
    case GL_RGB16F: return {FormatInfo::Color, 3, "RGB16F"};
    case GL_RGB32F: return {FormatInfo::Color, 3, "RGB32F"};
    case GL_R11F_G11F_B10F: return {FormatInfo::Color, 3, "R11F_G11F_B10F"};
    case GL_RGB9_E5: return {FormatInfo::Color, 3, "RGB9_E5"};
    case GL_SRGB8: return {FormatInfo::Color, 3, "SRGB8"};
    case GL_RGBA8: return {FormatInfo::Color, 4, "RGBA8"};
    case GL_SRGB8_ALPHA8: return {FormatInfo::Color, 4, "SRGB8_ALPHA8"};
    case GL_RGB10_A2: return {FormatInfo::Color, 4, "RGB10_A2"};
    case GL_RGBA16: return {FormatInfo::Color, 4, "RGBA16"};
    case GL_RGBA16F: return {FormatInfo::Color, 4, "RGBA16F"};
    case GL_RGBA32F: return {FormatInfo::Color, 4, "RGBA32F"};
    default: return {};
  }
}


}  // namespace

struct Context::Impl {
  Gl gl;
  LogCallback log;
  int width = 0, height = 0;

  GLuint reflection = 0, blurTemp = 0, resolved = 0, hit = 0, iterations = 0;
  // Min-max depth pyramid: mip m holds level m + 1 (sslr_shared.h). Its base is padded so that
  // every mip halves exactly: mip m has at least ceil(size / 2^(m+1)) cells per axis.
  GLuint hiz = 0;
  int hizLevels = 0, hizWidth = 0, hizHeight = 0;
  GLuint frameUbo = 0, tileBuffer = 0, statsBuffer = 0;
  GLuint nearestSampler = 0, linearSampler = 0, vao = 0;
  std::map<std::string, GLuint> programs;  // key: entry files + defines
  FrameStats stats;
  bool haveFrame = false;  // a dispatch filled the tile list, so composite has work to draw
  int frameIndex = 0;      // per-dispatch stamp for the blur tile list (1, 2, ...)

  ~Impl() { destroy(); }

  void message(LogLevel level, const std::string& text) const {
    if (log) log(level, text);
  }

  void label(GLenum type, GLuint name, const char* text) const {
    gl.ObjectLabel(type, name, -1, text);
  }

  void destroyTargets() {
    GLuint textures[] = {reflection, blurTemp, resolved, hit, iterations, hiz};
    gl.DeleteTextures(6, textures);
    GLuint buffers[] = {tileBuffer};
    gl.DeleteBuffers(1, buffers);
    reflection = blurTemp = resolved = hit = iterations = hiz = tileBuffer = 0;
  }

  void destroy() {
    if (gl.DeleteTextures == nullptr) return;  // loading failed: nothing was created
    destroyTargets();
    GLuint buffers[] = {frameUbo, statsBuffer};
    gl.DeleteBuffers(2, buffers);
    GLuint samplers[] = {nearestSampler, linearSampler};
    gl.DeleteSamplers(2, samplers);
    gl.DeleteVertexArrays(1, &vao);
    for (auto& [key, program] : programs) gl.DeleteProgram(program);
    programs.clear();
    frameUbo = statsBuffer = nearestSampler = linearSampler = vao = 0;
  }

  GLuint makeTexture(GLenum format, const char* name) const {
    GLuint t = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &t);
    gl.TextureStorage2D(t, 1, format, width, height);
    label(GL_TEXTURE, t, name);
    return t;
  }

  void createTargets() {
    reflection = makeTexture(GL_RGBA16F, "sslr.reflection");
    blurTemp = makeTexture(GL_RGBA16F, "sslr.blurTemp");
    resolved = makeTexture(GL_RGBA16F, "sslr.resolved");
    hit = makeTexture(GL_RGBA32F, "sslr.hit");
    iterations = makeTexture(GL_R32F, "sslr.iterations");
    hizLevels = shared::sslrHiZLevelCount(width, height);
    const int top = 1 << hizLevels;
    hizWidth = (width + top - 1) / top * (top / 2);
    hizHeight = (height + top - 1) / top * (top / 2);
    gl.CreateTextures(GL_TEXTURE_2D, 1, &hiz);
    gl.TextureStorage2D(hiz, hizLevels, GL_RG32F, hizWidth, hizHeight);
    label(GL_TEXTURE, hiz, "sslr.depthPyramid");
    const GLsizeiptr tiles = static_cast<GLsizeiptr>(tilesX()) * tilesY();
    gl.CreateBuffers(1, &tileBuffer);
    // Header (12 uints, see common/tiles.glsl), traced tiles, tiles to blur, per-tile stamps
    // (zero-initialized: frame indices start at 1).
    const std::vector<GLuint> zeros(static_cast<size_t>(kTileHeader + 3 * tiles), 0u);
    gl.NamedBufferStorage(tileBuffer, static_cast<GLsizeiptr>(zeros.size() * sizeof(GLuint)), zeros.data(),
                          GL_DYNAMIC_STORAGE_BIT);
    label(GL_BUFFER, tileBuffer, "sslr.tiles");
  }

  int tilesX() const { return (width + SSLR_TILE_SIZE - 1) / SSLR_TILE_SIZE; }
  int tilesY() const { return (height + SSLR_TILE_SIZE - 1) / SSLR_TILE_SIZE; }

  // Compiles one stage from an embedded entry with #defines prepended; logs name the file.
  Expected<GLuint> compileStage(GLenum stage, const char* entry, const std::string& defines) const {
    const char* body = detail::embeddedShader(entry);
    if (body == nullptr) return Status::error(std::string("sslr: no embedded shader ") + entry);
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
      return Status::error(std::string("sslr: compiling ") + entry + " failed:\n" + errors);
    }
    return shader;
  }

  // Returns a linked program from the cache, building it on first use (only permutations that
  // a frame needs are ever compiled).
  Expected<GLuint> program(const std::vector<std::pair<GLenum, const char*>>& stages,
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
        return Status::error(shader.error());
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
      return Status::error("sslr: linking " + key + " failed:\n" + errors);
    }
    std::string labelText = "sslr.program" + key;
    label(GL_PROGRAM, prog, labelText.c_str());
    programs.emplace(key, prog);
    return prog;
  }

  Expected<GLuint> computeProgram(const char* entry, const std::string& defines = {}) {
    return program({{GL_COMPUTE_SHADER, entry}}, defines);
  }

  // Checks one host texture: exists, is 2D, has the context's size and a usable format.
  Status checkTexture(GLName tex, const char* what, FormatInfo::Kind kind, int minChannels,
                      FormatInfo* infoOut = nullptr) const {
    std::ostringstream where;
    where << "sslr: FrameInputs::" << what << " (texture " << tex << ")";
    if (tex == 0) return Status::error(where.str() + " is 0: the texture is required");
    if (!gl.IsTexture(tex)) return Status::error(where.str() + " is not a texture name");
    GLint target = 0;
    gl.GetTextureParameteriv(tex, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D) return Status::error(where.str() + " is not a GL_TEXTURE_2D");
    GLint w = 0, h = 0, format = 0;
    gl.GetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
    gl.GetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
    gl.GetTextureLevelParameteriv(tex, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (w != width || h != height) {
      where << " is " << w << "x" << h << " but the context is " << width << "x" << height;
      return Status::error(where.str());
    }
    FormatInfo info = formatInfo(format);
    if (info.kind != kind) {
      where << " has internal format 0x" << std::hex << format << std::dec << " ("
            << info.name << "); expected " << (kind == FormatInfo::Depth ? "a depth format" :
                                               "a float or unorm colour format");
      return Status::error(where.str());
    }
    if (info.channels < minChannels) {
      where << " has " << info.channels << " channel(s) (" << info.name << "); needs " << minChannels;
      return Status::error(where.str());
    }
    if (kind == FormatInfo::Depth &&
        (format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8)) {
      GLint mode = 0;
      gl.GetTextureParameteriv(tex, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
      if (mode != GL_DEPTH_COMPONENT)
        return Status::error(where.str() + " samples stencil (GL_DEPTH_STENCIL_TEXTURE_MODE); "
                             "set it to GL_DEPTH_COMPONENT");
    }
    if (infoOut) *infoOut = info;
    return {};
  }

  Status checkInputs(const FrameInputs& in, Method method) const {
    if (Status s = checkTexture(in.depthTexture, "depthTexture", FormatInfo::Depth, 1); !s) return s;
    if (method == Method::PositionBuffer) {
      if (Status s = checkTexture(in.positionTexture, "positionTexture", FormatInfo::Color, 4); !s)
        return Status::error(s.message() + " (Method::PositionBuffer needs a view-space position texture)");
    }
    if (Status s = checkTexture(in.colorTexture, "colorTexture", FormatInfo::Color, 3); !s) return s;
    const int normalChannels = in.surface.normals == NormalEncoding::Octahedral ? 2 : 3;
    FormatInfo normalInfo;
    if (Status s = checkTexture(in.normalTexture, "normalTexture", FormatInfo::Color, normalChannels,
                                &normalInfo);
        !s)
      return s;
    const SurfaceLayout& sl = in.surface;
    auto checkChannel = [&](int channel, const char* name) -> Status {
      if (channel < -1 || channel > 3)
        return Status::error(std::string("sslr: SurfaceLayout::") + name + " = " +
                             std::to_string(channel) + " (must be -1..3)");
      if (channel >= normalInfo.channels)
        return Status::error(std::string("sslr: SurfaceLayout::") + name + " = " +
                             std::to_string(channel) + " but normalTexture (" + normalInfo.name +
                             ") has only " + std::to_string(normalInfo.channels) + " channel(s)");
      return {};
    };
    if (Status s = checkChannel(sl.roughnessChannel, "roughnessChannel"); !s) return s;
    if (Status s = checkChannel(sl.reflectanceChannel, "reflectanceChannel"); !s) return s;
    const int normalUses = sl.normals == NormalEncoding::Octahedral ? 2 : 3;
    if (sl.roughnessChannel >= 0 && sl.roughnessChannel < normalUses)
      return Status::error("sslr: SurfaceLayout::roughnessChannel overlaps the normal's channels");
    if (sl.reflectanceChannel >= 0 && sl.reflectanceChannel < normalUses)
      return Status::error("sslr: SurfaceLayout::reflectanceChannel overlaps the normal's channels");
    if (!std::isfinite(sl.constantRoughness) || !std::isfinite(sl.constantReflectance))
      return Status::error("sslr: SurfaceLayout constant roughness/reflectance must be finite");
    return {};
  }

  void bindInputs(const FrameInputs& in) const {
    gl.BindTextureUnit(0, in.depthTexture);
    gl.BindSampler(0, nearestSampler);
    gl.BindTextureUnit(1, in.normalTexture);
    gl.BindSampler(1, nearestSampler);
    gl.BindTextureUnit(2, in.colorTexture);
    gl.BindSampler(2, linearSampler);
    gl.BindTextureUnit(6, hiz);  // read by the depth-only trace (built when a mode needs it)
    gl.BindSampler(6, nearestSampler);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, SSLR_BINDING_FRAME_UBO, frameUbo);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_TILE_SSBO, tileBuffer);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileBuffer);
  }

  // The min-max depth pyramid, one dispatch per level (each reads the level below). Its shader
  // returns at once when classification listed no tile.
  void buildPyramid(GLuint prog) const {
    gl.UseProgram(prog);
    gl.BindTextureUnit(6, hiz);
    gl.BindSampler(6, nearestSampler);
    for (int level = 1; level <= hizLevels; ++level) {
      const int w = hizWidth >> (level - 1), h = hizHeight >> (level - 1);
      gl.ProgramUniform1i(prog, 0, level - 1);  // uSourceLevel
      if (level == 1) gl.ProgramUniform2i(prog, 1, width, height);  // uSourceSize
      else gl.ProgramUniform2i(prog, 1, hizWidth >> (level - 2), hizHeight >> (level - 2));
      gl.BindImageTexture(0, hiz, level - 1, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
      gl.DispatchCompute(static_cast<GLuint>((w + SSLR_TILE_SIZE - 1) / SSLR_TILE_SIZE),
                         static_cast<GLuint>((h + SSLR_TILE_SIZE - 1) / SSLR_TILE_SIZE), 1);
      gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
  }

  Status dispatch(const FrameInputs& in, const Settings& settings);
  Status composite(GLName framebuffer);
};


Status Context::Impl::dispatch(const FrameInputs& in, const Settings& settings) {
  haveFrame = false;
  auto constants = frameConstants(in, settings, width, height);  // validates settings + projection
  if (!constants) return Status::error(constants.error());
  if (Status s = checkInputs(in, settings.method); !s) return s;

  // Build every program this frame needs before touching any state.
  std::string traceDefines;
  if (settings.debugOutputs) traceDefines += "#define SSLR_DEBUG_OUTPUTS 1\n";
  if (settings.collectStats) traceDefines += "#define SSLR_COLLECT_STATS 1\n";
  if (settings.method == Method::PositionBuffer) traceDefines += "#define SSLR_METHOD_POSITION_BUFFER 1\n";
  auto classify = computeProgram("classify.comp");
  const bool depthOnly = settings.method != Method::PositionBuffer;
  const bool pyramid = depthOnly && (settings.method == Method::HierarchicalDepth || settings.hierarchicalFallback);
  Expected<GLuint> hizBuild = pyramid ? computeProgram("hiz.comp") : Expected<GLuint>(GLuint(0));
  auto trace = computeProgram("trace.comp", traceDefines);
  const bool blur = settings.blur && settings.blurMaxRadiusPx > 0.0f;
  Expected<GLuint> blurH = GLuint(0), blurV = GLuint(0);
  if (blur) {
    blurH = computeProgram("blur.comp", "#define SSLR_BLUR_AXIS ivec2(1, 0)\n");
    blurV = computeProgram("blur.comp", "#define SSLR_BLUR_AXIS ivec2(0, 1)\n#define SSLR_BLUR_VERTICAL 1\n");
  }
  for (const auto* p : {&classify, &hizBuild, &trace, &blurH, &blurV})
    if (!*p) return Status::error(p->error());

  detail::StateGuard guard(gl, false);
  gl.PushDebugGroup(GL_DEBUG_SOURCE_THIRD_PARTY, 0, -1, "sslr.dispatch");

  shared::SslrFrame frame = constants.value();
  frameIndex = frameIndex == 0x7fffffff ? 1 : frameIndex + 1;
  frame.trace.frameIndex = frameIndex;
  gl.NamedBufferSubData(frameUbo, 0, sizeof(frame), &frame);
  // Tile list header: trace dispatch (0, 1, 1), draw (6 vertices, 0 instances), blur dispatch.
  const GLuint header[kTileHeader] = {0, 1, 1, 6, 0, 0, 0, 0, 0, 1, 1, 0};
  gl.NamedBufferSubData(tileBuffer, 0, sizeof(header), header);
  // Outputs are only written inside listed tiles: clear so the rest reads as "no reflection".
  const float zero[4] = {0, 0, 0, 0};
  gl.ClearTexImage(reflection, 0, GL_RGBA, GL_FLOAT, zero);
  gl.ClearTexImage(resolved, 0, GL_RGBA, GL_FLOAT, zero);
  if (settings.debugOutputs) {
    gl.ClearTexImage(hit, 0, GL_RGBA, GL_FLOAT, zero);
    gl.ClearTexImage(iterations, 0, GL_RED, GL_FLOAT, zero);
  }
  if (settings.collectStats) {
    const GLuint statsZero[4] = {0, 0, 0, 0};
    gl.NamedBufferSubData(statsBuffer, 0, sizeof(statsZero), statsZero);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_STATS_SSBO, statsBuffer);
  }
  bindInputs(in);
  if (settings.method == Method::PositionBuffer) {
    gl.BindTextureUnit(5, in.positionTexture);
    gl.BindSampler(5, nearestSampler);
  }

  // Classification covers the screen; everything after runs over the listed tiles only.
  gl.UseProgram(classify.value());
  gl.DispatchCompute(static_cast<GLuint>(tilesX()), static_cast<GLuint>(tilesY()), 1);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);

  if (pyramid) buildPyramid(hizBuild.value());

  gl.UseProgram(trace.value());
  gl.BindImageTexture(0, reflection, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  gl.BindImageTexture(3, resolved, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  if (settings.debugOutputs) {
    gl.BindImageTexture(1, hit, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl.BindImageTexture(2, iterations, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  }
  gl.DispatchComputeIndirect(0);
  gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                   GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);

  // The trace wrote resolved = reflection everywhere; the separable blur (reflection -> blurTemp
  // -> resolved) runs only over the tiles the trace listed as having a pixel to blur.
  if (blur) {
    gl.BindSampler(3, nearestSampler);
    gl.BindSampler(4, nearestSampler);
    gl.UseProgram(blurH.value());
    gl.BindTextureUnit(3, reflection);
    gl.BindImageTexture(0, blurTemp, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl.DispatchComputeIndirect(kBlurDispatchOffset);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    gl.UseProgram(blurV.value());
    gl.BindTextureUnit(3, blurTemp);
    gl.BindTextureUnit(4, reflection);
    gl.BindImageTexture(0, resolved, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl.DispatchComputeIndirect(kBlurDispatchOffset);
  }
  // The host (and composite) may read the outputs in any way next: make all writes visible.
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  gl.PopDebugGroup();

  stats = {};
  if (settings.collectStats) {
    GLuint counts[kTileHeader] = {};
    GLuint counters[3] = {0, 0, 0};
    gl.GetNamedBufferSubData(tileBuffer, 0, sizeof(counts), counts);
    gl.GetNamedBufferSubData(statsBuffer, 0, sizeof(counters), counters);
    stats.tiles = counts[0];
    stats.blurTiles = counts[8];
    stats.tracedPixels = counters[0];
    stats.fetches = counters[1];
    stats.hierarchicalPixels = counters[2];
  }
  haveFrame = true;
  return {};
}

Status Context::Impl::composite(GLName framebuffer) {
  if (!haveFrame)
    return Status::error("sslr: composite() needs a successful dispatch() first");
  if (framebuffer != 0 && !gl.IsFramebuffer(framebuffer))
    return Status::error("sslr: composite(): " + std::to_string(framebuffer) +
                         " is not a framebuffer name");
  auto prog = program({{GL_VERTEX_SHADER, "composite.vert"}, {GL_FRAGMENT_SHADER, "composite.frag"}}, "");
  if (!prog) return Status::error(prog.error());
  detail::StateGuard guard(gl, true);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  if (gl.CheckNamedFramebufferStatus(framebuffer, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return Status::error("sslr: composite(): framebuffer " + std::to_string(framebuffer) +
                         " is not complete");
  gl.PushDebugGroup(GL_DEBUG_SOURCE_THIRD_PARTY, 0, -1, "sslr.composite");
  gl.UseProgram(prog.value());
  gl.BindVertexArray(vao);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, SSLR_BINDING_FRAME_UBO, frameUbo);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_TILE_SSBO, tileBuffer);
  gl.BindBuffer(GL_DRAW_INDIRECT_BUFFER, tileBuffer);
  gl.BindTextureUnit(4, resolved);
  gl.BindSampler(4, nearestSampler);
  gl.Viewport(0, 0, width, height);
  gl.Disable(GL_DEPTH_TEST);
  gl.Disable(GL_STENCIL_TEST);
  gl.Disable(GL_CULL_FACE);
  gl.Disable(GL_SCISSOR_TEST);
  gl.Disable(GL_RASTERIZER_DISCARD);
  // Draw buffer 0 gets colour + reflection (its alpha kept); other draw buffers are masked.
  gl.Enablei(GL_BLEND, 0);
  gl.BlendFuncSeparatei(0, GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  gl.BlendEquationSeparatei(0, GL_FUNC_ADD, GL_FUNC_ADD);
  gl.ColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  GLint maxDrawBuffers = 0;
  gl.GetIntegerv(GL_MAX_DRAW_BUFFERS, &maxDrawBuffers);
  for (GLint i = 1; i < std::min(maxDrawBuffers, 8); ++i) gl.ColorMaski(i, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  // 6 vertices per listed tile, instance count written by classification (offset 12 bytes).
  gl.DrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(kDrawArgsOffset));
  gl.PopDebugGroup();
  return {};
}

// ---- Context ------------------------------------------------------------------------------

Context::Context(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Context::~Context() = default;

Expected<std::unique_ptr<Context>> Context::create(const ContextDesc& desc) {
  if (desc.width <= 0 || desc.height <= 0 || desc.width > 16384 || desc.height > 16384)
    return Status::error("sslr: ContextDesc size " + std::to_string(desc.width) + "x" +
                         std::to_string(desc.height) + " is invalid (must be 1..16384 each)");
  auto impl = std::make_unique<Impl>();
  impl->log = desc.log;
  if (Status s = impl->gl.load(desc.getProcAddress); !s) {
    impl->gl = {};
    return s;
  }
  const Gl& gl = impl->gl;
  GLint major = 0, minor = 0;
  gl.GetIntegerv(GL_MAJOR_VERSION, &major);
  gl.GetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45) {
    impl->gl = {};
    return Status::error("sslr: needs OpenGL 4.5, the current context is " + std::to_string(major) +
                         "." + std::to_string(minor));
  }
  GLint vertexSsbos = 0;
  gl.GetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &vertexSsbos);
  if (vertexSsbos < 1) {
    impl->gl = {};
    return Status::error("sslr: the GL implementation allows no storage blocks in vertex shaders "
                         "(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS = 0); composite needs one");
  }
  impl->width = desc.width;
  impl->height = desc.height;
  gl.CreateBuffers(1, &impl->frameUbo);
  gl.NamedBufferStorage(impl->frameUbo, sizeof(shared::SslrFrame), nullptr, GL_DYNAMIC_STORAGE_BIT);
  impl->label(GL_BUFFER, impl->frameUbo, "sslr.frame");
  gl.CreateBuffers(1, &impl->statsBuffer);
  gl.NamedBufferStorage(impl->statsBuffer, 4 * sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
  impl->label(GL_BUFFER, impl->statsBuffer, "sslr.stats");
  gl.CreateSamplers(1, &impl->nearestSampler);
  gl.CreateSamplers(1, &impl->linearSampler);
  for (GLuint s : {impl->nearestSampler, impl->linearSampler}) {
    const GLint filter = s == impl->linearSampler ? GL_LINEAR : GL_NEAREST;
    gl.SamplerParameteri(s, GL_TEXTURE_MIN_FILTER, filter);
    gl.SamplerParameteri(s, GL_TEXTURE_MAG_FILTER, filter);
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    // The host's depth texture may have comparison enabled; sslr reads raw depth.
    gl.SamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  }
  impl->label(GL_SAMPLER, impl->nearestSampler, "sslr.nearest");
  impl->label(GL_SAMPLER, impl->linearSampler, "sslr.linear");
  gl.CreateVertexArrays(1, &impl->vao);
  impl->label(GL_VERTEX_ARRAY, impl->vao, "sslr.emptyVao");
  impl->createTargets();
  return std::unique_ptr<Context>(new Context(std::move(impl)));
}

Status Context::resize(int width, int height) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    return Status::error("sslr: resize to " + std::to_string(width) + "x" + std::to_string(height) +
                         " is invalid (must be 1..16384 each)");
  if (width == impl_->width && height == impl_->height) return {};
  impl_->destroyTargets();
  impl_->width = width;
  impl_->height = height;
  impl_->createTargets();
  impl_->haveFrame = false;
  return {};
}

int Context::width() const { return impl_->width; }
int Context::height() const { return impl_->height; }
Status Context::dispatch(const FrameInputs& inputs, const Settings& settings) {
  return impl_->dispatch(inputs, settings);
}
Status Context::composite(GLName framebuffer) { return impl_->composite(framebuffer); }
GLName Context::reflectionTexture() const { return impl_->reflection; }
GLName Context::resolvedTexture() const { return impl_->resolved; }
GLName Context::hitTexture() const { return impl_->hit; }
GLName Context::iterationsTexture() const { return impl_->iterations; }
FrameStats Context::lastStats() const { return impl_->stats; }

}  // namespace sslr
