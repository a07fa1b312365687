// shared/thickness.h - Thickness behind the depth buffer: curved solids and the measured back-face depth.
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_THICKNESS_H
#define SSLR_SHARED_THICKNESS_H

#include "language.h"
#include "normals.h"
#include "pyramid.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- Curved solids (hierarchical traversal) ---------------------------------------------------
// A depth buffer has no thickness; the traversal assumes what a pixel shows to be objectDepthRelative x
// its distance deep. A convex curved surface tells more: it is taken to be the surface of a solid
// as curved as it looks, a sphere of its own radius of curvature r, which extends 2 r cos(a)
// behind the pixel along the view ray (a: the view ray's angle to the normal). A mirror sphere of
// radius 1 seen from 8 units is 2 deep at its centre, the default slab 0.6: rays that run into its
// hidden side would be let through to the wall behind.
// Flat faces (a box) keep the slab. Whether the pyramid holds them: sslrCurvedSolids (pyramid.h).
// Classification only lists the quads whose normals turn and a pass of its own computes their
// cells, so that the math costs the listed quads alone. This file is the pyramid's side (the
// pyramid passes, the CPU tracer and the tests include it); the traversal reads the result.

// The radius of curvature between two neighbouring pixels, or 0 where they do not look like one
// convex curved surface. On a sphere P_a - P_b = r (N_a - N_b) exactly; the two differences must
// point the same way (convex, within ~18 deg) and the normals turn as on a curved surface
// (sslrNormalsTurnAsCurved); a step of more than 8 footprints (footprintA: pixel A's) is a depth
// jump (a silhouette), not a surface. Squared forms: every listed quad runs this four times, and
// on a CPU rasterizer each square root and division shows.
SSLR_FN float sslrConvexRadius(SslrSurface s, vec3 vsA, vec3 vsNa, vec3 vsB, vec3 vsNb, float footprintA) {
  vec3 dN = vsNa - vsNb;
  float dn2 = dot(dN, dN);
  vec3 dP = vsA - vsB;
  float along = dot(dP, dN);
  float dp2 = dot(dP, dP);
  bool curved = sslrNormalsTurnAsCurved(s, vsNa, vsNb) && along > 0.0f && along * along > 0.9025f * dp2 * dn2 &&
                dp2 <= 64.0f * footprintA * footprintA;
  return curved ? along / dn2 : 0.0f;
}

// How much deeper than the slab (objectDepthRelative x view depth) a pixel's solid extends, in view
// depth: max(0, min(2 r cos a, 4 x slab) |v.z| - slab), v the unit view direction. The cap keeps a
// gently curved wall from becoming a solid hill. r: the largest radius the pixel shares with a
// neighbour (sslrConvexRadius).
SSLR_FN float sslrCurvedExtraDepth(SslrProjection p, SslrTraceParams t, vec3 vsPos, vec3 vsNormal, float r) {
  vec3 v = sslrOrthographic(p) ? vec3(0.0f, 0.0f, -1.0f) : vsPos * inversesqrt(dot(vsPos, vsPos));
  float slab = t.objectDepthRelative * -vsPos.z;
  float chord = min(2.0f * r * abs(dot(vsNormal, v)), 4.0f * slab) * abs(v.z);
  return max(chord - slab, 0.0f);
}

// Two estimates of one radius that agree within a factor of 2 (0 where either is missing): both
// rows (or both columns) of a quad on a sphere or a cylinder see the same curvature; noise does
// not: per-pixel turns like a normal map's pass one pair's test on some flat pixels, and would
// make those faces deep.
SSLR_FN float sslrAgreedRadius(float a, float b) {
  return a > 0.0f && b > 0.0f && a < 2.0f * b && b < 2.0f * a ? min(a, b) : 0.0f;
}

// The extra depth of each pixel of a 2x2 quad (x, y, z, w: pixels (0,0), (1,0), (0,1), (1,1)),
// from the quad's radius: its two rows' estimates where they agree, or its two columns'
// (sslrAgreedRadius), the larger. ok: the pixel holds geometry with a trusted normal. The curved
// pass computes it once for the pyramid's level 1 and for the traversal's pixels
// (level 0's texels), so a cell's farthest key bounds what its pixels' solids reach.
SSLR_FN vec4 sslrQuadCurvedExtraDepth(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 vs0, vec3 vs1,
                                      vec3 vs2, vec3 vs3, vec3 n0, vec3 n1, vec3 n2, vec3 n3, bvec4 ok) {
  // One footprint per quad, its farthest pixel's (a pixel without geometry has vs = 0).
  float farthest = max(max(-vs0.z, -vs1.z), max(-vs2.z, -vs3.z));
  float footprint = sslrPixelFootprint(p, s.height, sslrOrthographic(p) ? 1.0f : max(farthest, 0.0f));
  float r01 = ok.x && ok.y ? sslrConvexRadius(s, vs0, n0, vs1, n1, footprint) : 0.0f;
  float r23 = ok.z && ok.w ? sslrConvexRadius(s, vs2, n2, vs3, n3, footprint) : 0.0f;
  float r02 = ok.x && ok.z ? sslrConvexRadius(s, vs0, n0, vs2, n2, footprint) : 0.0f;
  float r13 = ok.y && ok.w ? sslrConvexRadius(s, vs1, n1, vs3, n3, footprint) : 0.0f;
  float r = max(sslrAgreedRadius(r01, r23), sslrAgreedRadius(r02, r13));
  return vec4(ok.x ? sslrCurvedExtraDepth(p, t, vs0, n0, r) : 0.0f, ok.y ? sslrCurvedExtraDepth(p, t, vs1, n1, r) : 0.0f,
              ok.z ? sslrCurvedExtraDepth(p, t, vs2, n2, r) : 0.0f, ok.w ? sslrCurvedExtraDepth(p, t, vs3, n3, r) : 0.0f);
}

// ---- Measured thickness: back-face depth (FrameInputs::backDepthTexture) ----------------------
// With a back-face depth (the host's depth pass with front faces culled: per pixel, the nearest
// back face), what a pixel shows is as deep as measured, not objectDepthRelative x its distance: a
// leg thinner than the slab lets rays pass just behind it, a box seen across its diagonal stops
// rays deeper than the slab. The measurement enters where the curved solids' estimate does (it
// replaces it): as the pixel's extra depth over the slab, in level 0 of the pyramid and in the
// far key of level 1 where positive. Negative extra depths thin the slab (down to nothing: the
// traversal then lets a ray just behind a very thin object pass). Whether it is given:
// sslrBackDepth (pyramid.h).

// A pixel's measured extra depth over the slab (view units), or 0 where nothing is measured: no
// back face behind it (a floor, an open mesh, the background), or the back face not behind the
// shown surface (a one-sided face seen from behind is its own back face). front: the view depth
// of `depth` (sslrViewDepthFromDepth).
SSLR_FN float sslrMeasuredExtraDepth(SslrProjection p, SslrSurface s, SslrTraceParams t, float depth, float front,
                                     float backDepth) {
  if (!sslrIsGeometryDepth(s, depth) || !sslrIsGeometryDepth(s, backDepth)) return 0.0f;
  float thickness = sslrViewDepthFromDepth(p, backDepth) - front;
  if (!(thickness > 1e-4f * front)) return 0.0f;
  float extra = thickness - t.objectDepthRelative * front;
  return extra != 0.0f ? extra : 1e-7f * front;  // 0 means "not measured"
}

// A pixel's texel of level 1 when its solid reaches extra deeper than the slab: (min, max) of its
// depth and of the depth of the solid's back (clamped to the depth range). viewDepth: the
// pixel's view depth (-z).
SSLR_FN vec2 sslrHiZSolidTexel(SslrProjection p, SslrSurface s, float depth, float viewDepth, float extra) {
  vec2 texel = sslrHiZTexel(s, depth);
  if (!(extra > 0.0f) || !sslrIsGeometryDepth(s, depth)) return texel;
  float back = clamp(sslrDepthFromViewDepth(p, viewDepth + extra), 0.0f, 1.0f);
  return vec2(min(texel.x, back), max(texel.y, back));
}

// Level 1's cell of a quad whose pixels' solids reach `extra` deeper than the slab (curved or
// measured): the min-max of the four sslrHiZSolidTexel.
SSLR_FN vec2 sslrHiZQuadSolids(SslrProjection p, SslrSurface s, vec4 depths, vec4 viewDepths, vec4 extra) {
  return sslrHiZReduce(sslrHiZReduce(sslrHiZSolidTexel(p, s, depths.x, viewDepths.x, extra.x),
                                     sslrHiZSolidTexel(p, s, depths.y, viewDepths.y, extra.y)),
                       sslrHiZReduce(sslrHiZSolidTexel(p, s, depths.z, viewDepths.z, extra.z),
                                     sslrHiZSolidTexel(p, s, depths.w, viewDepths.w, extra.w)));
}

// Pixel k (0: (0,0), 1: (1,0), 2: (0,1), 3: (1,1)) of level-1 cell `cell`'s 2x2 quad, clamped to
// the screen (`last`: the last pixel): a quad straddling the edge repeats one of its own pixels,
// neutral for the min-max and flat for the curvature.
SSLR_FN ivec2 sslrQuadPixel(ivec2 cell, int k, ivec2 last) {
  return min(cell * 2 + ivec2(k & 1, k >> 1), last);
}

// Level 1 with measured thickness: the (min, max) of the quad's depths and, where a solid reaches
// deeper than the slab, of its back (sslrHiZSolidTexel); `extra` receives the pixels' measured
// extra depths (sslrMeasuredExtraDepth) for level 0.
SSLR_FN vec2 sslrHiZLevel1Measured(SslrProjection p, SslrSurface s, SslrTraceParams t, vec4 depths, vec4 backDepths,
                                   SSLR_OUT(vec4) extra) {
  vec4 front = vec4(sslrViewDepthFromDepth(p, depths.x), sslrViewDepthFromDepth(p, depths.y),
                    sslrViewDepthFromDepth(p, depths.z), sslrViewDepthFromDepth(p, depths.w));
  extra = vec4(sslrMeasuredExtraDepth(p, s, t, depths.x, front.x, backDepths.x),
               sslrMeasuredExtraDepth(p, s, t, depths.y, front.y, backDepths.y),
               sslrMeasuredExtraDepth(p, s, t, depths.z, front.z, backDepths.z),
               sslrMeasuredExtraDepth(p, s, t, depths.w, front.w, backDepths.w));
  return sslrHiZQuadSolids(p, s, depths, front, extra);
}

// Level 1 of the pyramid without solids: the (min, max) of a quad's four depths.
SSLR_FN vec2 sslrHiZLevel1Plain(SslrSurface s, vec4 depths) {
  return sslrHiZReduce(sslrHiZReduce(sslrHiZTexel(s, depths.x), sslrHiZTexel(s, depths.y)),
                       sslrHiZReduce(sslrHiZTexel(s, depths.z), sslrHiZTexel(s, depths.w)));
}

// Whether a quad's normals turn at all (packed texels compared): only such quads can hold a curved
// solid (sslrConvexRadius needs a turn), so classification lists them for the curved pass and
// gives the others the plain cell, which is what sslrHiZLevel1Cell computes for them.
SSLR_FN bool sslrQuadNormalsTurn(vec4 n0, vec4 n1, vec4 n2, vec4 n3) {
  return n0 != n1 || n0 != n2 || n0 != n3;
}

// Level 1 of the pyramid, one cell from its 2x2 quad (pixel coordinates clamped to the screen,
// their depth and packed normal texels): the curved pass on the GPU, the CPU tracer's pyramid and
// the tests all build it here. With curved solids, `extra` receives the quad's pixels' extra
// depths (sslrQuadCurvedExtraDepth), which the curved pass stores in level 0 for the traversal's
// pixels (the quad's math inside the traversal's loop cost every step on llvmpipe).
SSLR_FN vec2 sslrHiZLevel1Cell(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 p0, ivec2 p1, ivec2 p2,
                               ivec2 p3, vec4 depths, vec4 n0, vec4 n1, vec4 n2, vec4 n3, SSLR_OUT(vec4) extra) {
  extra = vec4(0.0f);
  if (!sslrCurvedSolids(t)) return sslrHiZLevel1Plain(s, depths);
  vec3 vs0, vs1, vs2, vs3, m0, m1, m2, m3;
  bool ok0 = sslrSurfaceFromDepth(p, s, p0, depths.x, vs0);
  ok0 = sslrDecodeNormal(s, n0, m0) && ok0;
  bool ok1 = sslrSurfaceFromDepth(p, s, p1, depths.y, vs1);
  ok1 = sslrDecodeNormal(s, n1, m1) && ok1;
  bool ok2 = sslrSurfaceFromDepth(p, s, p2, depths.z, vs2);
  ok2 = sslrDecodeNormal(s, n2, m2) && ok2;
  bool ok3 = sslrSurfaceFromDepth(p, s, p3, depths.w, vs3);
  ok3 = sslrDecodeNormal(s, n3, m3) && ok3;
  extra = sslrQuadCurvedExtraDepth(p, s, t, vs0, vs1, vs2, vs3, m0, m1, m2, m3, bvec4(ok0, ok1, ok2, ok3));
  return sslrHiZQuadSolids(p, s, depths, vec4(-vs0.z, -vs1.z, -vs2.z, -vs3.z), extra);
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_THICKNESS_H
