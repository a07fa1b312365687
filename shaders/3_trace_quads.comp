// Pass 3, half resolution's quad rays (passes/trace.cpp runQuads; Settings::halfResolution): one
// invocation per 2x2 quad of a listed tile traces the quad's ray (passes/trace_quad.glsl). With a
// deferred second stage (ContextDesc::traversalPass) it runs the first stage alone and lists the
// quads that need the second; their retrace, one group per tile with a quad listed and before the
// shading pass reads the quads, is this program with the whole tracer in its retrace role
// (passes/retrace_list.glsl; never SSLR_QUADS_WIDE).
#include "passes/trace_common.glsl"
#include "passes/retrace_list.glsl"
#include "passes/trace_quad.glsl"

#ifdef SSLR_QUADS_WIDE
#define SSLR_QUADS_TILES 4u  // DeviceProfile::Gpu: four listed tiles a group (64 invocations, no half-empty warp)
#else
#define SSLR_QUADS_TILES 1u  // DeviceProfile::Software: one listed tile's quads a group (16 along x)
#endif
layout(local_size_x = SSLR_QUADS_TILES * SSLR_TILE_QUADS) in;

void main() {
  // The quad: of a listed tile, or in the retrace role one of those listed for the tile in list slot
  // `slot`. One call of sslrTraceQuad for both roles, so that the tracer is in the program once.
  uint slot;
  bool traced;
  ivec2 quad;
  if (uRetrace != 0) {
    slot = retrace.entries[gl_WorkGroupID.x];
    traced = gl_LocalInvocationIndex < tiles.tileCoords[sslrQuadRetraceCountIndex(slot)];
    quad = traced ? sslrEnterCoord(retrace.entries[sslrQuadRetraceRegion(slot) + gl_LocalInvocationIndex]) : ivec2(0);
  } else {
    slot = gl_WorkGroupID.x * SSLR_QUADS_TILES + gl_LocalInvocationIndex / uint(SSLR_TILE_QUADS);
    traced = slot < tiles.dispatchX;  // (the last wide group's tiles past the list trace nothing)
    quad = traced ? sslrTileOrigin(slot) / 2 + sslrTileQuad(gl_LocalInvocationIndex % uint(SSLR_TILE_QUADS)) : ivec2(0);
  }
  uint steps = traced ? sslrTraceQuad(slot, quad) : 0u;
  sslrCountRayWork(uRetrace != 0 ? SSLR_RAY_WORK_QUAD_RETRACE : SSLR_RAY_WORK_QUADS, steps);
}
