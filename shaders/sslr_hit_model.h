// sslr_hit_model.h - the hit model: what a ray that reached a pixel it neither passes in front of
// nor far behind has met there. Shared by the GPU pass and the CPU tests.
//
// The hierarchical traversal (sslr_trace_hiz.h) only walks: it finds the pixels where the ray's
// segment goes behind what the depth buffer shows (SslrCrossing) and leaves the decision here.
// A depth buffer holds one sample per pixel and no thickness, so the model takes each pixel to show
// a small oriented piece of surface (its depth, its normal: the tangent plane) with a solid behind
// it, and decides from what the pyramid and the G-buffer hold:
//   - a hit where the ray meets the pixel's tangent plane inside the pixel (sslrPlaneHit,
//     sslr_trace.h, shared with adaptive L), or across a contact line to a touching surface;
//   - else, by how deep behind the surface the ray goes, compared with the solid behind it: the
//     slab, objectDepthRelative x distance (thinner near the object's outline: sslrSlabNearOutline;
//     deeper behind a convex curved surface, or as measured by a back-face depth: level 0's extra
//     depth, shared/thickness.h): within the hit tolerance it goes on (pixel snapping), inside the
//     solid the walk ends, deeper it passes behind (sslrJudgePixel);
//   - a ray that ended inside a solid met, in this order: the surface where it went in, as the
//     shape given to the sample there reaches it (sslrEntryHit: a curved surface between two
//     samples, the side of a face narrower than a pixel, a curved surface's rim), a thin object's
//     hidden side (sslrMetThinObject: a thin object is about as deep as it is wide); else it is
//     hidden (measured) or a guess (sslrJudgeInside);
//   - a ray that ends without a hit where it went out of sight takes the colour there at the
//     guesses' confidence (sslrHiddenGuess, sslrSlabGuess).
//
// Besides the loaders of sslr_trace.h, the includer defines sslrLoadPyramidTexel (sslr_trace_hiz.h).
#ifndef SSLR_HIT_MODEL_H
#define SSLR_HIT_MODEL_H

#include "sslr_trace.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- Thickness: how deep what a pixel shows is taken to be ------------------------------------

// Whether a ray whose segment in a cell lies segNear deep, beyond the cell's farthest key keyFar,
// passes behind everything the cell shows: deeper than any tolerance and than the objects'
// assumed thickness, distRay - distFar > max(tolerance, slab) (+ extra: sslrJudgePixel's solid).
// The tolerance's slope term is unknown before a pixel is looked at: the largest one, tan = 16, is
// assumed. Both bounds are affine in distFar (sslrHitTolerance), which keeps the step free of
// divisions that depend on the ray (sslrBeyondDepth).
SSLR_FN bool sslrPassesBehindCell(SslrProjection p, SslrSurface s, SslrTraceParams t, float keySign, float segNear,
                                  float keyFar, float extra) {
  // A far key of background (the clear value, the end of the key range) has no ray behind it:
  // the walk's rays stay inside the range.
  if (!(segNear > keyFar)) return false;
  float farDepth = keySign * keyFar;
  // The tolerance is affine in the distance: its value at 0 and its growth per unit.
  float tolFixed = sslrHitTolerance(p, s, 0.0f, 16.0f);
  float tolPerDist = sslrHitTolerance(p, s, 1.0f, 16.0f) - tolFixed;
  float rayDepth = keySign * segNear;
  // Perspective without a measured solid: both bounds are k x distFar + extra (the tolerance is
  // 0 at distance 0), and the larger k decides alone.
  if (!sslrOrthographic(p) && !sslrBackDepth(s))
    return sslrBeyondDepth(p, rayDepth, farDepth, 1.0f + max(tolPerDist, t.objectDepthRelative), extra);
  float tolExtra = sslrBackDepth(s) ? 0.0f : extra;  // a measured extra is the solid's; a curved one adds
  return sslrBeyondDepth(p, rayDepth, farDepth, 1.0f + tolPerDist, tolFixed + tolExtra) &&
         sslrBeyondDepth(p, rayDepth, farDepth, 1.0f + t.objectDepthRelative, extra);
}

// How deep may what pixel px shows extend behind it, where a ray rayDepthKey deep (window key) passes?
// At most `slab` (objectDepthRelative x distance); less near the outline of what the pixel shows:
// there the object has had no room to get deep. An object is taken to be no deeper, at a distance
// d from its outline, than a right-angled corner of the face the pixel shows would make it:
// d (cot a + tan a), a the face's angle to the view ray (a box's edge; a face seen edge-on, like a
// sphere's rim, allows any depth). d is bounded by the smallest pyramid cell around the pixel that
// holds a surface beyond the ray (seen past the object: its outline lies inside that cell). Only
// rays the slab would stop pay for this (up to a few fetches).
SSLR_FN float sslrSlabNearOutline(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 px, vec3 vsSurface,
                                  vec3 vsSurfaceNormal, float rayDepthKey, float keySign, float slab) {
  float sinA = clamp(abs(dot(vsSurfaceNormal, sslrViewDirection(p, vsSurface))), 0.02f, 0.9998f);
  float dist = sslrOrthographic(p) ? 1.0f : -vsSurface.z;
  float depthPerPx = sslrPixelFootprint(p, s.height, dist) / (sinA * sqrt(1.0f - sinA * sinA));
  for (int level = 1; level <= t.hizLevels; ++level) {
    // The outline lies within 1.5 cells of the pixel (the cell is aligned, the pixel anywhere in it).
    float bound = 1.5f * float(1 << level) * depthPerPx;
    if (bound >= slab) break;  // coarser cells bound it no tighter
    vec2 minMax = sslrLoadPyramidTexel(level, ivec2(px.x >> level, px.y >> level));
    if (max(keySign * minMax.x, keySign * minMax.y) > rayDepthKey) return bound;
  }
  return slab;
}

// ---- After the walk: what a ray inside a solid met ------------------------------------------------

// Where the view ray through window point w (pixels) meets the plane (vsOnPlane, vsN). Any depth
// gives a point of that ray (the camera's, orthographic or not); the plane fixes the rest.
SSLR_FN vec3 sslrPlaneAtWindow(SslrProjection p, SslrSurface s, vec2 w, vec3 vsOnPlane, vec3 vsN) {
  vec3 a = sslrViewFromUvDepth(p, w / vec2(s.width, s.height), 0.5f);
  vec3 dir = sslrViewDirection(p, a);
  float dn = dot(dir, vsN);
  return a + dir * (abs(dn) > 1e-6f ? dot(vsOnPlane - a, vsN) / dn : 0.0f);
}

// How many pixels the face that pixel px shows reaches along `axis`, each way (offsets 1, 2, 4, 8
// and 16: it stops at the first that leaves the face), plus px itself; once that exceeds
// maxWidth the face is not thin and the count stops. A pixel is on the face while its
// depth lies within the tolerance, plus half its distance (a curved face may bend away), of px's
// tangent plane.
SSLR_FN float sslrFaceWidthPx(SslrProjection p, SslrSurface s, ivec2 px, ivec2 axis, vec3 vsSurface, vec3 vsN,
                              float tolerance, float footprint, float maxWidth) {
  float width = 1.0f;
  for (int way = -1; way <= 1; way += 2) {
    int reach = 0;
    for (int offset = 1; offset <= SSLR_THIN_MAX_WIDTH_PX; offset *= 2) {
      ivec2 q = px + axis * (way * offset);
      vec3 vsQ;
      if (q.x < 0 || q.y < 0 || q.x >= s.width || q.y >= s.height || !sslrLoadSurface(q, vsQ)) break;
      vec3 vsOnPlane = sslrPlaneAtWindow(p, s, vec2(q) + 0.5f, vsSurface, vsN);
      if (!(abs(vsQ.z - vsOnPlane.z) <= tolerance + 0.5f * float(offset) * footprint)) break;
      reach = offset;
    }
    width += float(reach);
    if (width > maxWidth) break;
  }
  return width;
}

// sslrMetThinObject's first test, without a fetch: the walk keeps only rays that pass it.
// `footprint`: the pixel footprint at the surface the ray went behind.
SSLR_FN bool sslrThinEntryShallow(float footprint, float entryBehind) {
  return entryBehind < SSLR_THIN_MAX_DEPTH_FOOTPRINTS * footprint;
}

// Thin objects (traversal first): whether a ray that went `entryBehind` (view units) into the
// assumed slab of what pixel px shows met that object's hidden side rather than passing behind it.
// Without a thickness the depth buffer cannot tell; the prior is that a thin object (a bar, a rail,
// a leg: at most 16 px and a 30th of the screen height across, its narrower extent around px) is
// about as deep as it is wide, so a ray less deep behind it than its width (and than
// SSLR_THIN_MAX_DEPTH_FOOTPRINTS pixel footprints) met it. Wider objects keep the slab's answers:
// there a ray this close behind the outline mostly passes a corner (results/composite.md, "0.9.2").
SSLR_FN bool sslrMetThinObject(SslrProjection p, SslrSurface s, ivec2 px, vec3 vsSurface, vec3 vsN, float tolerance,
                               float entryBehind) {
  float footprint = sslrPixelFootprint(p, s.height, sslrClipW(p, vsSurface));
  if (!sslrThinEntryShallow(footprint, entryBehind)) return false;
  float maxWidth = min(float(SSLR_THIN_MAX_WIDTH_PX), SSLR_THIN_MAX_WIDTH_SCREEN * float(s.height));
  float width = min(sslrFaceWidthPx(p, s, px, ivec2(1, 0), vsSurface, vsN, tolerance, footprint, maxWidth),
                    sslrFaceWidthPx(p, s, px, ivec2(0, 1), vsSurface, vsN, tolerance, footprint, maxWidth));
  return width <= maxWidth && entryBehind < SSLR_THIN_DEPTH_PER_WIDTH * width * footprint;
}

// The side of the face pixel px shows, where a ray crossed its outline into px from npx (window
// point wEntry, just past the boundary): a face the depth buffer
// holds no sample of where it is narrower than a pixel (a box's top seen from just above it, a
// pillar's side seen nearly along it). The side is taken to meet the shown face (vsSurface, vsN)
// at a right angle along the outline (the corner outline thinning assumes). It is a hit when the
// side faces the camera, the ray meets it from outside no deeper than `slab` behind the edge, and
// the hit projects between the outline and npx's centre (had the side reached that centre, npx
// would show it). A side within ~6 degrees of edge-on (cos <= 0.1) is not trusted: rays from many
// pixels converge on such a sliver, and most of them would be wrong (docs/design-notes.md).
SSLR_FN bool sslrCornerHit(SslrProjection p, SslrSurface s, vec3 wEntry, vec3 vsP, vec3 vsR, ivec2 px, ivec2 npx,
                           vec3 vsSurface, vec3 vsN, float slab, SSLR_OUT(float) L) {
  L = 0.0f;
  // Crossed in along x where it moved between columns (a crossing through a corner: along x).
  ivec2 outward = npx.x != px.x ? ivec2(npx.x - px.x, 0) : ivec2(0, npx.y - px.y);
  bool acrossX = outward.x != 0;
  // The outline on the shown face's plane, and the side's outward normal.
  vec2 wEdge = acrossX ? vec2(float(px.x) + (outward.x > 0 ? 1.0f : 0.0f), wEntry.y)
                       : vec2(wEntry.x, float(px.y) + (outward.y > 0 ? 1.0f : 0.0f));
  vec2 along = acrossX ? vec2(0.0f, 1.0f) : vec2(1.0f, 0.0f);
  vec3 vsEdge = sslrPlaneAtWindow(p, s, wEdge, vsSurface, vsN);
  vec3 vsEdge1 = sslrPlaneAtWindow(p, s, wEdge + along, vsSurface, vsN);
  vec3 vsOut = sslrPlaneAtWindow(p, s, wEdge + 0.5f * vec2(outward), vsSurface, vsN);
  vec3 side = cross(vsEdge1 - vsEdge, vsN);
  if (!(dot(side, side) > 0.0f)) return false;
  side = normalize(side);
  if (dot(side, vsOut - vsEdge) < 0.0f) side = -side;
  if (!(dot(side, -sslrViewDirection(p, vsEdge)) > 0.1f)) return false;  // hidden, or nearly edge-on
  float denom = dot(vsR, side);
  if (!(denom < 0.0f)) return false;  // the ray does not come at the side from outside
  L = dot(vsEdge - vsP, side) / denom;
  vec3 vsQ = vsP + vsR * L;
  float depthBehind = dot(vsEdge - vsQ, vsN);
  if (!(L > 0.0f) || !(depthBehind >= 0.0f) || depthBehind > slab || sslrClipW(p, vsQ) <= 0.0f) return false;
  float keySign = sslrReversedZ(s) ? -1.0f : 1.0f;
  vec3 wQ = sslrWindowFromView(p, vec2(s.width, s.height), keySign, vsQ);
  float outside = acrossX ? (wQ.x - wEdge.x) * float(outward.x) : (wQ.y - wEdge.y) * float(outward.y);
  return outside >= -0.05f && outside <= 0.5f;
}

// A curved surface near its outline, where the radius estimate gives no extra depth: a ray that
// crossed into px from npx (wEntry, d as above) behind px's sample (keyIn: its depth key, distIn:
// its view depth) met the surface there
// - across a crease: npx is the same surface with its sample beyond the ray (`crease`: the crossing
//   lies between the two samples, where neither pixel's tangent plane holds it);
// - at the rim: it came from beyond the outline and is behind the rim's sample by less than the
//   surface recedes from the pixel inwards (on the screen: sslrEntryHit checked it) to the rim (the
//   part that turns away within the pixel). A rim hit is reported halfway to where the ray leaves
//   the rim pixel: its colour, not a blend with what lies beyond the outline.
SSLR_FN bool sslrRimHit(SslrProjection p, SslrSurface s, vec3 wEntry, vec3 d, vec3 vsP, vec3 vsR, ivec2 px,
                        ivec2 npx, float keyIn, float distIn, bool crease, SSLR_OUT(float) L) {
  L = 0.0f;
  float keySign = sslrReversedZ(s) ? -1.0f : 1.0f;
  float tIn = 0.0f;
  if (!crease) {  // the rim: the pixel inwards is the same surface, nearer by more than the ray is behind
    float keyInward = keySign * sslrLoadDepth(px + (px - npx));
    if (!sslrIsGeometryDepth(s, keySign * keyInward) || !(keyInward < keyIn) ||
        !(abs(sslrViewDepthFromDepth(p, keySign * keyInward) - distIn) <= sslrHitTolerance(p, s, distIn, 16.0f)) ||
        !(wEntry.z - keyIn <= keyIn - keyInward))
      return false;
    vec2 stepOut = vec2(d.x >= 0.0f ? 1.0f : 0.0f, d.y >= 0.0f ? 1.0f : 0.0f);
    vec2 tOut = (vec2(px) + stepOut - vec2(wEntry.x, wEntry.y)) /
                vec2(abs(d.x) > 1e-12f ? d.x : 1e-12f, abs(d.y) > 1e-12f ? d.y : 1e-12f);
    tIn = clamp(0.5f * min(tOut.x, tOut.y), 0.0f, 0.5f);
  }
  L = sslrRayLengthAt(p, vec2(s.width, s.height), keySign, wEntry, d, tIn, vsP, vsR);
  return L > 0.0f;
}

// What a ray that ended inside a solid met where it went in: window point wEntry, where the run of
// pixels it has been behind began (just past the boundary it crossed into pixel px, unless the walk
// moved it on inside px), d its window-space direction. A hit (at length L) where the shape the
// model gives px's sample reaches the ray there:
// - px has extra depth (level 0: a curved surface's, or a measured solid thicker than the slab):
//   a faceted mesh with interpolated normals holds flat facets in depth while its shading normals
//   tilt away from them, so the pixel tests' tangent planes refuse its crossings.
//   - Crossed in from npx, whose sample of the same surface (within the steepest slope's hit
//     tolerance; an outline steps further) lies beyond the ray: it crossed the surface between the
//     two samples, at the boundary (a crease between facets, seen at an angle).
//   - Moved on inside px: where it lies on px's surface within the hit tolerance (adaptive L's test).
// - Else, crossed in from npx showing something beyond the ray there, or nothing (an outline, or a
//   crease), by the shape of px's surface: curved where px's shading normal and the next sample's
//   turn as on one curved surface (sslrNormalsTurnAsCurved), not as on a flat face (one normal) or
//   at an edge between two faces: its crease or rim (sslrRimHit); flat: the side of a face
//   narrower than a pixel (sslrCornerHit), as deep as the slab behind px (with a back-face depth:
//   plus the measured difference).
SSLR_FN bool sslrEntryHit(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 wEntry, vec3 d, vec3 vsP,
                          vec3 vsR, SSLR_OUT(float) L) {
  L = 0.0f;
  ivec2 px = ivec2(floor(vec2(wEntry.x, wEntry.y)));
  float keySign = sslrReversedZ(s) ? -1.0f : 1.0f;
  vec3 vsSurface, vsN;
  if (!sslrLoadSurface(px, vsSurface) || !sslrDecodeNormal(s, sslrLoadNormal(px), vsN)) return false;
  float keyIn = keySign * sslrLoadDepth(px);
  float distIn = sslrViewDepthFromDepth(p, keySign * keyIn);  // from the depth buffer, as npx's
  float extra = sslrLoadPyramidTexel(0, px).y;
  // The pixel the ray came from: just before the boundary it crossed (2 nudges back along the
  // major axis; a corner's other boundary, crossed earlier, stays crossed).
  ivec2 npx = ivec2(floor(vec2(wEntry.x, wEntry.y) - vec2(d.x, d.y) * (2.0f * SSLR_HIZ_NUDGE)));
  bool crossedIn = (npx.x != px.x || npx.y != px.y) && wEntry.z > keyIn && npx.x >= 0 && npx.y >= 0 &&
                   npx.x < s.width && npx.y < s.height;
  bool sameSurface = false;
  if (crossedIn) {
    float depthOut = sslrLoadDepth(npx);
    bool outGeometry = sslrIsGeometryDepth(s, depthOut);
    if (outGeometry && !(wEntry.z <= keySign * depthOut)) return false;  // npx is nearer: no outline
    sameSurface =
        outGeometry && abs(sslrViewDepthFromDepth(p, depthOut) - distIn) <= sslrHitTolerance(p, s, distIn, 16.0f);
  }
  if (extra > 0.0f || !crossedIn) {  // px's own surface where the ray reached it
    L = sslrRayLengthAt(p, vec2(s.width, s.height), keySign, wEntry, d, 0.0f, vsP, vsR);
    if (!(extra > 0.0f && L > 0.0f)) return false;
    return crossedIn ? sameSurface : length(vsP + vsR * L - vsSurface) <= sslrHitTolerance(p, s, distIn, 0.0f);
  }
  float slab = max(t.objectDepthRelative * distIn + (sslrBackDepth(s) ? extra : 0.0f), 0.0f);
  // The next sample of px's surface: npx across a crease, else the pixel inwards.
  ivec2 other = sameSurface ? npx : px + (px - npx);
  vec3 nOther;
  bool curvedShape = min(other.x, other.y) >= 0 && other.x < s.width && other.y < s.height &&
                     sslrDecodeNormal(s, sslrLoadNormal(other), nOther) && sslrNormalsTurnAsCurved(s, vsN, nOther);
  return curvedShape ? sslrRimHit(p, s, wEntry, d, vsP, vsR, px, npx, keyIn, distIn, sameSurface, L)
                     : sslrCornerHit(p, s, wEntry, vsP, vsR, px, npx, vsSurface, vsN, slab, L);
}

// ---- The verdict at a pixel -------------------------------------------------------------------

// What the walk hands the model at a pixel (level 0) it neither passes in front of nor far
// behind: the pixel and its window depth (level 0's .x, the depth buffer's value: the walk has
// read it), the ray's nearest and farthest depth keys in it (window depth x keySign, -1 for
// reversed Z), the pixel's extra depth (level 0's .y: curved or measured; 0: none) and whether
// the ray was out of sight (behind what the screen shows) when it got there.
struct SslrCrossing {
  ivec2 px;
  float depth, segNear, segFar, keySign, extra;
  bool hidden;
};

// What the ray met at the pixel.
#define SSLR_VERDICT_NONE 0      // nothing to judge (the background; the reflecting pixel behind)
#define SSLR_VERDICT_IN_FRONT 1  // the ray is in front of what the pixel shows
#define SSLR_VERDICT_NEAR 2      // behind it by no more than the hit tolerance (pixel snapping)
#define SSLR_VERDICT_HIT 3       // a hit at L, with confidence `valid`
#define SSLR_VERDICT_INSIDE 4    // inside the solid behind it: the walk ends (sslrJudgeInside)
#define SSLR_VERDICT_BEHIND 5    // deeper than the solid: it passes behind what the pixel shows

struct SslrVerdict {
  int kind;               // SSLR_VERDICT_*
  float L, valid;         // HIT: the ray's length and the validation (sslrPlaneHit)
  bool measured;          // INSIDE: a measured solid (back-face depth): the ray is known hidden
  bool thinCandidate;     // INSIDE: it may have met a thin object's hidden side (sslrMetThinObject)
  float behind;           // INSIDE: how deep behind the surface its segment in the pixel begins
  float tolerance;        // INSIDE: the hit tolerance there
};

// A verdict that says nothing (SSLR_VERDICT_NONE), every field set.
SSLR_FN SslrVerdict sslrNoVerdict() {
  SslrVerdict v;
  v.kind = SSLR_VERDICT_NONE;
  v.L = 0.0f;
  v.valid = 0.0f;
  v.measured = false;
  v.thinCandidate = false;
  v.behind = 0.0f;
  v.tolerance = 0.0f;
  return v;
}

// The model's verdict on crossing c (pxOrigin: the reflecting pixel).
SSLR_FN SslrVerdict sslrJudgePixel(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                   vec3 vsR, SslrCrossing c) {
  SslrVerdict v = sslrNoVerdict();
  vec3 vsSurface;
  // Background: only a ray at the far plane gets here.
  if (!sslrSurfaceFromDepth(p, s, c.px, c.depth, vsSurface)) return v;
  vec3 vsSurfaceNormal;
  bool normalOk = sslrDecodeNormal(s, sslrLoadNormal(c.px), vsSurfaceNormal);
  bool ownPixel = c.px.x == pxOrigin.x && c.px.y == pxOrigin.y;
  // The hit: where the ray meets the pixel's tangent plane (sslrPlaneHit).
  float L = 0.0f;
  float valid = normalOk && !ownPixel ? sslrPlaneHit(p, s, pxOrigin, vsP, vsR, c.px, vsSurface, vsSurfaceNormal, L)
                                      : 0.0f;
  if (valid >= 0.5f) {
    v.kind = SSLR_VERDICT_HIT;
    v.L = L;
    v.valid = valid;
    return v;
  }
  // No hit here. How deep behind the pixel's surface does the ray get inside the pixel?
  float distSurface = -vsSurface.z;  // view depth, as sslrViewDepthFromDepth measures it
  float behind = sslrViewDepthFromDepth(p, c.keySign * c.segFar) - distSurface;
  if (!(behind > 0.0f)) {
    v.kind = SSLR_VERDICT_IN_FRONT;
    return v;
  }
  if (ownPixel) return v;
  float tolerance =
      sslrHitTolerance(p, s, distSurface, normalOk ? sslrSlopeTan(p, vsSurface, vsSurfaceNormal) : 16.0f);
  // What the pixel shows is taken to fill [surface, surface + slab] along the view: the slab is
  // objectDepthRelative x distance. A ray inside it (deeper than the hit tolerance: pixel
  // snapping) ran into the hidden part of the object, from the front or from behind: nothing on
  // screen is its reflection. Deeper than the slab it passes behind; within the tolerance it goes
  // on. A curved surface's solid reaches deeper (its extra depth); a flat face's gets thinner near
  // its outline (the outline rule reads the pyramid's far keys, which on curved surfaces hold
  // their backs). A measured solid (back-face depth) holds the ray when any part of its segment in
  // the pixel lies inside [surface + tolerance, back]: a ray running along the view direction
  // crosses a box's depth within one pixel, its far end already behind the back.
  float slab = t.objectDepthRelative * distSurface;
  bool measured = sslrBackDepth(s) && c.extra != 0.0f;
  float behindNear = measured ? sslrViewDepthFromDepth(p, c.keySign * c.segNear) - distSurface : behind;
  if (measured) slab = max(slab + c.extra, 0.0f);
  else if (c.extra > 0.0f) slab += c.extra;
  else if (normalOk && behind > tolerance && behind < slab)
    slab = sslrSlabNearOutline(p, s, t, c.px, vsSurface, vsSurfaceNormal, c.segFar, c.keySign, slab);
  // A measured solid thinner than twice the tolerance (a face seen at a grazing angle has a wide
  // one) holds the ray once it is half the solid deep: the measurement says it is inside.
  float into = measured ? min(tolerance, 0.5f * slab) : tolerance;
  if (behind > into && behindNear < slab) {
    v.kind = SSLR_VERDICT_INSIDE;
    v.measured = measured;
    v.behind = max(behindNear, 0.0f);
    v.tolerance = tolerance;
    // A thin object's hidden side, tested after the walk (outside its loop): not where the ray was
    // already out of sight (the hidden guess's), nor behind a curved or measured solid (their
    // depth is estimated or known), nor without a normal.
    bool shallow = sslrThinEntryShallow(sslrPixelFootprint(p, s.height, sslrClipW(p, vsSurface)), v.behind);
    v.thinCandidate = t.thinObjectHits != 0 && normalOk && !measured && !c.hidden && !(c.extra > 0.0f) && shallow;
    return v;
  }
  v.kind = behindNear >= slab ? SSLR_VERDICT_BEHIND : SSLR_VERDICT_NEAR;
  return v;
}

// What the walk knows of a ray that ended inside what pixel px shows (SSLR_VERDICT_INSIDE): where
// it entered the run of pixels it has been behind since it was last in front or deeper than the
// solid (window space wEntry, its window-space direction d, its length LEntry there), and the
// verdict at px.
struct SslrInside {
  vec3 wEntry, d;
  float LEntry;
  ivec2 px;
  SslrVerdict verdict;
};

// The answer for a ray that ended inside a solid (`hit`: the walk's record so far): the surface
// where it went in (sslrEntryHit), a thin object's hidden side
// (a guess: half resolution's other pixels do not reuse it); else hidden where it entered (a
// measured solid) or the slab guess's length there (sslrSlabGuess).
SSLR_FN SslrHit sslrJudgeInside(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 vsP, vec3 vsR, SslrHit hit,
                                SslrInside entered) {
  float Lc = 0.0f;
  if (sslrEntryHit(p, s, t, entered.wEntry, entered.d, vsP, vsR, Lc) && Lc <= t.maxDistance)
    return sslrFinishHit(p, hit, vsP, vsR, Lc, 1.0f);
  vec3 vsSlab, vsSlabNormal;
  if (entered.verdict.thinCandidate && sslrLoadSurface(entered.px, vsSlab) &&
      sslrDecodeNormal(s, sslrLoadNormal(entered.px), vsSlabNormal) &&
      sslrMetThinObject(p, s, entered.px, vsSlab, vsSlabNormal, entered.verdict.tolerance, entered.verdict.behind) &&
      entered.LEntry <= t.maxDistance) {
    SslrHit met = sslrFinishHit(p, hit, vsP, vsR, entered.LEntry, 1.0f);
    met.guessed = 1;
    if (met.status == SSLR_STATUS_HIT) return met;
  }
  if (entered.verdict.measured) {  // known hidden from where it entered the solid's pixels (sslrProbeAfterWalk)
    hit.status = SSLR_STATUS_HIDDEN;
    hit.L = entered.LEntry;
  } else {
    hit.LSlab = entered.LEntry;
  }
  return hit;
}

// ---- Guesses ------------------------------------------------------------------------------------

// Settings::traversal.hiddenGuess: a final answer without a hit whose traversal ended behind what
// the screen shows (off the screen, out of steps) takes the colour where the ray last went behind,
// at confidence hiddenGuess: the occluder's visible side for its hidden one, fading towards the
// fallback. The hit metrics count hits above 0.5 confidence, so a weight up to 0.5 changes the
// image, not recall or false hits.
SSLR_FN SslrHit sslrHiddenGuess(SslrTraceParams t, SslrHit answer) {
  if (!(t.hiddenGuess > 0.0f) || answer.status == SSLR_STATUS_HIT) return answer;
  // Finite, on the screen and within the reflection's reach (a poisoned depth buffer can make
  // neither: then no guess, as no hit). isnan/isinf explicitly: shader compilers may assume that
  // comparisons never see a NaN.
  vec2 uv = answer.uvGuess;
  float L = answer.LGuess;
  if (isnan(uv.x) || isnan(uv.y) || isnan(L) || isinf(uv.x) || isinf(uv.y) || isinf(L)) return answer;
  if (!(L > 0.0f && L <= t.maxDistance)) return answer;
  if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)) return answer;
  answer.status = SSLR_STATUS_HIT;
  answer.uvHit = answer.uvGuess;
  answer.L = answer.LGuess;
  answer.confidence = t.hiddenGuess;
  answer.guessed = 1;
  return answer;
}

// A ray the traversal stopped inside an object's assumed slab, past which adaptive L found nothing
// (or which it did not probe: a ray towards the camera, sslrTraversalOnly), passed behind the
// object (a miss: the fallback) or met its hidden side (the slab's colour): the answer is where it
// went into the slab, at the guesses' confidence (Settings::traversal.hiddenGuess). It runs after
// sslrHiddenGuess, whose guess (where the ray first went behind something) takes precedence.
SSLR_FN SslrHit sslrSlabGuess(SslrProjection p, SslrTraceParams t, vec3 vsP, vec3 vsR, SslrHit answer) {
  if (answer.status == SSLR_STATUS_HIT || !(answer.LSlab > 0.0f) || !(t.hiddenGuess > 0.0f) ||
      !(answer.LSlab <= t.maxDistance))
    return answer;
  SslrHit guess = sslrFinishHit(p, answer, vsP, vsR, answer.LSlab, t.hiddenGuess);
  guess.guessed = 1;
  return guess.status == SSLR_STATUS_HIT ? guess : answer;
}

// The guesses for a traversal-first answer without a hit, in their order: where the ray went out of
// sight, else where it went into a slab. Whichever stage answers the ray applies them.
SSLR_FN SslrHit sslrGuess(SslrProjection p, SslrTraceParams t, vec3 vsP, vec3 vsR, SslrHit answer) {
  return sslrSlabGuess(p, t, vsP, vsR, sslrHiddenGuess(t, answer));
}


#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_HIT_MODEL_H
