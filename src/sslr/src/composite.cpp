// composite(): puts the resolved reflection into the host's framebuffer over the listed tiles.
#include <algorithm>

#include "context_impl.hpp"
#include "gl_state.hpp"

namespace sslr {

// The image draw buffer 0 of `framebuffer` (bound as the draw framebuffer: GL_DRAW_BUFFER0 is
// read from it) writes: attachment GL_NONE when there is none.
Context::Impl::DrawImage Context::Impl::drawBuffer0Image(GLName framebuffer) const {
  DrawImage image;
  gl.GetIntegerv(GL_DRAW_BUFFER0, &image.attachment);
  if (image.attachment == GL_NONE) return image;
  const auto parameter = [&](GLenum pname, GLint* value) {
    gl.GetNamedFramebufferAttachmentParameteriv(framebuffer, static_cast<GLenum>(image.attachment), pname, value);
  };
  parameter(GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &image.type);
  parameter(GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &image.name);
  // A name deleted while attached to a framebuffer that was not bound stays attached, but queries
  // by that name fail (GL_INVALID_OPERATION): asked first.
  const GLuint name = static_cast<GLuint>(image.name);
  image.deleted = (image.type == GL_TEXTURE && !gl.IsTexture(name)) ||
                  (image.type == GL_RENDERBUFFER && !gl.IsRenderbuffer(name));
  if (image.deleted) return image;
  if (image.type == GL_TEXTURE || image.type == GL_RENDERBUFFER)
    parameter(GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &image.componentType);
  if (image.type == GL_TEXTURE) {
    parameter(GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL, &image.level);
    gl.GetTextureLevelParameteriv(static_cast<GLuint>(image.name), image.level, GL_TEXTURE_WIDTH, &image.width);
    gl.GetTextureLevelParameteriv(static_cast<GLuint>(image.name), image.level, GL_TEXTURE_HEIGHT, &image.height);
    gl.GetTextureLevelParameteriv(static_cast<GLuint>(image.name), image.level, GL_TEXTURE_INTERNAL_FORMAT, &image.format);
  } else if (image.type == GL_RENDERBUFFER) {
    gl.GetNamedRenderbufferParameteriv(static_cast<GLuint>(image.name), GL_RENDERBUFFER_WIDTH, &image.width);
    gl.GetNamedRenderbufferParameteriv(static_cast<GLuint>(image.name), GL_RENDERBUFFER_HEIGHT, &image.height);
    gl.GetNamedRenderbufferParameteriv(static_cast<GLuint>(image.name), GL_RENDERBUFFER_INTERNAL_FORMAT, &image.format);
  }
  return image;
}

namespace {
// "texture 7" or "renderbuffer 7": the image named in messages.
std::string imageName(GLint type, GLint name) {
  return std::string(type == GL_TEXTURE ? "texture " : "renderbuffer ") + std::to_string(name);
}
}  // namespace

std::string Context::Impl::drawImageProblem(const DrawImage& image) const {
  if (image.type != GL_TEXTURE && image.type != GL_RENDERBUFFER) return "";
  const std::string what = imageName(image.type, image.name);
  if (image.deleted) return "draw buffer 0's " + what + " was deleted while attached";
  if (image.componentType == GL_INT || image.componentType == GL_UNSIGNED_INT)
    return "draw buffer 0 (" + what + ", internal format " + std::to_string(image.format) +
           ") holds integers, which the composite's blended draw cannot write";
  return "";
}

// The image draw buffer 0 of `framebuffer` writes must be a live, non-integer image covering the
// context's size: a smaller one would get only part of the reflection. (The default framebuffer's
// size is the window system's, which GL does not report: it is the host's to match.)
Status Context::Impl::checkCompositeTarget(GLName framebuffer) const {
  if (framebuffer == 0) return {};
  const DrawImage image = drawBuffer0Image(framebuffer);  // (bound by composite())
  if (image.attachment == GL_NONE)
    return Status::error(StatusCode::InvalidInput, "sslr: composite(): framebuffer " + std::to_string(framebuffer) +
                         " has no image on draw buffer 0, where the reflection is written");
  const std::string fb = "sslr: composite(): framebuffer " + std::to_string(framebuffer) + "'s ";
  if (const std::string problem = drawImageProblem(image); !problem.empty())
    return Status::error(StatusCode::InvalidInput, fb + problem);
  if (image.type != GL_TEXTURE && image.type != GL_RENDERBUFFER) return {};
  if (image.width < width || image.height < height)
    return Status::error(StatusCode::InvalidInput,
                         fb + "draw buffer 0 (" + imageName(image.type, image.name) + ") is " +
                             std::to_string(image.width) + "x" +
                             std::to_string(image.height) + ", smaller than the context's " + std::to_string(width) +
                             "x" + std::to_string(height));
  return {};
}

// A sized format prepare()'s scratch target can be made with (glTextureStorage2D takes sized
// formats only): the host's own where it is one of GL's colour-renderable sized formats, the
// 8-bit one of an unsized base format (glTexImage2D's GL_RGBA), else one of the same component
// type (the draw's machine code depends on the target's type and blending more than its size).
namespace {
GLenum scratchFormat(GLint format, GLint componentType) {
  switch (format) {
    case GL_R8: case GL_RG8: case GL_RGB8: case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_R16: case GL_RG16:
    case GL_RGBA16: case GL_RGB10_A2: case GL_RGB5_A1: case GL_RGBA4: case GL_RGB565: case GL_R11F_G11F_B10F:
    case GL_R16F: case GL_RG16F: case GL_RGBA16F: case GL_R32F: case GL_RG32F: case GL_RGBA32F:
      return static_cast<GLenum>(format);
    case GL_RED: return GL_R8;
    case GL_RG: return GL_RG8;
    case GL_RGB: return GL_RGB8;
    case GL_RGBA: return GL_RGBA8;
    case GL_SRGB: case GL_SRGB_ALPHA: case GL_SRGB8: return GL_SRGB8_ALPHA8;
    default: return componentType == GL_FLOAT ? GL_RGBA16F : GL_RGBA8;
  }
}
}  // namespace

// The composite's program: added (the default), or the fallback's draw (BlendOverFallback).
Expected<GLuint> Context::Impl::compositeProgram(bool overFallback) {
  const std::vector<std::pair<GLenum, const char*>> stages = {{GL_VERTEX_SHADER, "composite.vert"},
                                                               {GL_FRAGMENT_SHADER, "composite.frag"}};
  const std::string viewsDefine = views > 1 ? "#define SSLR_VIEWS " + std::to_string(views) + "\n" : "";
  return program(stages, viewsDefine + (overFallback ? "#define SSLR_COMPOSITE_FALLBACK 1\n" : ""));
}

// CompositeOptions that composite() and prepare()'s warm-up accept.
Status Context::Impl::checkCompositeOptions(const CompositeOptions& options) const {
  const bool blendOverFallback = options.mode == CompositeMode::BlendOverFallback;
  if (options.view < 0 || options.view >= views)
    return Status::error(StatusCode::InvalidSettings, "sslr: composite(): CompositeOptions::view " + std::to_string(options.view) +
                         " is not a view of the context (0.." + std::to_string(views - 1) + ")");
  if (options.mode != CompositeMode::Add && !blendOverFallback)
    return Status::error(StatusCode::InvalidSettings, "sslr: composite(): CompositeOptions::mode " +
                         std::to_string(static_cast<int>(options.mode)) + " is not a CompositeMode");
  if (blendOverFallback) {
    if (Status s = checkTexture(options.fallbackSpecularTexture, "CompositeOptions::fallbackSpecularTexture",
                                FormatInfo::Color, 3, nullptr, false);
        !s)
      return Status::error(s.code(), s.message() + " (CompositeMode::BlendOverFallback reads it)");
  } else if (options.fallbackSpecularTexture != 0) {
    return Status::error(StatusCode::InvalidSettings, "sslr: composite(): CompositeOptions::fallbackSpecularTexture is set but the mode "
                         "is Add, which does not read it (use CompositeMode::BlendOverFallback)");
  }
  return {};
}

Status Context::Impl::composite(GLName framebuffer, const CompositeOptions& options) {
  if (Status s = checkCurrentContext("composite()"); !s) return s;
  if (!haveFrame)
    return Status::error(StatusCode::NoFrame, "sslr: composite() needs a successful dispatch() first");
  if (frameIsRadiance)
    return Status::error(StatusCode::InvalidSettings, "sslr: composite(): the last dispatch traced with "
                         "Settings::output = OutputMode::Radiance, which holds no Fresnel term: apply your own "
                         "specular term to resolvedTexture(), or dispatch with OutputMode::Weighted");
  if (framebuffer != 0 && !gl.IsFramebuffer(framebuffer))
    return Status::error(StatusCode::InvalidInput, "sslr: composite(): " + std::to_string(framebuffer) +
                         " is not a framebuffer name");
  if (Status s = checkCompositeOptions(options); !s) return s;
  const bool blendOverFallback = options.mode == CompositeMode::BlendOverFallback;
  auto addProgram = compositeProgram(false);
  if (!addProgram) return addProgram.status();
  Expected<GLuint> fallbackProgram = GLuint(0);
  if (blendOverFallback) {
    fallbackProgram = compositeProgram(true);
    if (!fallbackProgram) return fallbackProgram.status();
  }
  detail::StateGuard guard(gl, true, views > 1);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  if (gl.CheckNamedFramebufferStatus(framebuffer, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return Status::error(StatusCode::InvalidInput, "sslr: composite(): framebuffer " + std::to_string(framebuffer) +
                         " is not complete");
  if (Status s = checkCompositeTarget(framebuffer); !s) return s;
  drawComposite(framebuffer, addProgram.value(), fallbackProgram.value(), options);
  return {};
}

void Context::Impl::drawComposite(GLName framebuffer, GLuint addProgram, GLuint fallbackProgram,
                                  const CompositeOptions& options) const {
  const bool blendOverFallback = options.mode == CompositeMode::BlendOverFallback;
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  gl.PushDebugGroup(GL_DEBUG_SOURCE_THIRD_PARTY, 0, -1, "sslr.composite");
  gl.BindVertexArray(vao);
  gl.BindBufferBase(GL_UNIFORM_BUFFER, SSLR_BINDING_FRAME_UBO, frameUbo);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_TILE_SSBO, tileBuffer);
  gl.BindBuffer(GL_DRAW_INDIRECT_BUFFER, tileBuffer);
  gl.bindTexture2D(SSLR_UNIT_COMPOSITE_RESOLVED, resolved);
  gl.BindSampler(SSLR_UNIT_COMPOSITE_RESOLVED, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_COMPOSITE_FALLBACK, blendOverFallback ? options.fallbackSpecularTexture : 0);
  gl.BindSampler(SSLR_UNIT_COMPOSITE_FALLBACK, nearestSampler);
  // Viewport and scissor index 0 only (the draw uses index 0; glViewport and glDisable would set
  // every index), and no per-fragment state of the host's that would change what is written.
  const GLfloat viewport[4] = {0.0f, 0.0f, static_cast<GLfloat>(width), static_cast<GLfloat>(height)};
  gl.ViewportIndexedfv(0, viewport);
  gl.Disablei(GL_SCISSOR_TEST, 0);
  gl.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  // The tiles are placed in the textures' rows, which are the framebuffer's: a host drawing with an
  // upper-left clip origin would see them mirrored. The depth mode is the host's (the draw's z = 0
  // lies inside either range, and the depth test is off).
  GLint clipDepthMode = GL_NEGATIVE_ONE_TO_ONE;
  gl.GetIntegerv(GL_CLIP_DEPTH_MODE, &clipDepthMode);
  gl.ClipControl(GL_LOWER_LEFT, static_cast<GLenum>(clipDepthMode));
  for (GLenum cap : detail::kCompositeDisables) gl.Disable(cap);
  for (GLenum i = 0; i < detail::kClipDistances; ++i) gl.Disable(GL_CLIP_DISTANCE0 + i);
  // Draw buffer 0 only (its alpha kept); other draw buffers are masked.
  gl.Enablei(GL_BLEND, 0);
  gl.BlendFuncSeparatei(0, GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  gl.ColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  GLint maxDrawBuffers = 0;
  gl.GetIntegerv(GL_MAX_DRAW_BUFFERS, &maxDrawBuffers);
  for (GLint i = 1; i < std::min(maxDrawBuffers, 8); ++i) gl.ColorMaski(i, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  // 6 vertices per listed tile, instance count written by classification (offset 12 bytes).
  if (views > 1) {  // the view drawn (composite.vert, composite.frag: uView)
    for (GLuint program : {addProgram, fallbackProgram})
      if (program != 0) gl.ProgramUniform1i(program, SSLR_COMPOSITE_VIEW_LOCATION, options.view);
  }
  if (blendOverFallback) {
    // existing - coverage * fallback first, as a subtraction by the blender: a fixed-point target
    // clamps a negative source to 0 before blending, so "reflection - coverage * fallback" cannot
    // be one additive draw.
    gl.UseProgram(fallbackProgram);
    gl.BlendEquationSeparatei(0, GL_FUNC_REVERSE_SUBTRACT, GL_FUNC_ADD);
    gl.DrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(kDrawArgsOffset));
  }
  gl.UseProgram(addProgram);
  gl.BlendEquationSeparatei(0, GL_FUNC_ADD, GL_FUNC_ADD);
  gl.DrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(kDrawArgsOffset));
  gl.PopDebugGroup();
}

// prepare(): composite()'s draw once, into a scratch target of the host's format (drivers build a
// draw's machine code for the target format and blend state it first runs with).
Status Context::Impl::warmUpComposite(const PrepareOptions& options) {
  const CompositeOptions& co = options.compositeOptions;
  if (Status s = checkCompositeOptions(co); !s) return s;
  GLint format = GL_RGBA8;
  if (options.framebuffer != 0) {
    if (!gl.IsFramebuffer(options.framebuffer))
      return Status::error(StatusCode::InvalidInput, "sslr: prepare(): PrepareOptions::framebuffer " +
                           std::to_string(options.framebuffer) + " is not a framebuffer name");
    DrawImage image;
    {
      detail::StateGuard guard(gl, true);  // bound for drawBuffer0Image, then the host's binding back
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, options.framebuffer);
      image = drawBuffer0Image(options.framebuffer);
    }
    if (image.type != GL_TEXTURE && image.type != GL_RENDERBUFFER)
      return Status::error(StatusCode::InvalidInput, "sslr: prepare(): PrepareOptions::framebuffer " +
                           std::to_string(options.framebuffer) + " has no image on draw buffer 0");
    if (const std::string problem = drawImageProblem(image); !problem.empty())
      return Status::error(StatusCode::InvalidInput, "sslr: prepare(): PrepareOptions::framebuffer " +
                           std::to_string(options.framebuffer) + "'s " + problem);
    format = static_cast<GLint>(scratchFormat(image.format, image.componentType));
  }
  auto addProgram = compositeProgram(false);
  if (!addProgram) return addProgram.status();
  auto fallbackProgram = compositeProgram(true);
  if (!fallbackProgram) return fallbackProgram.status();
  GLuint target = 0, fbo = 0;
  gl.CreateTextures(GL_TEXTURE_2D, 1, &target);
  gl.TextureStorage2D(target, 1, static_cast<GLenum>(format), SSLR_TILE_SIZE, SSLR_TILE_SIZE);
  gl.CreateFramebuffers(1, &fbo);
  gl.NamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
  Status result;
  {
    detail::StateGuard guard(gl, true, views > 1);
    if (gl.CheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE)
      drawComposite(fbo, addProgram.value(), fallbackProgram.value(), co);
    else
      result = Status::error(StatusCode::InvalidInput, "sslr: prepare(): the format of PrepareOptions::framebuffer's draw "
                             "buffer 0 (internal format " + std::to_string(format) + ") cannot be rendered to");
  }
  gl.DeleteFramebuffers(1, &fbo);
  gl.DeleteTextures(1, &target);
  return result;
}

}  // namespace sslr
