// Saves the GL state an sslr call touches and restores it on destruction (RAII), so the host's
// state is exactly as it left it. The list is the contract documented in docs/integration.md.
#pragma once

#include <array>

#include "gl_functions.hpp"
#include "sslr_shared.h"

namespace sslr::detail {

// Texture units, image units and buffer binding points sslr binds during a call.
// Their names and meaning per pass: SSLR_UNIT_* and SSLR_IMAGE_* in sslr_shared.h.
inline constexpr int kTextureUnits = SSLR_UNIT_COUNT;
inline constexpr int kImageUnits = SSLR_IMAGE_COUNT;
inline constexpr int kSsboBindings = 3;  // 0 tile list, 1 stats, 2 retrace list / curved quads
inline constexpr int kUboBindings = 1;   // 0 frame constants

// Per-fragment state of the host's that the composite draw switches off (and the guard restores):
// a logic op, alpha-to-coverage, sample coverage or a sample mask would change what it writes.
inline constexpr GLenum kCompositeDisables[] = {GL_DEPTH_TEST,   GL_STENCIL_TEST,
                                                GL_CULL_FACE,    GL_RASTERIZER_DISCARD,
                                                GL_COLOR_LOGIC_OP, GL_SAMPLE_ALPHA_TO_COVERAGE,
                                                GL_SAMPLE_COVERAGE, GL_SAMPLE_MASK};
inline constexpr int kCompositeDisableCount = sizeof(kCompositeDisables) / sizeof(kCompositeDisables[0]);
// Clip distances the host enabled: the composite's vertex shader writes none, which leaves an
// enabled one undefined. GL 4.5 has at least 8; sslr saves and clears the first 8.
inline constexpr GLenum kClipDistances = 8;

class StateGuard {
 public:
  // `forDraw` additionally saves what the composite draw touches; `arrayTargets` each unit's
  // GL_TEXTURE_2D_ARRAY binding (a context of several views binds arrays; one view never does).
  StateGuard(const Gl& gl, bool forDraw, bool arrayTargets = false);
  ~StateGuard();
  StateGuard(const StateGuard&) = delete;
  StateGuard& operator=(const StateGuard&) = delete;

 private:
  struct IndexedBuffer {
    GLint name = 0;
    GLint64 start = 0;
    GLint64 size = 0;
  };
  struct ImageBinding {
    GLint name = 0, level = 0, layered = 0, layer = 0, access = GL_READ_ONLY, format = GL_R8;
  };
  const Gl& gl_;
  bool forDraw_, arrayTargets_;
  GLint program_ = 0, activeTexture_ = GL_TEXTURE0;
  std::array<GLint, kTextureUnits> textures_{}, arrayTextures_{}, samplers_{};
  std::array<ImageBinding, kImageUnits> images_{};
  std::array<IndexedBuffer, kSsboBindings> ssbos_{};
  std::array<IndexedBuffer, kUboBindings> ubos_{};
  GLint genericSsbo_ = 0, genericUbo_ = 0, dispatchIndirect_ = 0;
  // Draw state (composite only).
  GLint drawIndirect_ = 0, vao_ = 0, drawFramebuffer_ = 0;
  GLfloat viewport0_[4] = {};  // viewport index 0, the only one the composite sets
  GLint polygonMode_[2] = {GL_FILL, GL_FILL};  // a host's GL_LINE would draw the composite as wireframe
  // glClipControl: an upper-left origin would mirror the composite's tiles vertically.
  GLint clipOrigin_ = GL_LOWER_LEFT, clipDepthMode_ = GL_NEGATIVE_ONE_TO_ONE;
  std::array<GLboolean, kCompositeDisableCount> disabled_{};
  std::array<GLboolean, kClipDistances> clipDistances_{};
  GLboolean scissorTest0_ = 0;  // scissor test of viewport index 0
  GLboolean blend0_ = 0;
  GLint blendSrcRgb_ = 0, blendDstRgb_ = 0, blendSrcAlpha_ = 0, blendDstAlpha_ = 0;
  GLint blendEqRgb_ = 0, blendEqAlpha_ = 0;
  static constexpr int kMaxMasks = 8;
  int drawBuffers_ = 0;
  std::array<std::array<GLboolean, 4>, kMaxMasks> colorMasks_{};
};

}  // namespace sslr::detail
