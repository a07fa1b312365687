// Pass 3, half resolution's quad rays (passes.cpp runQuads; Settings::halfResolution): one
// invocation per 2x2 quad of a listed tile traces the quad's ray (passes/trace_quad.glsl). With a
// deferred traversal it runs adaptive L alone and lists the quads that need the traversal for
// 3_retrace_quads.comp.
#include "passes/trace_common.glsl"
#if defined(SSLR_DEFER_TRAVERSAL) || defined(SSLR_COUNT_TRAVERSAL)
#include "passes/retrace_list.glsl"
#endif
#include "passes/trace_quad.glsl"
#ifdef SSLR_COLLECT_STATS
#include "passes/ray_work.glsl"
#endif

#ifdef SSLR_QUADS_WIDE
// DeviceProfile::Gpu: four listed tiles a group (64 invocations, no half-empty warp).
layout(local_size_x = 4 * SSLR_TILE_QUADS) in;
void main() {
  uint slot = gl_WorkGroupID.x * 4u + gl_LocalInvocationIndex / uint(SSLR_TILE_QUADS);
  uint steps = 0u;
  if (slot < tiles.dispatchX)  // (the last group's tiles past the list trace nothing)
    steps = sslrTraceQuad(slot, sslrTileOrigin(slot) / 2 + sslrTileQuad(gl_LocalInvocationIndex % uint(SSLR_TILE_QUADS)));
#ifdef SSLR_COLLECT_STATS
  sslrCountRayWork(SSLR_RAY_WORK_QUADS, steps);
#endif
}
#else
// DeviceProfile::Software: one listed tile's quads a group (16 invocations along x).
layout(local_size_x = SSLR_TILE_QUADS) in;
void main() {
  uint steps = sslrTraceQuad(gl_WorkGroupID.x, sslrTileOrigin(gl_WorkGroupID.x) / 2 + sslrTileQuad(gl_LocalInvocationIndex));
#ifdef SSLR_COLLECT_STATS
  sslrCountRayWork(SSLR_RAY_WORK_QUADS, steps);
#endif
}
#endif
