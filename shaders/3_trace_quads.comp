// Pass 3, half resolution's quad rays (passes/trace.cpp runQuads; Settings::halfResolution): one
// invocation per 2x2 quad of a listed tile traces the quad's ray (passes/trace_quad.glsl). With a
// deferred second stage (ContextDesc::traversalPass) it runs the first stage alone and lists the
// quads that need the second for 3_retrace_quads.comp.
#include "passes/trace_common.glsl"
#if defined(SSLR_DEFER_TRAVERSAL) || defined(SSLR_COUNT_TRAVERSAL)
#include "passes/retrace_list.glsl"
#endif
#include "passes/trace_quad.glsl"

#ifdef SSLR_QUADS_WIDE
#define SSLR_QUADS_TILES 4u  // DeviceProfile::Gpu: four listed tiles a group (64 invocations, no half-empty warp)
#else
#define SSLR_QUADS_TILES 1u  // DeviceProfile::Software: one listed tile's quads a group (16 along x)
#endif
layout(local_size_x = SSLR_QUADS_TILES * SSLR_TILE_QUADS) in;

void main() {
  uint slot = gl_WorkGroupID.x * SSLR_QUADS_TILES + gl_LocalInvocationIndex / uint(SSLR_TILE_QUADS);
  uint steps = 0u;
  if (slot < tiles.dispatchX)  // (the last wide group's tiles past the list trace nothing)
    steps = sslrTraceQuad(slot, sslrTileOrigin(slot) / 2 + sslrTileQuad(gl_LocalInvocationIndex % uint(SSLR_TILE_QUADS)));
  sslrCountRayWork(SSLR_RAY_WORK_QUADS, steps);
}
