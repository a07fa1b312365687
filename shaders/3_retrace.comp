// Pass 3, the retrace (passes/trace.cpp runTrace): traces and shades, with the whole tracer, the pixels
// listed by 3_trace.comp (deferred traversal) or 3_shade_from_quads.comp (half resolution).
#include "passes/trace_common.glsl"
#include "passes/retrace_list.glsl"
#include "passes/shade_pixel.glsl"

layout(local_size_x = SSLR_RETRACE_GROUP) in;

bool sslrPixelHit(ivec2 px, SslrPixel q, out SslrHit hit, out bool ranTracer) {
  hit = sslrTraceRay(sslrRayParams(q), px, q.vsP, q.vsV, q.vsR);
  ranTracer = true;
  return true;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint steps = i < retrace.count ? sslrShadePixel(sslrEnterCoord(retrace.entries[i])) : 0u;
  sslrCountRayWork(SSLR_RAY_WORK_RETRACE, steps);
}
