// Pass 3, the quad retrace (passes/trace.cpp runQuads; a deferred traversal at half resolution): one
// group per tile with a quad listed by 3_trace_quads.comp traces those quads with the whole
// tracer, before the shading pass reads the quads.
#include "passes/trace_common.glsl"
#include "passes/retrace_list.glsl"
#include "passes/trace_quad.glsl"

layout(local_size_x = SSLR_TILE_QUADS) in;

void main() {
  uint slot = retrace.entries[gl_WorkGroupID.x];
  uint steps = 0u;
  if (gl_LocalInvocationIndex < tiles.tileCoords[sslrQuadRetraceCountIndex(slot)])
    steps = sslrTraceQuad(slot, sslrEnterCoord(retrace.entries[sslrQuadRetraceRegion(slot) + gl_LocalInvocationIndex]));
  sslrCountRayWork(SSLR_RAY_WORK_QUAD_RETRACE, steps);
}
