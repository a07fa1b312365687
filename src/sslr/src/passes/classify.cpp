// Pass 1, classification: the tile list (with the pyramid, its levels 0 and 1) and the clean-up of
// the previous frame's tiles (passes/classify.hpp).
#include "../context_impl.hpp"

namespace sslr {

// Pass 1: classification over the screen (the tile list; with the pyramid, its levels 0 and 1),
// then the clean-up of the tiles the previous frame traced and this one does not (DeviceProfile::Gpu:
// inside classification).
void Context::Impl::runClassify(const FramePlan& f, const FrameInputs& in) const {
  beginPass(f, 0);
  bindInputs(in);
  if (f.method == Method::PositionBuffer) {
    gl.bindTexture2D(SSLR_UNIT_POSITION, in.positionTexture);
    gl.BindSampler(SSLR_UNIT_POSITION, nearestSampler);
  }
  useProgram(f.programs.classify.classify);
  if (f.pyramid) bindPyramidLevels01();
  if (f.curvedSolids) {
    // The curved pass's dispatch (0, 1, 1) until the pyramid-args pass sets it; no quad listed.
    const GLuint curvedHeader[8] = {0, 1, 1, 0, 0, 0, 0, 0};
    bufferSubData(pyramid.curvedQuads, 0, sizeof(curvedHeader), curvedHeader);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_CURVED_SSBO, pyramid.curvedQuads);
  }
  if (f.wideClassify) {  // 2x2 tiles a group, the clean-up inside
    bindImage(SSLR_IMAGE_CLASSIFY_REFLECTION, reflection, 0, GL_RGBA16F);
    bindImage(SSLR_IMAGE_CLASSIFY_RESOLVED, resolved, 0, GL_RGBA16F);
    dispatchCompute(static_cast<GLuint>((area.tilesX + 1) / 2), static_cast<GLuint>((area.tilesY + 1) / 2),
                    static_cast<GLuint>(views));  // (z: one a view)
  } else {
    dispatchCompute(static_cast<GLuint>(area.tilesX), static_cast<GLuint>(area.tilesY), static_cast<GLuint>(views));
  }
  memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  if (f.wideClassify) return;
  useProgram(f.programs.classify.cleanup);
  bindImage(SSLR_IMAGE_REFLECTION, reflection, 0, GL_RGBA16F);
  bindImage(SSLR_IMAGE_RESOLVED, resolved, 0, GL_RGBA16F);
  dispatchComputeIndirect(kCleanupDispatchOffset);
  memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace sslr
