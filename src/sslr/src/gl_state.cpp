#include "gl_state.hpp"

#include <algorithm>

namespace sslr::detail {

namespace {
void saveIndexed(const Gl& gl, GLenum nameQuery, GLenum startQuery, GLenum sizeQuery, GLuint index,
                 GLint& name, GLint64& start, GLint64& size) {
  gl.GetIntegeri_v(nameQuery, index, &name);
  gl.GetInteger64i_v(startQuery, index, &start);
  gl.GetInteger64i_v(sizeQuery, index, &size);
}
void restoreIndexed(const Gl& gl, GLenum target, GLuint index, GLint name, GLint64 start,
                    GLint64 size) {
  // A zero size means the whole buffer was bound with glBindBufferBase.
  if (name != 0 && size > 0)
    gl.BindBufferRange(target, index, static_cast<GLuint>(name), start, size);
  else
    gl.BindBufferBase(target, index, static_cast<GLuint>(name));
}
}  // namespace

StateGuard::StateGuard(const Gl& gl, bool forDraw, bool arrayTargets)
    : gl_(gl), forDraw_(forDraw), arrayTargets_(arrayTargets) {
  gl.GetIntegerv(GL_CURRENT_PROGRAM, &program_);
  gl.GetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
  for (int unit = 0; unit < kTextureUnits; ++unit) {
    gl.ActiveTexture(GL_TEXTURE0 + unit);
    gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &textures_[unit]);
    if (arrayTargets_) gl.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &arrayTextures_[unit]);
    gl.GetIntegerv(GL_SAMPLER_BINDING, &samplers_[unit]);
  }
  gl.ActiveTexture(static_cast<GLenum>(activeTexture_));
  for (int i = 0; i < kImageUnits; ++i) {
    ImageBinding& b = images_[i];
    gl.GetIntegeri_v(GL_IMAGE_BINDING_NAME, i, &b.name);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_LEVEL, i, &b.level);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYERED, i, &b.layered);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYER, i, &b.layer);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_ACCESS, i, &b.access);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_FORMAT, i, &b.format);
  }
  for (int i = 0; i < kSsboBindings; ++i)
    saveIndexed(gl, GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START,
                GL_SHADER_STORAGE_BUFFER_SIZE, i, ssbos_[i].name, ssbos_[i].start, ssbos_[i].size);
  for (int i = 0; i < kUboBindings; ++i)
    saveIndexed(gl, GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE, i,
                ubos_[i].name, ubos_[i].start, ubos_[i].size);
  gl.GetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &genericSsbo_);
  gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &genericUbo_);
  gl.GetIntegerv(GL_DISPATCH_INDIRECT_BUFFER_BINDING, &dispatchIndirect_);
  if (!forDraw_) return;
  gl.GetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &drawIndirect_);
  gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
  gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer_);
  gl.GetFloati_v(GL_VIEWPORT, 0, viewport0_);
  gl.GetIntegerv(GL_POLYGON_MODE, polygonMode_);
  gl.GetIntegerv(GL_CLIP_ORIGIN, &clipOrigin_);
  gl.GetIntegerv(GL_CLIP_DEPTH_MODE, &clipDepthMode_);
  for (int i = 0; i < kCompositeDisableCount; ++i) disabled_[i] = gl.IsEnabled(kCompositeDisables[i]);
  for (GLenum i = 0; i < kClipDistances; ++i) clipDistances_[i] = gl.IsEnabled(GL_CLIP_DISTANCE0 + i);
  scissorTest0_ = gl.IsEnabledi(GL_SCISSOR_TEST, 0);
  blend0_ = gl.IsEnabledi(GL_BLEND, 0);
  gl.GetIntegeri_v(GL_BLEND_SRC_RGB, 0, &blendSrcRgb_);
  gl.GetIntegeri_v(GL_BLEND_DST_RGB, 0, &blendDstRgb_);
  gl.GetIntegeri_v(GL_BLEND_SRC_ALPHA, 0, &blendSrcAlpha_);
  gl.GetIntegeri_v(GL_BLEND_DST_ALPHA, 0, &blendDstAlpha_);
  gl.GetIntegeri_v(GL_BLEND_EQUATION_RGB, 0, &blendEqRgb_);
  gl.GetIntegeri_v(GL_BLEND_EQUATION_ALPHA, 0, &blendEqAlpha_);
  GLint maxDrawBuffers = 0;
  gl.GetIntegerv(GL_MAX_DRAW_BUFFERS, &maxDrawBuffers);
  drawBuffers_ = std::min(maxDrawBuffers, kMaxMasks);
  for (int i = 0; i < drawBuffers_; ++i)
    gl.GetBooleani_v(GL_COLOR_WRITEMASK, i, colorMasks_[i].data());
}

StateGuard::~StateGuard() {
  const Gl& gl = gl_;
  gl.UseProgram(static_cast<GLuint>(program_));
  for (int unit = 0; unit < kTextureUnits; ++unit) {
    gl.ActiveTexture(GL_TEXTURE0 + unit);
    gl.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(textures_[unit]));
    if (arrayTargets_) gl.BindTexture(GL_TEXTURE_2D_ARRAY, static_cast<GLuint>(arrayTextures_[unit]));
    gl.BindSampler(unit, static_cast<GLuint>(samplers_[unit]));
  }
  gl.ActiveTexture(static_cast<GLenum>(activeTexture_));
  for (int i = 0; i < kImageUnits; ++i) {
    const ImageBinding& b = images_[i];
    gl.BindImageTexture(i, static_cast<GLuint>(b.name), b.level, static_cast<GLboolean>(b.layered),
                        b.layer, static_cast<GLenum>(b.access), static_cast<GLenum>(b.format));
  }
  for (int i = 0; i < kSsboBindings; ++i)
    restoreIndexed(gl, GL_SHADER_STORAGE_BUFFER, i, ssbos_[i].name, ssbos_[i].start, ssbos_[i].size);
  for (int i = 0; i < kUboBindings; ++i)
    restoreIndexed(gl, GL_UNIFORM_BUFFER, i, ubos_[i].name, ubos_[i].start, ubos_[i].size);
  // glBindBufferBase/Range also set the generic binding: restore it last.
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(genericSsbo_));
  gl.BindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(genericUbo_));
  gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, static_cast<GLuint>(dispatchIndirect_));
  if (!forDraw_) return;
  gl.BindBuffer(GL_DRAW_INDIRECT_BUFFER, static_cast<GLuint>(drawIndirect_));
  gl.BindVertexArray(static_cast<GLuint>(vao_));
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer_));
  gl.ViewportIndexedfv(0, viewport0_);
  gl.PolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(polygonMode_[0]));
  gl.ClipControl(static_cast<GLenum>(clipOrigin_), static_cast<GLenum>(clipDepthMode_));
  auto set = [&](GLenum cap, GLboolean on) { on ? gl.Enable(cap) : gl.Disable(cap); };
  for (int i = 0; i < kCompositeDisableCount; ++i) set(kCompositeDisables[i], disabled_[i]);
  for (GLenum i = 0; i < kClipDistances; ++i) set(GL_CLIP_DISTANCE0 + i, clipDistances_[i]);
  scissorTest0_ ? gl.Enablei(GL_SCISSOR_TEST, 0) : gl.Disablei(GL_SCISSOR_TEST, 0);
  blend0_ ? gl.Enablei(GL_BLEND, 0) : gl.Disablei(GL_BLEND, 0);
  gl.BlendFuncSeparatei(0, static_cast<GLenum>(blendSrcRgb_), static_cast<GLenum>(blendDstRgb_),
                        static_cast<GLenum>(blendSrcAlpha_), static_cast<GLenum>(blendDstAlpha_));
  gl.BlendEquationSeparatei(0, static_cast<GLenum>(blendEqRgb_), static_cast<GLenum>(blendEqAlpha_));
  for (int i = 0; i < drawBuffers_; ++i)
    gl.ColorMaski(i, colorMasks_[i][0], colorMasks_[i][1], colorMasks_[i][2], colorMasks_[i][3]);
}

}  // namespace sslr::detail
