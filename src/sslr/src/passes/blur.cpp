// Pass 4, the separable roughness blur (passes/blur.hpp).
#include "../context_impl.hpp"

namespace sslr {

// Pass 4: the separable blur (resolved -> scratch -> resolved, radii from the reflection's alpha)
// over the tiles the trace listed as having a pixel to blur.
void Context::Impl::runBlur(const FramePlan& f) const {
  beginPass(f, 3);
  if (!f.blur) return;
  for (GLuint unit : {SSLR_UNIT_BLUR_INPUT, SSLR_UNIT_BLUR_REFLECTION, SSLR_UNIT_BLUR_UNBLURRED})
    gl.BindSampler(unit, nearestSampler);
  useProgram(f.programs.blur.horizontal);
  gl.bindTexture2D(SSLR_UNIT_BLUR_INPUT, resolved);
  gl.bindTexture2D(SSLR_UNIT_BLUR_REFLECTION, reflection);
  bindImage(SSLR_IMAGE_BLUR_OUTPUT, scratch, 0, GL_RGBA16F);
  dispatchComputeIndirect(kBlurDispatchOffset);
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  useProgram(f.programs.blur.vertical);
  gl.bindTexture2D(SSLR_UNIT_BLUR_INPUT, scratch);
  gl.bindTexture2D(SSLR_UNIT_BLUR_UNBLURRED, resolved);  // read where scratch is not written (see 4_blur.comp)
  bindImage(SSLR_IMAGE_BLUR_OUTPUT, resolved, 0, GL_RGBA16F);
  dispatchComputeIndirect(kBlurDispatchOffset);
}

}  // namespace sslr
