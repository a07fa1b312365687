// Pass 5, temporal reuse (passes/temporal.hpp; Settings::temporal).
#include "../context_impl.hpp"

namespace sslr {

// The history, its keys and its confidence output, on first use.
void Context::Impl::createTemporalResources(const FramePlan& f) {
  if (f.historyConfidence && temporal.confidence == 0)
    temporal.confidence = makeTexture(GL_R8, "sslr.historyConfidence");
  if (f.temporal && temporal.color == 0) {
    temporal.color = makeTexture(GL_RGBA16F, "sslr.history");
    temporal.key = makeTexture(GL_R32F, "sslr.historyKey");
  }
}

void TemporalPass::destroy(const detail::Gl& gl) {
  const GLuint textures[] = {color, key, confidence};
  gl.DeleteTextures(3, textures);
  color = key = confidence = 0;
  valid = false;
}

// Pass 5 (Settings::temporal): blend with the reprojected history, store this frame's output and
// keys, forget the tiles traced last frame and not now.
void Context::Impl::runTemporal(const FramePlan& f, const FrameInputs& in) {
  beginPass(f, 4);
  if (!f.temporal) return;
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  for (GLuint unit : {SSLR_UNIT_TEMPORAL_CURRENT, SSLR_UNIT_HISTORY, SSLR_UNIT_HISTORY_KEY})
    gl.BindSampler(unit, nearestSampler);
  useProgram(f.programs.temporal.blend);
  gl.bindTexture2D(SSLR_UNIT_MOTION, in.motionTexture);  // the pyramid's unit: free after the trace
  gl.BindSampler(SSLR_UNIT_MOTION, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_HIT_RECORD, trace.hit);  // written by the trace on the listed tiles (SSLR_TEMPORAL_HITS)
  gl.BindSampler(SSLR_UNIT_HIT_RECORD, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_TEMPORAL_CURRENT, resolved);
  gl.bindTexture2D(SSLR_UNIT_HISTORY, temporal.color);
  gl.bindTexture2D(SSLR_UNIT_HISTORY_KEY, temporal.key);
  bindImage(SSLR_IMAGE_TEMPORAL_OUTPUT, scratch, 0, GL_RGBA16F);
  if (f.historyConfidence)
    bindImage(SSLR_IMAGE_HISTORY_CONFIDENCE, temporal.confidence, 0, GL_R8);
  dispatchComputeIndirect(0);
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  useProgram(f.programs.temporal.store);
  gl.bindTexture2D(SSLR_UNIT_TEMPORAL_CURRENT, scratch);
  gl.bindTexture2D(SSLR_UNIT_HISTORY, 0);
  gl.bindTexture2D(SSLR_UNIT_HISTORY_KEY, 0);
  bindImage(SSLR_IMAGE_TEMPORAL_OUTPUT, resolved, 0, GL_RGBA16F);
  bindImage(SSLR_IMAGE_HISTORY, temporal.color, 0, GL_RGBA16F);
  bindImage(SSLR_IMAGE_HISTORY_KEY, temporal.key, 0, GL_R32F);
  dispatchComputeIndirect(0);
  memoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  useProgram(f.programs.temporal.cleanup);
  dispatchComputeIndirect(kCleanupDispatchOffset);
  temporal.valid = true;
}

}  // namespace sslr
