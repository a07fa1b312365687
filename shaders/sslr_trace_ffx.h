// sslr_trace_ffx.h - comparison method: the mirror-ray intersection of AMD FidelityFX SSSR 1.1.4
// (FFX_SSSR_HierarchicalRaymarch and FFX_SSSR_ValidateHit, ffx_sssr_intersect.h, MIT), written
// here from AMD's published description and source: the industry's reference hierarchical
// tracer, on sslr's G-buffer and pyramid. Shared by the GPU pass and the CPU tests.
//
// The walk: in window space (x, y in pixels, the depth as a key that grows away from the camera),
// start at the most detailed level (0: mirror rays) past the origin pixel's boundary; per step,
// read the cell's nearest depth at the current level; if the ray is in front of it, advance to
// the nearer of the cell's exit boundary and the plane of that depth (when the ray goes deeper);
// an exit through the boundary climbs a level (up to 6), anything else descends one. The walk
// ends when it descends below level 0 or after maxIntersections steps; the position reached is
// the hit candidate. FFX SSSR then accepts it by confidence:
//   - 0 off the screen, within 2 pixels of the origin (both axes), on background, or on a surface
//     whose normal faces along the ray (its back);
//   - else (1 - smoothstep(0, thickness, d))^2, d the view-space distance between the candidate
//     and the surface point under it (level 1's nearest depth at the candidate's 2x2 quad, as FFX
//     reads its mip 1), times a vignette 5% of the screen wide at the borders.
// Deviations, each forced by sslr's pipeline and without effect on a hit: window space in pixels
// instead of uv (the same line; FFX's 0.005 texel boundary offset kept in pixels), level 0 read
// from the depth buffer (sslr's pyramid holds no level-0 texels under a quad of sky), cells past
// a mip's size read as background (FFX's out-of-range loads return 0; its mips are sized
// max(1, size >> level) from the render size, rounded down, so at odd sizes the last row or
// column of a level has no cell above it: sslr's pyramid, padded to cover the screen, holds
// cells there that FFX has not, and they are not read), the direction
// projected from a probe point kept in front of the camera (FFX projects origin + direction,
// which for a ray towards the camera can land behind it), and the levels FFX has above sslr's
// pyramid's top (sslrHiZLevelCount: 5 at 320x180, where FFX walks up to 6) reduced on the fly
// from the top level's cells, as FFX's mips hold them (more fetches, the same answer). FFX's wave-occupancy exit applies to
// glossy rays only (mirror rays never take it) and is left out; its "valid hit" flag
// (steps <= the cap) is always true after its loop, so it is left out too.

#ifndef SSLR_TRACE_FFX_H
#define SSLR_TRACE_FFX_H

#include "sslr_trace.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

#define SSLR_FFX_MAX_LEVEL 6

// FFX's mip `level` size: max(1, size >> level) from the render size (SPD's rounding down).
SSLR_FN vec2 sslrFfxMipSize(SslrSurface s, int level) {
  return max(vec2(1.0f), floor(vec2(s.width, s.height) / float(1 << level)));
}

// The nearest depth key of cell `cell` at `level` (background and cells past the mip's size: the
// farthest key, which nothing lies beyond).
SSLR_FN float sslrFfxNearKey(SslrSurface s, int level, vec2 cell, float keySign, int pyramidTop) {
  float farKey = keySign * sslrClearDepth(s);
  vec2 levelSize = sslrFfxMipSize(s, level);
  if (cell.x < 0.0f || cell.y < 0.0f || cell.x >= levelSize.x || cell.y >= levelSize.y) return farKey;
  if (level == 0) {
    float depth = sslrLoadDepth(ivec2(cell));
    return sslrIsGeometryDepth(s, depth) ? keySign * depth : farKey;
  }
  if (level <= pyramidTop) {
    vec2 minMax = sslrLoadPyramidTexel(level, ivec2(cell));
    return min(keySign * minMax.x, keySign * minMax.y);
  }
  // Above sslr's pyramid: the nearest of the top level's cells inside this one (FFX's mip chain
  // reduces them 2x2 a level; every child of a cell in range is in range, rounding down).
  int n = 1 << (level - pyramidTop);
  vec2 topSize = sslrFfxMipSize(s, pyramidTop);
  float nearest = farKey;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      vec2 child = cell * float(n) + vec2(float(x), float(y));
      if (child.x >= topSize.x || child.y >= topSize.y) continue;
      vec2 minMax = sslrLoadPyramidTexel(pyramidTop, ivec2(child));
      nearest = min(nearest, min(keySign * minMax.x, keySign * minMax.y));
    }
  }
  return nearest;
}

SSLR_FN SslrHit sslrTraceFfx(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP, vec3 vsR) {
  SslrHit hit = sslrNoHit(SSLR_STATUS_MISS);
  vec2 sizePx = vec2(s.width, s.height);
  float keySign = sslrReversedZ(s) ? -1.0f : 1.0f;
  // Origin: the pixel centre at its own depth (FFX's uv and depth sample); direction: along the ray.
  vec3 wP = sslrWindowFromView(p, sizePx, keySign, vsP);
  vec3 d = sslrWindowDirection(p, s, keySign, vsP, vsR, wP);
  vec3 o = vec3(vec2(pxOrigin) + 0.5f, wP.z);
  if (!(max(abs(d.x), abs(d.y)) > 1e-6f)) return hit;
  vec3 invD = vec3(d.x != 0.0f ? 1.0f / d.x : 3.0e38f, d.y != 0.0f ? 1.0f / d.y : 3.0e38f,
                   d.z != 0.0f ? 1.0f / d.z : 3.0e38f);
  vec2 boundary = vec2(d.x < 0.0f ? 0.0f : 1.0f, d.y < 0.0f ? 0.0f : 1.0f);
  vec2 offset = vec2(d.x < 0.0f ? -0.005f : 0.005f, d.y < 0.0f ? -0.005f : 0.005f);
  int topLevel = SSLR_FFX_MAX_LEVEL;

  // Past the origin pixel's boundary first (no self-intersection).
  vec2 planes0 = floor(vec2(o.x, o.y)) + boundary + offset;
  vec2 t0 = (planes0 - vec2(o.x, o.y)) * vec2(invD.x, invD.y);
  float tRay = min(t0.x, t0.y);
  vec3 pos = o + d * tRay;
  int level = 0;
  int i = 0;
  while (i < t.maxTraversalIntersections && level >= 0) {
    float cellSize = float(1 << level);
    vec2 cell = floor(vec2(pos.x, pos.y) / cellSize);
    float surfaceKey = sslrFfxNearKey(s, level, cell, keySign, t.hizLevels);
    vec2 planes = (cell + boundary) * cellSize + offset;
    vec2 tXY = (planes - vec2(o.x, o.y)) * vec2(invD.x, invD.y);
    float tZ = d.z > 0.0f ? (surfaceKey - o.z) * invD.z : 3.0e38f;  // only when going deeper
    float tMin = min(min(tXY.x, tXY.y), tZ);
    bool above = surfaceKey > pos.z;  // the surface is farther than the ray: the ray is in front
    bool skipped = tMin != tZ && above;
    if (above) tRay = tMin;
    pos = o + d * tRay;
    if (!(skipped && level >= topLevel)) level += skipped ? 1 : -1;
    ++i;
  }
  hit.iterations = i;
  hit.hierarchical = 1;

  // FFX_SSSR_ValidateHit.
  if (!(pos.x >= 0.0f && pos.y >= 0.0f && pos.x <= sizePx.x && pos.y <= sizePx.y)) {
    hit.status = SSLR_STATUS_OFF_SCREEN;
    return hit;
  }
  vec2 fromOrigin = abs(vec2(pos.x, pos.y) - (vec2(pxOrigin) + 0.5f));
  if (fromOrigin.x < 2.0f && fromOrigin.y < 2.0f) return hit;
  ivec2 texel = min(ivec2(floor(vec2(pos.x, pos.y))), ivec2(sizePx) - 1);
  // Mip 1 as FFX sizes it: a candidate in the last row or column of an odd-sized screen has no
  // texel there, and FFX's load returns background.
  ivec2 quadCell = texel / 2;
  vec2 mip1 = sslrFfxMipSize(s, 1);
  float farDepth = sslrClearDepth(s);
  vec2 quad = float(quadCell.x) < mip1.x && float(quadCell.y) < mip1.y ? sslrLoadPyramidTexel(1, quadCell)
                                                                       : vec2(farDepth);
  float surfaceDepth = sslrReversedZ(s) ? max(quad.x, quad.y) : min(quad.x, quad.y);
  if (!sslrIsGeometryDepth(s, surfaceDepth)) {
    hit.status = SSLR_STATUS_SKY;
    return hit;
  }
  vec3 vsHitNormal;
  vec3 vsSurface = sslrViewFromUvDepth(p, vec2(pos.x, pos.y) / sizePx, surfaceDepth);
  vec3 vsHit = sslrViewFromUvDepth(p, vec2(pos.x, pos.y) / sizePx, keySign * pos.z);
  if (sslrDecodeNormal(s, sslrLoadNormal(texel), vsHitNormal) && dot(vsHitNormal, vsHit - vsP) > 0.0f) return hit;
  float distance = length(vsSurface - vsHit);
  vec2 uv = vec2(pos.x, pos.y) / sizePx;
  vec2 fov = 0.05f * vec2(sizePx.y / sizePx.x, 1.0f);
  vec2 border = smoothstep(vec2(0.0f), fov, uv) * (vec2(1.0f) - smoothstep(vec2(1.0f) - fov, vec2(1.0f), uv));
  float confidence = 1.0f - smoothstep(0.0f, t.depthBufferThickness, distance);
  confidence *= confidence;
  hit.confidence = border.x * border.y * confidence;
  hit.uvHit = uv;
  hit.L = length(vsHit - vsP);
  hit.status = hit.confidence > 0.0f ? SSLR_STATUS_HIT : SSLR_STATUS_MISS;
  return hit;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_TRACE_FFX_H
