// Pass 2, curved solids (passes/pyramid.cpp runPyramid; sslr_shared.h, "Curved solids"): for each quad
// listed because its normals turn, level 1's cell with the solids' backs (over the plain cell
// already written) and its pixels' extra depths in level 0. A pass of its own so that the math
// costs only the listed quads.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#include "passes/pyramid_levels01.glsl"

layout(local_size_x = 64) in;

// A 2x2 quad of the G-buffer (level 1's cell `cell`): its pixels clamped to the screen
// (sslrQuadPixel), their depths and packed normal texels. Straight-line code: a loop with
// per-pixel branches runs slower on SIMD CPU rasterizers.
struct SslrQuad {
  ivec2 p0, p1, p2, p3;
  vec4 depths;
  vec4 n0, n1, n2, n3;
};
SslrQuad sslrLoadQuad(ivec2 cell) {
  ivec2 last = ivec2(frame.surface.width, frame.surface.height) - 1;
  SslrQuad q;
  q.p0 = sslrQuadPixel(cell, 0, last);
  q.p1 = sslrQuadPixel(cell, 1, last);
  q.p2 = sslrQuadPixel(cell, 2, last);
  q.p3 = sslrQuadPixel(cell, 3, last);
  q.depths = vec4(texelFetch(uDepth, sslrTexel(q.p0), 0).r, texelFetch(uDepth, sslrTexel(q.p1), 0).r,
                  texelFetch(uDepth, sslrTexel(q.p2), 0).r, texelFetch(uDepth, sslrTexel(q.p3), 0).r);
  q.n0 = texelFetch(uNormal, sslrTexel(q.p0), 0);
  q.n1 = texelFetch(uNormal, sslrTexel(q.p1), 0);
  q.n2 = texelFetch(uNormal, sslrTexel(q.p2), 0);
  q.n3 = texelFetch(uNormal, sslrTexel(q.p3), 0);
  return q;
}

void main() {
  // Classification under DeviceProfile::Gpu sizes this dispatch while it lists tiles, so a frame
  // that lists none may still launch groups; they return here (such a frame needs no pyramid).
  if (gl_GlobalInvocationID.x >= curved.count || tiles.dispatchX == 0u) return;
  ivec2 cell = sslrEnterCoord(curved.quads[gl_GlobalInvocationID.x]);
  SslrQuad q = sslrLoadQuad(cell);
  vec4 extra;
  vec2 level1 = sslrHiZLevel1Cell(frame.proj, frame.surface, frame.trace, q.p0, q.p1, q.p2, q.p3, q.depths, q.n0, q.n1,
                                  q.n2, q.n3, extra);
  imageStore(uLevel1, SSLR_AT(cell), vec4(level1, 0.0f, 0.0f));
  sslrWriteLevel0(cell, q.depths, extra);
}
