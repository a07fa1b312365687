// shared/pyramid.h - The min-max depth pyramid of the hierarchical traversal.
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_PYRAMID_H
#define SSLR_SHARED_PYRAMID_H

#include "language.h"
#include "projection.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- Min-max depth pyramid (hierarchical traversal) -----------------------------------------
// Level l >= 1 holds, per 2^l x 2^l cell, the (min, max) of the raw window depth of its pixels
// (with curved solids, the far end reaches the backs of their solids: "Curved solids" below).
// Level l has ceil(size / 2^l) cells per axis, so cell c of level l covers exactly pixels
// [c 2^l, (c + 1) 2^l) of the screen. Level 0 is the pyramid's too (mip 0 of the same texture):
// per pixel, its depth as sslrHiZTexel reads it and its curved solid's extra depth
// (sslrHiZLevel0Texel; a quad of background alone gets none, and the walk never reads level 0
// there). The traversal's walk thus reads every level, and a pixel's extra depth, in
// one fetch per step: with level 0 in the depth buffer and the extra depths in a texture of
// their own, SIMD lanes at different levels fetched from all three (llvmpipe runs every branch's
// fetch under lane masks; docs/design-notes.md).

// What the cells hold behind each pixel (thickness.h): curved solids, off where a back-face depth
// measures the solids and for FidelityFX SSSR; the measured back-face depth where the host gives
// one. Compiled in on the GPU (SSLR_CURVED_SOLIDS, SSLR_BACK_DEPTH); the CPU reads the block.
SSLR_FN bool sslrCurvedSolids(SslrTraceParams t) {
#ifdef SSLR_CURVED_SOLIDS
  return SSLR_CURVED_SOLIDS != 0;
#else
  return t.curvedSolids != 0;
#endif
}
SSLR_FN bool sslrBackDepth(SslrSurface s) {
#ifdef SSLR_BACK_DEPTH
  return SSLR_BACK_DEPTH != 0;
#else
  return s.hasBackDepth != 0;
#endif
}

// Levels worth building: the top level's cells are about an eighth of the larger screen side
// (coarser cells would cover most of the screen and skip nothing).
SSLR_FN int sslrHiZLevelCount(int width, int height) {
  int side = max(max(width, height), 1);
  int levels = 0;
  while (levels < SSLR_HIZ_MAX_LEVELS && (side >> (levels + 1)) >= 8) ++levels;
  return max(levels, 1);
}

// The pyramid's (min, max) for a cell without pixels (outside the screen): neutral in both.
SSLR_FN vec2 sslrHiZEmpty() { return vec2(2.0f, -1.0f); }

// One depth texel as the pyramid stores it: background, NaN and out-of-range depth all become the
// clear value (the farthest depth), so nothing that is not geometry can stop a ray.
SSLR_FN vec2 sslrHiZTexel(SslrSurface s, float depth) {
  float d = sslrIsGeometryDepth(s, depth) ? depth : sslrClearDepth(s);
  return vec2(d, d);
}

SSLR_FN vec2 sslrHiZReduce(vec2 a, vec2 b) { return vec2(min(a.x, b.x), max(a.y, b.y)); }

// Level 0's texel of a pixel: (its depth as sslrHiZTexel reads it, its curved extra depth, 0 on
// flat surfaces and without curved solids).
SSLR_FN vec2 sslrHiZLevel0Texel(SslrSurface s, float depth, float extra) {
  return vec2(sslrHiZTexel(s, depth).x, extra);
}
// The (min, max) of a cell from its pyramid texel: a level-0 texel holds one depth.
SSLR_FN vec2 sslrHiZMinMax(int level, vec2 texel) { return level == 0 ? vec2(texel.x, texel.x) : texel; }
// Whether a cell of level >= 1 holds any geometry: its nearest depth is not background. Where it
// does not, classification writes no level-0 texels under it and the traversal skips it whole.
SSLR_FN bool sslrHiZCellHoldsGeometry(SslrSurface s, vec2 minMax) {
  return sslrIsGeometryDepth(s, sslrReversedZ(s) ? max(minMax.x, minMax.y) : min(minMax.x, minMax.y));
}

// The depth key (keySign x depth, larger = farther) of the clear value, which the pyramid stores
// for every pixel that is not geometry (sslrHiZTexel): a cell whose nearest key is this holds no
// geometry. Geometry's keys are all smaller (sslrIsGeometryDepth). It equals the clear value
// itself: 1, or under reversed Z -1 x 0 = 0.
SSLR_FN float sslrHiZBackgroundKey(SslrSurface s) { return sslrClearDepth(s); }

// View distance (or orthographic -z) of a window depth: the tolerance and "how far behind" tests
// of the traversal work in view units, like the adaptive-L tracer's.
SSLR_FN float sslrViewDepthFromDepth(SslrProjection p, float depth) {
  return -sslrViewFromNdc(p, vec2(0.0f), sslrNdcZFromDepth(p, depth)).z;
}

// Whether a ray at window depth rayDepth lies farther than k x the view depth of farDepth plus e
// (view units). Perspective: 1 / distance = n / zOffset with n = sslrNdcZPlusZScale(depth), affine
// in depth (sslrViewFromNdc), so distRay > k distFar + e reads invFar > invRay (k + e invFar),
// here times zOffset^2 > 0: nFar zOffset > nRay (k zOffset + e nFar), without a division. A ray
// at or beyond infinite distance (invRay <= 0) is beyond.
SSLR_FN bool sslrBeyondDepth(SslrProjection p, float rayDepth, float farDepth, float k, float e) {
  if (sslrOrthographic(p)) return sslrViewDepthFromDepth(p, rayDepth) > k * sslrViewDepthFromDepth(p, farDepth) + e;
  float nFar = sslrNdcZPlusZScale(p, farDepth);
  return nFar * p.zOffset > sslrNdcZPlusZScale(p, rayDepth) * (k * p.zOffset + e * nFar);
}

// Window depth of a view depth (-z): sslrViewDepthFromDepth's inverse.
SSLR_FN float sslrDepthFromViewDepth(SslrProjection p, float dist) {
  if (sslrOrthographic(p)) return sslrDepthFromNdcZ(p, p.zOffset - p.zScale * dist);
  float ndcScale = sslrNdcZeroToOne(p) ? 1.0f : 2.0f;
  return (p.zOffset / (ndcScale * dist) + p.infDepthLo) + p.infDepthHi;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_PYRAMID_H
