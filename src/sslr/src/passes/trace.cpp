// Pass 3, the trace (passes/trace.hpp): over the listed tiles, with half resolution's quad pass
// before it and the retrace of the listed pixels after it.
#include "../context_impl.hpp"

namespace sslr {

// The trace's images and lists the plan needs that no earlier frame created.
void Context::Impl::createTraceResources(const FramePlan& f) {
  if (f.halfResolution && trace.quadHit == 0) {
    const int qw = (width + 1) / 2, qh = (height + 1) / 2;
    trace.quadHit = createTexture(GL_RGBA32F, 1, qw, qh);
    label(GL_TEXTURE, trace.quadHit, "sslr.quadHit");
    trace.quadSurface = createTexture(GL_RGBA16F, 1, qw, qh);
    label(GL_TEXTURE, trace.quadSurface, "sslr.quadSurface");
  }
  if ((f.retracePass || f.countTraversal) && trace.retraceList == 0) {
    gl.CreateBuffers(1, &trace.retraceList);
    // Header, then a pixel list (at most every pixel of the traced tiles) or the quad list (a slot
    // and a tile's quads per tile; passes/retrace_list.glsl).
    const size_t tileCount = static_cast<size_t>(tilesX()) * tilesY() * views;  // every view's
    gl.NamedBufferStorage(trace.retraceList,
                          static_cast<GLsizeiptr>((4 + tileCount * SSLR_TILE_SIZE * SSLR_TILE_SIZE) * sizeof(GLuint)),
                          nullptr, GL_DYNAMIC_STORAGE_BIT);
    label(GL_BUFFER, trace.retraceList, "sslr.retrace");
  }
  // The hit record and iteration images only for the frames that write them (20 B per pixel).
  if ((f.debugOutputs || f.temporal) && trace.hit == 0) trace.hit = makeTexture(GL_RGBA32F, "sslr.hit");
  if (f.hitDistance && trace.hitDistance == 0) trace.hitDistance = makeTexture(GL_R32F, "sslr.hitDistance");
  if (f.debugOutputs && trace.iterations == 0) trace.iterations = makeTexture(GL_R32F, "sslr.iterations");
}

void TracePass::destroy(const detail::Gl& gl) {
  const GLuint textures[] = {quadHit, quadSurface, hit, iterations, hitDistance};
  gl.DeleteTextures(5, textures);
  gl.DeleteBuffers(1, &retraceList);
  quadHit = quadSurface = hit = iterations = hitDistance = retraceList = 0;
}

// Pass 3: the trace over the listed tiles (half resolution: the quad pass first; a deferred
// traversal or half resolution: the retrace pass after).
void Context::Impl::runTrace(const FramePlan& f) const {
  beginPass(f, 2);
  const GLuint retraceHeader[4] = {0, 1, 1, 0};  // dispatch (0, 1, 1), count 0
  if (f.retracePass || f.countTraversal) {
    bufferSubData(trace.retraceList, 0, sizeof(retraceHeader), retraceHeader);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SSLR_BINDING_RETRACE_SSBO, trace.retraceList);
  }
  if (f.halfResolution) runQuads(f);
  useProgram(f.programs.trace.trace);
  if (f.programs.trace.retraceRole) gl.ProgramUniform1i(f.programs.trace.trace, SSLR_RETRACE_ROLE_LOCATION, 0);
  bindImage(SSLR_IMAGE_REFLECTION, reflection, 0, GL_RGBA16F);
  bindImage(SSLR_IMAGE_RESOLVED, resolved, 0, GL_RGBA16F);
  if (f.debugOutputs || f.temporal) bindImage(SSLR_IMAGE_HIT, trace.hit, 0, GL_RGBA32F);
  if (f.debugOutputs) bindImage(SSLR_IMAGE_ITERATIONS, trace.iterations, 0, GL_R32F);
  if (f.hitDistance)
    bindImage(SSLR_IMAGE_HIT_DISTANCE, trace.hitDistance, 0, GL_R32F);
  dispatchComputeIndirect(0);
  if (f.retracePass) {  // the pixels whose quad's ray did not answer them, or that need the traversal
    memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    useProgram(f.programs.trace.retrace);
    gl.ProgramUniform1i(f.programs.trace.retrace, SSLR_RETRACE_ROLE_LOCATION, 1);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, trace.retraceList);
    dispatchComputeIndirect(0);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileBuffer);
  }
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                GL_COMMAND_BARRIER_BIT);
}

// Half resolution's quad pass (one ray per 2x2 quad), its retrace of the quads that need the
// traversal, and the retrace list handed on to the pixels.
void Context::Impl::runQuads(const FramePlan& f) const {
  const GLuint retraceHeader[4] = {0, 1, 1, 0};
  useProgram(f.programs.trace.quads);
  if (f.programs.trace.quadRetraceRole) gl.ProgramUniform1i(f.programs.trace.quads, SSLR_RETRACE_ROLE_LOCATION, 0);
  bindImage(SSLR_IMAGE_QUAD_HIT, trace.quadHit, 0, GL_RGBA32F);
  bindImage(SSLR_IMAGE_QUAD_SURFACE, trace.quadSurface, 0, GL_RGBA16F);
  // One group per listed tile (Software: 16 invocations), or per 4 of them (Gpu: 64).
  dispatchComputeIndirect(f.wideClassify ? kQuadDispatchOffset : 0);
  if (f.quadRetracePass) {  // the quads whose ray needs the traversal
    memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    useProgram(f.programs.trace.quadRetrace);
    gl.ProgramUniform1i(f.programs.trace.quadRetrace, SSLR_RETRACE_ROLE_LOCATION, 1);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, trace.retraceList);
    dispatchComputeIndirect(0);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileBuffer);
  }
  if (f.quadRetracePass || f.countQuads) {
    // The quads that needed the traversal (Auto's feedback), then the list is the pixels'.
    memoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    if (f.countQuads && f.feedbackWritten)
      copyBufferSubData(trace.retraceList, feedback.buffer, 3 * sizeof(GLuint), 3 * sizeof(GLuint), sizeof(GLuint));
    bufferSubData(trace.retraceList, 0, sizeof(retraceHeader), retraceHeader);
  }
  memoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  gl.bindTexture2D(SSLR_UNIT_QUAD_HIT, trace.quadHit);
  gl.BindSampler(SSLR_UNIT_QUAD_HIT, nearestSampler);
  gl.bindTexture2D(SSLR_UNIT_QUAD_SURFACE, trace.quadSurface);
  gl.BindSampler(SSLR_UNIT_QUAD_SURFACE, nearestSampler);
}

}  // namespace sslr
