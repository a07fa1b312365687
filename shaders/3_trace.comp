// Pass 3, the trace (passes/trace.cpp runTrace): one invocation per pixel of a listed tile traces its
// ray and writes the reflection (rgb = hit colour x weights, a = blur weight), the resolved output
// (same rgb, a = coverage) and, with SSLR_DEBUG_OUTPUTS, the hit and iteration images.
// With a deferred second stage (ContextDesc::traversalPass, SSLR_DEFER_TRAVERSAL) it runs the first
// stage alone and lists the pixels that need the second, so that the second tracer's code is in no
// program that every pixel runs. The retrace of those pixels (and of those half resolution could
// not answer from their quad's ray) is this program with the whole tracer in its retrace role
// (passes/retrace_list.glsl).
#include "passes/trace_common.glsl"
#include "passes/retrace_list.glsl"
#include "passes/shade_pixel.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

bool sslrPixelHit(ivec2 px, SslrPixel q, out SslrHit hit, out bool ranTracer) {
#ifdef SSLR_DEFER_TRAVERSAL
  bool needsTraversal;
  hit = sslrTraceFirstStage(frame.proj, frame.surface, sslrRayParams(q), px, q.vsP, q.vsR, needsTraversal);
  ranTracer = !needsTraversal;
  if (needsTraversal) sslrListPixelForRetrace(px);
  return !needsTraversal;
#else
  hit = sslrTraceRay(sslrRayParams(q), px, q.vsP, q.vsV, q.vsR);
  ranTracer = true;
#ifdef SSLR_COUNT_TRAVERSAL
  // Inline under TraversalPass::Auto: count the pixels the traversal ran for (its feedback).
  if (uRetrace == 0 && sslrRanSecondStage(frame.trace, hit)) atomicAdd(retrace.count, 1u);
#endif
  return true;
#endif
}

void main() {
  // The pixel: of a listed tile, or in the retrace role one of SSLR_RETRACE_GROUP listed pixels a
  // group (past the list's end: none). One call of sslrShadePixel for both roles, so that the
  // tracer is in the program once.
  ivec2 px;
  bool inside;
  if (uRetrace != 0) {
    uint i = gl_WorkGroupID.x * uint(SSLR_RETRACE_GROUP) + gl_LocalInvocationIndex;
    inside = i < retrace.count;
    px = inside ? sslrEnterCoord(retrace.entries[i]) : ivec2(0);
  } else {
    px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
    inside = sslrInside(px);
  }
  uint steps = inside ? sslrShadePixel(px) : 0u;
  sslrCountRayWork(uRetrace != 0 ? SSLR_RAY_WORK_RETRACE : SSLR_RAY_WORK_TRACE, steps);
}
