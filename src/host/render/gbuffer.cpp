#include "sslr_host/gbuffer.hpp"

#include <algorithm>

#include <cmath>
#include <cstring>

#include "sslr_host/embedded_shaders.hpp"
#include "sslr_shared.h"

namespace sslr::host {

namespace {

struct Vertex {
  float position[3];
  float normal[3];
  float uv[2];
};

glm::mat4 toFloat(const glm::dmat4& m) { return glm::mat4(m); }

}  // namespace

GpuScene::GpuScene(const Scene& scene) : scene_(scene) {
  // Sized once: growing by doubling would hold up to twice the geometry while it uploads (the
  // loader's budget counts one upload copy).
  size_t vertexCount = 0, indexCount = 0;
  for (const Mesh& m : scene.meshes) {
    vertexCount += m.positions.size();
    indexCount += m.indices.size();
  }
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
  vertices.reserve(vertexCount);
  indices.reserve(indexCount);
  for (const Mesh& m : scene.meshes) {
    Draw d;
    d.baseVertex = static_cast<GLint>(vertices.size());
    d.firstIndex = indices.size();
    d.indexCount = static_cast<GLsizei>(m.indices.size());
    d.material = m.material;
    d.worldFromModel = m.worldFromModel;
    for (size_t i = 0; i < m.positions.size(); ++i) {
      Vertex v{};
      std::memcpy(v.position, &m.positions[i], sizeof v.position);
      const glm::vec3 n = i < m.normals.size() ? m.normals[i] : glm::vec3(0, 0, 1);
      std::memcpy(v.normal, &n, sizeof v.normal);
      const glm::vec2 uv = i < m.uvs.size() ? m.uvs[i] : glm::vec2(0.0f);
      std::memcpy(v.uv, &uv, sizeof v.uv);
      vertices.push_back(v);
    }
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
    draws_.push_back(d);
  }
  glCreateBuffers(1, &vbo_);
  glNamedBufferStorage(vbo_, static_cast<GLsizeiptr>(std::max<size_t>(vertices.size(), 1) * sizeof(Vertex)),
                       vertices.empty() ? nullptr : vertices.data(), 0);
  glCreateBuffers(1, &ibo_);
  glNamedBufferStorage(ibo_, static_cast<GLsizeiptr>(std::max<size_t>(indices.size(), 1) * 4),
                       indices.empty() ? nullptr : indices.data(), 0);
  glCreateVertexArrays(1, &vao_);
  glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao_, ibo_);
  const GLuint offsets[3] = {offsetof(Vertex, position), offsetof(Vertex, normal), offsetof(Vertex, uv)};
  const GLint sizes[3] = {3, 3, 2};
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vao_, a);
    glVertexArrayAttribFormat(vao_, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
    glVertexArrayAttribBinding(vao_, a, 0);
  }
  for (const Texture& t : scene.textures) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    const int levels = 1 + static_cast<int>(std::floor(std::log2(std::max(t.width, t.height))));
    glTextureStorage2D(tex, levels, GL_SRGB8_ALPHA8, t.width, t.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(tex, 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba8.data());
    glGenerateTextureMipmap(tex);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    textures_.push_back(tex);
  }
}

GpuScene::~GpuScene() {
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vbo_);
  glDeleteBuffers(1, &ibo_);
  if (!textures_.empty()) glDeleteTextures(static_cast<GLsizei>(textures_.size()), textures_.data());
}

Expected<std::unique_ptr<GBuffer>> GBuffer::create(const GBufferOptions& o) {
  if (o.width <= 0 || o.height <= 0 || o.width > 16384 || o.height > 16384)
    return Status::error("G-buffer size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                         " is invalid (1..16384 each)");
  auto g = std::unique_ptr<GBuffer>(new GBuffer());
  g->options_ = o;
  auto make = [&](GLenum format, const char* label) {
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, o.width, o.height);
    glObjectLabel(GL_TEXTURE, t, -1, label);
    return t;
  };
  g->color_ = make(GL_R11F_G11F_B10F, "host.gbuffer.color");
  g->normal_ = make(o.normals == NormalEncoding::Octahedral ? GL_RGBA16 : GL_RGBA8, "host.gbuffer.normal");
  g->depth_ = make(o.depth == DepthMode::GlDefault ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT32F,
                   "host.gbuffer.depth");
  if (o.withPosition) g->position_ = make(GL_RGBA32F, "host.gbuffer.position");
  if (o.withBackDepth) {
    g->backDepth_ = make(o.depth == DepthMode::GlDefault ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT32F,
                         "host.gbuffer.backDepth");
    glCreateFramebuffers(1, &g->backFbo_);
    glNamedFramebufferTexture(g->backFbo_, GL_DEPTH_ATTACHMENT, g->backDepth_, 0);
    glNamedFramebufferDrawBuffer(g->backFbo_, GL_NONE);
    if (glCheckNamedFramebufferStatus(g->backFbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      return Status::error("back-face depth framebuffer is incomplete");
  }
  g->fallback_ = make(GL_R11F_G11F_B10F, "host.fallbackSpecular");
  glCreateFramebuffers(1, &g->fbo_);
  glNamedFramebufferTexture(g->fbo_, GL_COLOR_ATTACHMENT0, g->color_, 0);
  glNamedFramebufferTexture(g->fbo_, GL_COLOR_ATTACHMENT1, g->normal_, 0);
  if (g->position_ != 0) glNamedFramebufferTexture(g->fbo_, GL_COLOR_ATTACHMENT2, g->position_, 0);
  glNamedFramebufferTexture(g->fbo_, GL_COLOR_ATTACHMENT3, g->fallback_, 0);
  glNamedFramebufferTexture(g->fbo_, GL_DEPTH_ATTACHMENT, g->depth_, 0);
  const GLenum buffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                             g->position_ != 0 ? GLenum(GL_COLOR_ATTACHMENT2) : GLenum(GL_NONE), GL_COLOR_ATTACHMENT3};
  glNamedFramebufferDrawBuffers(g->fbo_, 4, buffers);
  if (glCheckNamedFramebufferStatus(g->fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return Status::error("G-buffer framebuffer is incomplete");
  auto program = linkHostProgram({{GL_VERTEX_SHADER, "host/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "host/gbuffer.frag"}});
  if (!program) return Status::error(program.error());
  g->program_ = program.value();
  return g;
}

GBuffer::~GBuffer() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteFramebuffers(1, &backFbo_);
  const GLuint textures[6] = {color_, normal_, depth_, position_, fallback_, backDepth_};
  glDeleteTextures(6, textures);
  glDeleteProgram(program_);
}

Status GBuffer::render(const GpuScene& gpu, const Camera& camera, glm::dvec2 jitterPx) {
  if (std::string why = camera.validate(); !why.empty()) return Status::error("camera: " + why);
  const Scene& scene = gpu.scene();
  const double aspect = static_cast<double>(options_.width) / options_.height;
  viewFromWorld_ = camera.viewFromWorld();
  clipFromView_ = camera.clipFromView(options_.depth, aspect, jitterPx, {options_.width, options_.height});
  const DepthConvention conv = depthConvention(options_.depth);
  const bool reversed = conv.reversedZ;

  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, options_.width, options_.height);
  glClipControl(GL_LOWER_LEFT, conv.range == DepthRange::ZeroToOne ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(reversed ? GL_GREATER : GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  const float background[4] = {scene.background.r, scene.background.g, scene.background.b, 1.0f};
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(fbo_, GL_COLOR, 0, background);
  glClearNamedFramebufferfv(fbo_, GL_COLOR, 1, zero);
  if (position_ != 0) glClearNamedFramebufferfv(fbo_, GL_COLOR, 2, zero);
  glClearNamedFramebufferfv(fbo_, GL_COLOR, 3, zero);
  const float clearDepth = reversed ? 0.0f : 1.0f;
  glClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, &clearDepth);

  glUseProgram(program_);
  glBindVertexArray(gpu.vao());
  const glm::vec3 vsLight = glm::normalize(glm::vec3(viewFromWorld_ * glm::dvec4(glm::dvec3(scene.lightDirection), 0.0)));
  const glm::vec3 vsUp = glm::normalize(glm::vec3(viewFromWorld_ * glm::dvec4(0.0, 1.0, 0.0, 0.0)));
  glProgramUniform3fv(program_, 9, 1, &vsLight.x);
  glProgramUniform3fv(program_, 10, 1, &vsUp.x);
  glProgramUniform3fv(program_, 12, 1, &scene.background.x);
  glProgramUniform1i(program_, 13, camera.orthographic ? 1 : 0);
  glProgramUniform1i(program_, 11, options_.normals == NormalEncoding::Octahedral ? SSLR_NORMALS_OCTAHEDRAL
                                                                                  : SSLR_NORMALS_XYZ_UNORM);
  for (const GpuScene::Draw& d : gpu.draws()) {
    const glm::dmat4 viewFromModel = viewFromWorld_ * d.worldFromModel;
    const glm::mat4 clipFromModel = toFloat(clipFromView_ * viewFromModel);
    const glm::mat4 viewFromModelF = toFloat(viewFromModel);
    const glm::mat3 normalMatrix = glm::mat3(normalMatrixOf(viewFromModel));
    glProgramUniformMatrix4fv(program_, 0, 1, GL_FALSE, &clipFromModel[0][0]);
    glProgramUniformMatrix4fv(program_, 1, 1, GL_FALSE, &viewFromModelF[0][0]);
    glProgramUniformMatrix3fv(program_, 2, 1, GL_FALSE, &normalMatrix[0][0]);
    const Material& m = scene.materials.at(static_cast<size_t>(d.material));
    glProgramUniform3fv(program_, 3, 1, &m.baseColor.x);
    glProgramUniform1f(program_, 4, m.metallic);
    glProgramUniform1f(program_, 5, m.roughness);
    glProgramUniform1f(program_, 6, reflectance(m));
    const glm::vec3 emission = m.baseColor * m.emissive + m.emissiveColor;
    glProgramUniform3fv(program_, 7, 1, &emission.x);
    const GLuint tex = gpu.texture(m.baseColorTexture);
    glProgramUniform1i(program_, 8, tex != 0 ? 1 : 0);
    glBindTextureUnit(0, tex);
    glDrawElementsBaseVertex(GL_TRIANGLES, d.indexCount, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(d.firstIndex * 4), d.baseVertex);
  }
  if (backFbo_ != 0) renderBackDepth(gpu, clearDepth);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return {};
}

// The same draws into the back-face depth alone, front faces culled: per pixel, the nearest back
// face. A transform that mirrors (negative determinant) turns a mesh's winding over.
void GBuffer::renderBackDepth(const GpuScene& gpu, float clearDepth) {
  glBindFramebuffer(GL_FRAMEBUFFER, backFbo_);
  glClearNamedFramebufferfv(backFbo_, GL_DEPTH, 0, &clearDepth);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  for (const GpuScene::Draw& d : gpu.draws()) {
    const glm::dmat4 viewFromModel = viewFromWorld_ * d.worldFromModel;
    const glm::mat4 clipFromModel = toFloat(clipFromView_ * viewFromModel);
    glProgramUniformMatrix4fv(program_, 0, 1, GL_FALSE, &clipFromModel[0][0]);
    glFrontFace(glm::determinant(glm::dmat3(d.worldFromModel)) < 0.0 ? GL_CW : GL_CCW);
    glDrawElementsBaseVertex(GL_TRIANGLES, d.indexCount, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(d.firstIndex * 4), d.baseVertex);
  }
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  glDisable(GL_CULL_FACE);
}

FrameInputs GBuffer::frameInputs() const {
  FrameInputs in;
  in.colorTexture = color_;
  in.normalTexture = normal_;
  in.depthTexture = depth_;
  in.positionTexture = position_;
  in.backDepthTexture = backDepth_;
  in.clipFromView = clipFromView_;
  in.depth = depthConvention(options_.depth);
  if (options_.normals == NormalEncoding::Octahedral) {
    in.surface = SurfaceLayout{NormalEncoding::Octahedral, 2, 3, 0.0f, 1.0f};
  } else {
    in.surface = SurfaceLayout{NormalEncoding::XyzUnorm, -1, 3, 0.0f, 1.0f};
  }
  return in;
}

int GBuffer::bytesPerPixel() const {
  return 4 + (options_.normals == NormalEncoding::Octahedral ? 8 : 4) + 4;
}

Image readTexture(GLuint texture, int width, int height, int channels, GLenum format) {
  Image img;
  img.width = width;
  img.height = height;
  img.channels = channels;
  img.pixels.assign(static_cast<size_t>(width) * height * channels, 0.0f);
  if (texture == 0) return img;  // not created yet (sslr's debug images before a debug frame): zeros
  if (format == 0) format = channels == 1 ? GL_RED : channels == 2 ? GL_RG : channels == 3 ? GL_RGB : GL_RGBA;
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture, 0, format, GL_FLOAT, static_cast<GLsizei>(img.pixels.size() * sizeof(float)),
                    img.pixels.data());
  return img;
}

Image GBuffer::readColor() const { return readTexture(color_, width(), height(), 3); }
Image GBuffer::readFallbackSpecular() const { return readTexture(fallback_, width(), height(), 3); }
Image GBuffer::readNormalPacked() const { return readTexture(normal_, width(), height(), 4); }
bool GBuffer::showsNothing(const Image& depth) const {
  const float clearDepth = frameInputs().depth.reversedZ ? 0.0f : 1.0f;
  return std::all_of(depth.pixels.begin(), depth.pixels.end(), [clearDepth](float d) { return d == clearDepth; });
}

Image GBuffer::readDepth() const { return readTexture(depth_, width(), height(), 1, GL_DEPTH_COMPONENT); }
Image GBuffer::readBackDepth() const {
  return backDepth_ != 0 ? readTexture(backDepth_, width(), height(), 1, GL_DEPTH_COMPONENT) : Image{};
}
Image GBuffer::readPosition() const {
  return position_ != 0 ? readTexture(position_, width(), height(), 4) : Image{};
}

Image decodeNormals(const Image& packed, NormalEncoding encoding) {
  Image out;
  out.width = packed.width;
  out.height = packed.height;
  out.channels = 3;
  out.pixels.resize(static_cast<size_t>(out.width) * out.height * 3);
  shared::SslrSurface s{};
  s.normalEncoding = encoding == NormalEncoding::Octahedral ? SSLR_NORMALS_OCTAHEDRAL : SSLR_NORMALS_XYZ_UNORM;
  for (size_t p = 0; p < static_cast<size_t>(out.width) * out.height; ++p) {
    const float* src = &packed.pixels[p * packed.channels];
    glm::vec4 v(src[0], packed.channels > 1 ? src[1] : 0.0f, packed.channels > 2 ? src[2] : 0.0f,
                packed.channels > 3 ? src[3] : 0.0f);
    glm::vec3 n(0.0f);
    if (!shared::sslrDecodeNormal(s, v, n)) n = glm::vec3(0.0f);
    std::memcpy(&out.pixels[p * 3], &n, sizeof n);
  }
  return out;
}

Image reconstructPositions(const Image& depth, const glm::dmat4& clipFromView, DepthConvention convention) {
  Image out;
  out.width = depth.width;
  out.height = depth.height;
  out.channels = 4;
  out.pixels.assign(static_cast<size_t>(out.width) * out.height * 4, 0.0f);
  const shared::SslrProjection p =
      shared::sslrProjectionFromMatrix(clipFromView, convention.range == DepthRange::ZeroToOne);
  shared::SslrSurface s{};
  s.reversedZ = convention.reversedZ ? 1 : 0;
  const glm::vec2 size(static_cast<float>(depth.width), static_cast<float>(depth.height));
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) {
      const float d = depth.at(x, y, 0);
      if (!shared::sslrIsGeometryDepth(s, d)) continue;
      const glm::vec3 v = shared::sslrViewFromUvDepth(p, shared::sslrUvFromPixel({x, y}, size), d);
      float* dst = &out.at(x, y, 0);
      dst[0] = v.x;
      dst[1] = v.y;
      dst[2] = v.z;
      dst[3] = 1.0f;
    }
  return out;
}

Expected<GLuint> linkHostProgram(const std::vector<std::pair<GLenum, const char*>>& stages) {
  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  for (const auto& [stage, entry] : stages) {
    const char* body = embeddedShader(entry);
    if (body == nullptr) {
      cleanup();
      return Status::error(std::string("no embedded host shader ") + entry);
    }
    const char* sources[] = {"#version 450 core\n", body};
    GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 2, sources, nullptr);
    glCompileShader(shader);
    shaders.push_back(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[8192] = {};
      glGetShaderInfoLog(shader, sizeof log, nullptr, log);
      cleanup();
      return Status::error(std::string("compiling ") + entry + " failed:\n" + annotateShaderLog(log));
    }
  }
  GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  cleanup();
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    return Status::error(std::string("linking ") + stages.front().second + " failed: " + log);
  }
  return program;
}

}  // namespace sslr::host
