// Pass 3, the trace (passes/trace.cpp runTrace): one invocation per pixel of a listed tile traces its
// ray and writes the reflection (rgb = hit colour x weights, a = blur weight), the resolved output
// (same rgb, a = coverage) and, with SSLR_DEBUG_OUTPUTS, the hit and iteration images.
// With a deferred second stage (ContextDesc::traversalPass, SSLR_DEFER_TRAVERSAL) it runs the first
// stage alone and lists the pixels that need the second for 3_retrace.comp, so that the second
// tracer's code is in no program that every pixel runs.
#include "passes/trace_common.glsl"
#if defined(SSLR_DEFER_TRAVERSAL) || defined(SSLR_COUNT_TRAVERSAL)
#include "passes/retrace_list.glsl"
#endif
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
  if (sslrRanSecondStage(frame.trace, hit)) atomicAdd(retrace.count, 1u);
#endif
  return true;
#endif
}

void main() {
  ivec2 px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  uint steps = sslrInside(px) ? sslrShadePixel(px) : 0u;
  sslrCountRayWork(SSLR_RAY_WORK_TRACE, steps);
}
