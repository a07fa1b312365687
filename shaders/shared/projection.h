// shared/projection.h - Projection and depth: view position from depth, window and clip space.
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_PROJECTION_H
#define SSLR_SHARED_PROJECTION_H

#include "language.h"
#include "frame.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- The projection's kind and the depth convention -------------------------------------------
// Compiled in (0 or 1) where the program knows them (Context::Impl::buildPrograms, when every view
// agrees), as the normal encoding is: every projection and depth conversion branches on them, and
// a CPU rasterizer runs both arms of a branch on a uniform. -1: read from the block (C++ always).
#ifndef SSLR_ORTHOGRAPHIC
#define SSLR_ORTHOGRAPHIC -1
#define SSLR_NDC_ZERO_TO_ONE -1
#define SSLR_REVERSED_Z -1
#endif
SSLR_FN bool sslrOrthographic(SslrProjection p) {
  return SSLR_ORTHOGRAPHIC >= 0 ? SSLR_ORTHOGRAPHIC != 0 : p.orthographic != 0;
}
SSLR_FN bool sslrNdcZeroToOne(SslrProjection p) {
  return SSLR_NDC_ZERO_TO_ONE >= 0 ? SSLR_NDC_ZERO_TO_ONE != 0 : p.ndcZeroToOne != 0;
}
SSLR_FN bool sslrReversedZ(SslrSurface s) {
  return SSLR_REVERSED_Z >= 0 ? SSLR_REVERSED_Z != 0 : s.reversedZ != 0;
}

// ---- Pure math ----------------------------------------------------------------------------

SSLR_FN float sslrSaturate(float x) { return clamp(x, 0.0f, 1.0f); }

// Window depth -> ndc z, and back.
SSLR_FN float sslrNdcZFromDepth(SslrProjection p, float depth) {
  return sslrNdcZeroToOne(p) ? depth : depth * 2.0f - 1.0f;
}
SSLR_FN float sslrDepthFromNdcZ(SslrProjection p, float ndcZ) {
  return sslrNdcZeroToOne(p) ? ndcZ : ndcZ * 0.5f + 0.5f;
}

// The clear value: the farthest depth of the convention, what background holds.
SSLR_FN float sslrClearDepth(SslrSurface s) { return sslrReversedZ(s) ? 0.0f : 1.0f; }

// A depth sample that holds geometry: finite, inside [0,1] and not the clear value. NaN fails
// every comparison and so counts as background (poisoned input never reaches the tracer).
SSLR_FN bool sslrIsGeometryDepth(SslrSurface s, float depth) {
  bool inRange = depth >= 0.0f && depth <= 1.0f;
  return inRange && (sslrReversedZ(s) ? depth > 0.0f : depth < 1.0f);
}

SSLR_FN vec2 sslrNdcFromUv(vec2 uv) { return uv * 2.0f - 1.0f; }
SSLR_FN vec2 sslrUvFromNdc(vec2 ndc) { return ndc * 0.5f + 0.5f; }
// Whether uv lies on the screen (borders included); false for NaN.
SSLR_FN bool sslrInsideUv(vec2 uv) { return uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f; }
SSLR_FN vec2 sslrUvFromPixel(ivec2 px, vec2 sizePx) { return (vec2(px) + 0.5f) / sizePx; }
SSLR_FN ivec2 sslrPixelFromUv(vec2 uv, vec2 sizePx) {
  return clamp(ivec2(floor(uv * sizePx)), ivec2(0), ivec2(sizePx) - 1);
}

// Perspective: ndcZ + zScale of a window depth, as ndcScale * (depth - d_inf) (see
// SslrProjection::infDepthHi); it equals zOffset / dist, dist the view distance along -z.
SSLR_FN float sslrNdcZPlusZScale(SslrProjection p, float depth) {
  float ndcScale = sslrNdcZeroToOne(p) ? 1.0f : 2.0f;
  return ndcScale * ((depth - p.infDepthHi) - p.infDepthLo);
}

// View-space position from ndc, exact for both projection kinds (see SslrProjection).
// Perspective: dist = zOffset / (ndcZ + zScale) is the view distance along -z; x and y follow.
SSLR_FN vec3 sslrViewFromNdc(SslrProjection p, vec2 ndcXY, float ndcZ) {
  if (sslrOrthographic(p)) {
    return vec3((ndcXY.x - p.xOffset) / p.xScale, (ndcXY.y - p.yOffset) / p.yScale,
                (ndcZ - p.zOffset) / p.zScale);
  }
  float dist = p.zOffset / sslrNdcZPlusZScale(p, sslrDepthFromNdcZ(p, ndcZ));
  return vec3(dist * (ndcXY.x + p.xOffset) / p.xScale, dist * (ndcXY.y + p.yOffset) / p.yScale,
              -dist);
}

SSLR_FN vec3 sslrViewFromUvDepth(SslrProjection p, vec2 uv, float depth) {
  return sslrViewFromNdc(p, sslrNdcFromUv(uv), sslrNdcZFromDepth(p, depth));
}

// The surface a depth texel shows, as the tracer's sslrLoadSurface wants it: false for the
// background (clear value, NaN, out of range), else the view position at the pixel centre.
SSLR_FN bool sslrSurfaceFromDepth(SslrProjection p, SslrSurface s, ivec2 px, float depth,
                                  SSLR_OUT(vec3) vsPos) {
  if (!sslrIsGeometryDepth(s, depth)) {
    vsPos = vec3(0.0f);
    return false;
  }
  vsPos = sslrViewFromUvDepth(p, sslrUvFromPixel(px, vec2(s.width, s.height)), depth);
  return true;
}

// Clip w of a view-space point: the view distance (perspective) or 1 (orthographic).
SSLR_FN float sslrClipW(SslrProjection p, vec3 vsPos) {
  return sslrOrthographic(p) ? 1.0f : -vsPos.z;
}

// View space -> ndc (x, y, z). The caller must have checked sslrClipW > 0.
SSLR_FN vec3 sslrNdcFromView(SslrProjection p, vec3 vsPos) {
  if (sslrOrthographic(p)) {
    return vec3(p.xScale * vsPos.x + p.xOffset, p.yScale * vsPos.y + p.yOffset,
                p.zScale * vsPos.z + p.zOffset);
  }
  float w = -vsPos.z;
  return vec3((p.xScale * vsPos.x + p.xOffset * vsPos.z) / w,
              (p.yScale * vsPos.y + p.yOffset * vsPos.z) / w,
              (p.zScale * vsPos.z + p.zOffset) / w);
}

// Unit direction from the camera towards a view-space point (orthographic: constant -z).
SSLR_FN vec3 sslrViewDirection(SslrProjection p, vec3 vsPos) {
  return sslrOrthographic(p) ? vec3(0.0f, 0.0f, -1.0f) : normalize(vsPos);
}

// Distance used for pixel footprints and relative tolerances.
SSLR_FN float sslrViewDistance(SslrProjection p, vec3 vsPos) {
  return sslrOrthographic(p) ? 1.0f : max(-vsPos.z, 0.0f);
}

// Size (view units) of one pixel at a given view distance.
SSLR_FN float sslrPixelFootprint(SslrProjection p, float heightPx, float dist) {
  return 2.0f * dist / (abs(p.yScale) * heightPx);
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_PROJECTION_H
