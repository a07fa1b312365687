// Pass 3, half resolution's quad rays (passes.cpp runQuads; Settings::halfResolution): one
// invocation per 2x2 quad of a listed tile traces the quad's ray (passes/trace_quad.glsl). With a
// deferred traversal it runs adaptive L alone and lists the quads that need the traversal for
// 3_retrace_quads.comp.
#include "passes/trace_common.glsl"
#if defined(SSLR_DEFER_TRAVERSAL) || defined(SSLR_COUNT_TRAVERSAL)
#include "passes/retrace_list.glsl"
#endif
#include "passes/trace_quad.glsl"

layout(local_size_x = SSLR_TILE_QUADS) in;  // one listed tile's quads (sslrTileQuad)

void main() { sslrTraceQuad(sslrTileOrigin(gl_WorkGroupID.x) / 2 + sslrTileQuad(gl_LocalInvocationIndex)); }
