// sslr_trace_hiz.h - the hierarchical traversal over the min-max depth pyramid, and the per-pixel
// choice between it and the adaptive-L tracer. Shared by the GPU pass and the CPU tests.
//
// Besides the loaders of sslr_trace.h, the includer defines
//   vec2 sslrLoadPyramidTexel(int level, ivec2 cell);  // the pyramid (sslr_shared.h): level 0
//                                                      // sslrHiZLevel0Texel, level >= 1 (min, max)
//
// The traversal (in the spirit of Uludag's Hi-Z tracing, GPU Pro 5, and FidelityFX SSSR) runs in
// window space: x, y in pixels and the raw window depth. Both kinds of projection map the view-
// space ray to a straight line there with the depth affine along it (perspective: depth is affine
// in 1/w, as are x and y), so a cell of the pyramid is crossed by one segment whose nearest and
// farthest depth sit at its ends. The depth is multiplied by keySign (-1 for reversed Z) so that a
// larger key is always farther from the camera; the sign flip is exact, reversed-Z keeps its bits.
//
// Per step, at the current level, the cell under the ray is
//   - skipped when the segment lies in front of the nearest depth of the cell, or behind its
//     farthest depth by more than any hit tolerance and the objects' assumed thickness (the ray
//     passes behind what the cell shows: depth buffers have no thickness, this is the thickness
//     test); after a skip the level rises when the ray enters a new parent cell;
//   - else descended into, after moving to where the ray reaches the cell's nearest depth;
//   - at level 0 (a pixel), a crossing is a hit when it passes the plane check (sslrPlaneHit) and
//     the adaptive-L validation. A crossing that fails them ends the ray when it went less deep
//     behind the surface than the thickness (it hit the hidden side of what the pixel shows, or,
//     just past an outline, a visible side narrower than a pixel: sslrCornerHit), and lets it pass
//     behind when it went deeper (a silhouette the ray passes behind). A ray that ends inside a
//     curved surface's solid hits where it went behind, across a crease between two samples or
//     at the rim the outline's pixel hides (sslrCurvedEntryHit and its sslrRimEntryHit).

#ifndef SSLR_TRACE_HIZ_H
#define SSLR_TRACE_HIZ_H

#include "sslr_trace.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// The level after a skipped cell (or a tested pixel, level 0): one coarser when the ray enters a
// new parent cell, else the same (the parent, containing the cell, could not have been skipped
// whole).
SSLR_FN int sslrHiZNextLevel(vec3 o, vec3 d, float tRay, vec2 cell, int level, int topLevel) {
  if (level >= topLevel) return topLevel;
  float parentSize = float(2 << level);
  vec2 parentNext = floor((vec2(o.x, o.y) + vec2(d.x, d.y) * tRay) / parentSize);
  vec2 parentNow = floor(cell * 0.5f);
  return (parentNext.x != parentNow.x || parentNext.y != parentNow.y) ? level + 1 : level;
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
  float dist = p.orthographic != 0 ? 1.0f : -vsSurface.z;
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
// about as deep as it is wide, so a ray less deep behind it than twice its width (and than
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

// A ray that crosses an object's outline into its pixel a little behind the face the pixel shows
// met the object's side: a face the depth buffer holds no sample of where it is narrower than a
// pixel (a box's top seen from just above it, a pillar's side seen nearly along it). The side is
// taken to meet the shown face at a right angle along the outline (the corner outline thinning
// assumes). It is a hit when the side faces the camera, the ray meets it from outside no deeper
// than the slab behind the edge, and the hit projects between the outline and the outer pixel's
// centre (had the side reached that centre, the outer pixel would show it). A side within ~6
// degrees of edge-on (cos <= 0.1) is not trusted: rays from many pixels converge on such a
// sliver, and most of them would be wrong (docs/design-notes.md). wEntry: where the ray entered the pixel
// (window space, just past the boundary), d: the ray's window-space direction.
SSLR_FN bool sslrCornerHit(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 wEntry, vec3 d, vec3 vsP,
                           vec3 vsR, SSLR_OUT(float) L) {
  L = 0.0f;
  ivec2 px = ivec2(floor(vec2(wEntry.x, wEntry.y)));
  vec2 f = vec2(wEntry.x, wEntry.y) - vec2(px);
  float ex = d.x > 0.0f ? f.x : 1.0f - f.x;  // distance from the boundary the ray came through
  float ey = d.y > 0.0f ? f.y : 1.0f - f.y;
  bool acrossX = ex <= ey;
  if (min(ex, ey) > 0.02f) return false;  // it did not cross a boundary here (it was moved on inside)
  ivec2 outward = acrossX ? ivec2(d.x > 0.0f ? -1 : 1, 0) : ivec2(0, d.y > 0.0f ? -1 : 1);
  ivec2 npx = px + outward;
  if (npx.x < 0 || npx.y < 0 || npx.x >= s.width || npx.y >= s.height) return false;
  float keySign = s.reversedZ != 0 ? -1.0f : 1.0f;
  float depthOut = sslrLoadDepth(npx);
  // An outline: the outer pixel shows something beyond the ray, or nothing.
  if (sslrIsGeometryDepth(s, depthOut) && !(keySign * depthOut > wEntry.z)) return false;
  vec3 vsSurface;
  vec3 vsN;
  if (!sslrLoadSurface(px, vsSurface) || !sslrDecodeNormal(s, sslrLoadNormal(px), vsN)) return false;
  // A curved surface is no corner (its solid is the sphere of its curvature).
  if (sslrCurvedSolids(t) && sslrLoadPyramidTexel(0, px).y > 0.0f) return false;
  float slab = t.objectDepthRelative * -vsSurface.z;
  if (sslrBackDepth(s)) {  // measured (0: nothing measured there, the slab assumed)
    float measured = sslrLoadPyramidTexel(0, px).y;
    if (measured != 0.0f) slab = max(slab + measured, 0.0f);
  }
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
  vec3 wQ = sslrWindowFromView(p, vec2(s.width, s.height), keySign, vsQ);
  float outside = acrossX ? (wQ.x - wEdge.x) * float(outward.x) : (wQ.y - wEdge.y) * float(outward.y);
  return outside >= -0.05f && outside <= 0.5f;
}

// The ray's length L at window-space parameter tRay (o + d tRay), for a HIDDEN answer.
SSLR_FN float sslrRayLengthAt(SslrProjection p, vec2 sizePx, float keySign, vec3 o, vec3 d, float tRay, vec3 vsP,
                              vec3 vsR) {
  vec3 w = o + d * tRay;
  return dot(sslrViewFromUvDepth(p, vec2(w.x, w.y) / sizePx, keySign * w.z) - vsP, vsR);
}

// The traversal's state between its steps: the ray in window space (x, y in pixels, z the depth
// key; t counts pixels along the major axis) and where the walk stands.
struct SslrWalk {
  vec3 o, d;
  vec2 invD;          // 1 / d.xy, huge but finite on an axis the ray does not move along
  vec2 boundaryStep;  // 1 on an axis the ray moves up, 0 down: the cell boundary it leaves by
  vec2 sizePx;
  float keySign;      // -1 with reversed depth: keySign x depth grows away from the camera
  float tRay;         // where the ray is
  int level, topLevel;
  int i;              // steps taken
  // Where the ray entered the first pixel of the pixels it has been behind since it was last in
  // front of (or deeper than the slab behind) what the screen shows: the outline it may have
  // crossed onto an object's side (sslrCornerHit, tried once, if the ray ends in the slab).
  float tRun;
  bool inSlab;
  bool measuredSlab;  // ... inside a solid whose depth the back-face depth measured
  // ... inside what pixel slabPx shows, slabBehind deep behind it (view units) where its segment
  // there begins: a thin object's hidden side, if sslrMetThinObject says so after the walk.
  bool thinCandidate;
  ivec2 slabPx;
  float slabBehind, slabTolerance;
  bool hidden;  // the ray is behind what the screen shows now (its last pixel or cell)
  // The pixel sslrWalkToPixel reached: its cell, where the ray leaves it, the ray's nearest and
  // farthest depth keys in it, the cell's nearest key and the pixel's extra depth (level 0's .y).
  vec2 cell;
  float tExit, segNear, segFar, keyNear, extra;
};

// How a step ended: at a pixel to test, with the walk over (out of steps, or inside a slab), or
// with the hit record answered (a hit, off the screen, hidden).
#define SSLR_WALK_PIXEL 0
#define SSLR_WALK_ENDED 1
#define SSLR_WALK_ANSWERED 2
#define SSLR_WALK_ON 3  // sslrWalkStep: a cell skipped or descended into, the walk goes on
// Past a cell boundary, in pixels (exact in float up to 2^15 px).
#define SSLR_HIZ_NUDGE (1.0f / 256.0f)

// sslrCurvedEntryHit's branch for a pixel px with no curved extra depth, on a curved surface near
// an object's outline (where the radius estimate gives none): the ray crossed into px from npx
// (keyIn: px's depth key, depthOut: npx's raw depth) and went behind px's sample there. It met the
// surface where it went behind:
// - across a crease: npx is the same surface with its sample beyond the ray (the crossing lies
//   between the two samples, where neither pixel's tangent plane holds it);
// - at the rim: it came from beyond the outline and is behind the rim's sample by less than the
//   surface recedes from the pixel inwards to the rim (the part that turns away within the pixel).
// Curved: the two pixels' shading normals turn as on one curved surface (sslrNormalsTurnAsCurved),
// not as on a flat face (one normal), which ends at its outline, or at an edge between two faces.
SSLR_FN bool sslrRimEntryHit(SslrProjection p, SslrSurface s, vec3 wEntry, vec3 d, vec3 vsP,
                             vec3 vsR, ivec2 px, ivec2 npx, float keyIn, float depthOut, SSLR_OUT(float) L) {
  L = 0.0f;
  float keySign = s.reversedZ != 0 ? -1.0f : 1.0f;
  bool outGeometry = sslrIsGeometryDepth(s, depthOut);
  if (outGeometry && !(wEntry.z <= keySign * depthOut)) return false;
  float distIn = sslrViewDepthFromDepth(p, keySign * keyIn);
  float tolerance = sslrHitTolerance(p, s, distIn, 16.0f);
  bool crease = outGeometry && abs(sslrViewDepthFromDepth(p, depthOut) - distIn) <= tolerance;
  ivec2 other = npx;
  if (!crease) {  // the rim: the pixel inwards, the same surface and nearer
    other = px + (px - npx);
    if (min(other.x, other.y) < 0 || other.x >= s.width || other.y >= s.height) return false;
    float keyInward = keySign * sslrLoadDepth(other);
    if (!sslrIsGeometryDepth(s, keySign * keyInward) || !(keyInward < keyIn) ||
        !(abs(sslrViewDepthFromDepth(p, keySign * keyInward) - distIn) <= tolerance) ||
        !(wEntry.z - keyIn <= keyIn - keyInward))
      return false;
  }
  vec3 nIn, nOther;
  if (!sslrDecodeNormal(s, sslrLoadNormal(px), nIn) || !sslrDecodeNormal(s, sslrLoadNormal(other), nOther) ||
      !sslrNormalsTurnAsCurved(s, nIn, nOther))
    return false;
  // A rim hit is reported halfway to where the ray leaves the rim pixel: its colour, not a blend
  // with what lies beyond the outline.
  float tIn = 0.0f;
  if (!crease) {
    vec2 stepOut = vec2(d.x >= 0.0f ? 1.0f : 0.0f, d.y >= 0.0f ? 1.0f : 0.0f);
    vec2 tOut = (vec2(px) + stepOut - vec2(wEntry.x, wEntry.y)) /
                vec2(abs(d.x) > 1e-12f ? d.x : 1e-12f, abs(d.y) > 1e-12f ? d.y : 1e-12f);
    tIn = clamp(0.5f * min(tOut.x, tOut.y), 0.0f, 0.5f);
  }
  L = sslrRayLengthAt(p, vec2(s.width, s.height), keySign, wEntry, d, tIn, vsP, vsR);
  return L > 0.0f;
}

// Where a ray that ended inside a curved surface's solid entered it (w.tRun, window space wEntry;
// the pixel there is px): a hit if it entered through the surface the pixel shows. A faceted mesh
// with interpolated normals holds flat facets in depth while its shading normals tilt away from
// them, so the pixel tests' tangent planes refuse such crossings, and a crease between facets,
// seen at an angle, steps in depth from one pixel to the next. Where px has a curved extra depth,
// two cases:
// - the ray crossed into px from a neighbour whose surface lies beyond it there, and is behind
//   px's: it crossed the surface between the two samples, at the boundary, if the two are one
//   surface (their depths differ by no more than the steepest slope's hit tolerance; an outline
//   steps further);
// - otherwise it went behind inside px: a hit where it did, if that point lies on px's surface
//   within the hit tolerance (adaptive L's convergence test).
// Where it has none (near an outline), sslrRimEntryHit. With the back-face depth, level 0 holds
// the measured extra depth instead, and the same two rules run on it: a measured solid thicker
// than the slab, or the rim where it is thinner (a ray that ended inside it entered somewhere).
SSLR_FN bool sslrCurvedEntryHit(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 wEntry, vec3 d, vec3 vsP,
                                vec3 vsR, SSLR_OUT(float) L) {
  L = 0.0f;
  if (!sslrCurvedSolids(t) && !sslrBackDepth(s)) return false;
  ivec2 px = ivec2(floor(vec2(wEntry.x, wEntry.y)));
  float keySign = s.reversedZ != 0 ? -1.0f : 1.0f;
  float keyIn = keySign * sslrLoadDepth(px);
  // The pixel the ray came from: just before the boundary it crossed (2 nudges back along the
  // major axis; a corner's other boundary, crossed earlier, stays crossed).
  ivec2 npx = ivec2(floor(vec2(wEntry.x, wEntry.y) - vec2(d.x, d.y) * (2.0f * SSLR_HIZ_NUDGE)));
  bool crossedIn = (npx.x != px.x || npx.y != px.y) && wEntry.z > keyIn && npx.x >= 0 && npx.y >= 0 &&
                   npx.x < s.width && npx.y < s.height;
  bool curvedPixel = sslrLoadPyramidTexel(0, px).y > 0.0f;
  if (!curvedPixel && crossedIn)
    return sslrRimEntryHit(p, s, wEntry, d, vsP, vsR, px, npx, keyIn, sslrLoadDepth(npx), L);
  vec3 vsSurface;
  if (!sslrLoadSurface(px, vsSurface)) return false;
  L = sslrRayLengthAt(p, vec2(s.width, s.height), keySign, wEntry, d, 0.0f, vsP, vsR);
  if (!(L > 0.0f)) return false;
  if (!crossedIn) {
    vec3 vsQ = vsP + vsR * L;
    float distS = p.orthographic != 0 ? abs(vsSurface.z) : -vsSurface.z;
    return curvedPixel && length(vsQ - vsSurface) <= sslrHitTolerance(p, s, distS, 0.0f);
  }
  float depthOut = sslrLoadDepth(npx);
  if (!sslrIsGeometryDepth(s, depthOut) || !(wEntry.z <= keySign * depthOut)) return false;
  float distIn = sslrViewDepthFromDepth(p, keySign * keyIn);
  return abs(sslrViewDepthFromDepth(p, depthOut) - distIn) <= sslrHitTolerance(p, s, distIn, 16.0f);
}

// The ray from vsP along vsR in window space, just out of its own pixel. False for a ray along the
// view direction: it stays in its own pixel, and nothing on screen can answer it.
SSLR_FN bool sslrWalkBegin(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 vsP, vec3 vsR,
                           SSLR_OUT(SslrWalk) w) {
  w.sizePx = vec2(s.width, s.height);
  w.keySign = s.reversedZ != 0 ? -1.0f : 1.0f;
  w.invD = vec2(0.0f);
  w.boundaryStep = vec2(0.0f);
  w.tRay = 0.0f;
  w.level = 0;
  w.topLevel = t.hizLevels;
  w.i = 0;
  w.tRun = -1.0f;
  w.inSlab = false;
  w.measuredSlab = false;
  w.thinCandidate = false;
  w.slabPx = ivec2(0);
  w.slabBehind = 0.0f;
  w.slabTolerance = 0.0f;
  w.hidden = false;
  w.cell = vec2(0.0f);
  w.tExit = 0.0f;
  w.segNear = 0.0f;
  w.segFar = 0.0f;
  w.keyNear = 0.0f;
  w.extra = 0.0f;
  w.o = sslrWindowFromView(p, w.sizePx, w.keySign, vsP);
  w.d = sslrWindowDirection(p, s, w.keySign, vsP, vsR, w.o);
  float majorPx = max(abs(w.d.x), abs(w.d.y));
  if (!(majorPx > 1e-3f)) return false;
  w.d /= majorPx;
  w.invD = vec2(abs(w.d.x) > 1e-12f ? 1.0f / w.d.x : 1e12f, abs(w.d.y) > 1e-12f ? 1.0f / w.d.y : 1e12f);
  w.boundaryStep = vec2(w.d.x >= 0.0f ? 1.0f : 0.0f, w.d.y >= 0.0f ? 1.0f : 0.0f);
  // Leave the reflecting pixel first.
  vec2 cell0 = floor(vec2(w.o.x, w.o.y));
  vec2 tBound0 = ((cell0 + w.boundaryStep) - vec2(w.o.x, w.o.y)) * w.invD;
  w.tRay = min(tBound0.x, tBound0.y) + SSLR_HIZ_NUDGE;
  // Level 0 is read only inside a 2x2 quad whose level-1 cell holds geometry (classification
  // writes no level-0 texels under a cell of background alone): the walk enters a new quad at
  // level 1, here and after each pixel it tested, as after a skip.
  w.level = sslrHiZNextLevel(w.o, w.d, w.tRay, cell0, 0, w.topLevel);
  return true;
}

// Whether a ray whose segment in a cell lies segNear deep, beyond the cell's farthest key keyFar,
// passes behind everything the cell shows: deeper than any tolerance and than the objects'
// assumed thickness. (The slope term of the tolerance is unknown before a pixel is looked at: the
// largest one, tan = 16, is assumed.)
SSLR_FN bool sslrPassesBehindCell(SslrProjection p, SslrSurface s, SslrTraceParams t, float keySign, float segNear,
                                  float keyFar, float extra) {
  float farDepth = keySign * keyFar;
  if (!(segNear > keyFar && sslrIsGeometryDepth(s, farDepth))) return false;
  float distFar = sslrViewDepthFromDepth(p, farDepth);
  float distRay = sslrViewDepthFromDepth(p, keySign * segNear);
  float tolerance16 = sslrHitTolerance(p, s, distFar, 16.0f);
  float passBehind = sslrBackDepth(s) ? max(tolerance16, t.objectDepthRelative * distFar + extra)
                                      : max(tolerance16, t.objectDepthRelative * distFar) + extra;
  return distRay - distFar > passBehind;
}

// A hidden passage begins (Settings::traversal.hiddenGuess): where, and the ray's length there.
SSLR_FN void sslrNoteHiddenStart(SslrProjection p, SslrTraceParams t, SslrWalk w, vec2 uv, vec3 vsP, vec3 vsR,
                                 SSLR_INOUT(SslrHit) hit) {
  if (!(t.hiddenGuess > 0.0f) || hit.LGuess != 0.0f) return;
  hit.uvGuess = uv;
  hit.LGuess = sslrRayLengthAt(p, w.sizePx, w.keySign, w.o, w.d, w.tRay, vsP, vsR);
}

// One step of the walk over pyramid cells: a cell skipped or descended into (SSLR_WALK_ON), or a
// pixel the ray does not pass in front of or far behind (SSLR_WALK_PIXEL: w.cell and the segment
// fields are that pixel's).
SSLR_FN int sslrWalkStep(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 vsP, vec3 vsR,
                         SSLR_INOUT(SslrWalk) w, SSLR_INOUT(SslrHit) hit) {
  vec3 pos = w.o + w.d * w.tRay;
  bool onScreen = pos.x >= 0.0f && pos.y >= 0.0f && pos.x < w.sizePx.x && pos.y < w.sizePx.y;
  float depthPos = w.keySign * pos.z;  // behind the near plane or beyond the far one: off too
  if (!onScreen || !(depthPos >= 0.0f && depthPos <= 1.0f)) {
    hit.status = SSLR_STATUS_OFF_SCREEN;
    return SSLR_WALK_ANSWERED;
  }
  float cellSize = float(1 << w.level);
  w.cell = floor(vec2(pos.x, pos.y) / cellSize);
  vec2 texel = sslrLoadPyramidTexel(w.level, ivec2(w.cell));
  vec2 minMax = sslrHiZMinMax(w.level, texel);
  hit.iterations = w.i + 1;
  w.keyNear = min(w.keySign * minMax.x, w.keySign * minMax.y);
  float keyFar = max(w.keySign * minMax.x, w.keySign * minMax.y);
  vec2 tBound = ((w.cell + w.boundaryStep) * cellSize - vec2(w.o.x, w.o.y)) * w.invD;
  w.tExit = min(tBound.x, tBound.y);
  float keyExit = w.o.z + w.d.z * w.tExit;
  w.segNear = min(pos.z, keyExit);
  w.segFar = max(pos.z, keyExit);
#ifdef SSLR_HIZ_DEBUG_HOOK
  SSLR_HIZ_DEBUG_HOOK(w.i, w.level, w.cell, w.tRay, w.tExit, pos, keyExit, w.keyNear, keyFar);
#endif
  // In front of everything the cell shows, or a cell of background alone (nothing in it can
  // stop a ray; classification writes no level-0 texels under such a level-1 cell): skip it.
  bool skip = w.segFar < w.keyNear || (w.level > 0 && !sslrHiZCellHoldsGeometry(s, minMax));
  // A pixel on a curved surface reaches deeper than the slab (coarse cells' far keys hold it).
  // With a back-face depth, the pixel's measured extra depth over the slab (either sign).
  w.extra = w.level == 0 && (sslrCurvedSolids(t) || sslrBackDepth(s)) ? texel.y : 0.0f;
  bool behindSkip = !skip && sslrPassesBehindCell(p, s, t, w.keySign, w.segNear, keyFar, w.extra);
  if (behindSkip) {
    w.hidden = true;
    sslrNoteHiddenStart(p, t, w, vec2(pos.x, pos.y) / w.sizePx, vsP, vsR, hit);
  } else if (skip) {
    hit.LGuess = 0.0f;  // in front again (or over background): not hidden
    w.hidden = false;
  }
  if (skip || behindSkip) {
    // Look coarser only on entering a new parent cell: the parent of this one was (or will
    // be) looked at already, and going up into it again costs a step just to come back down.
    w.tRun = -1.0f;
    w.tRay = w.tExit + SSLR_HIZ_NUDGE;
    w.level = sslrHiZNextLevel(w.o, w.d, w.tRay, w.cell, w.level, w.topLevel);
    return SSLR_WALK_ON;
  }
  if (w.level > 0) {
    // Move to where the ray reaches the cell's nearest depth (nothing in the cell is nearer),
    // then look finer.
    if (w.d.z > 0.0f && pos.z < w.keyNear) w.tRay = max(w.tRay, (w.keyNear - w.o.z) / w.d.z);
    --w.level;
    return SSLR_WALK_ON;
  }
  return SSLR_WALK_PIXEL;
}

// The walk until the ray reaches a pixel to test (SSLR_WALK_PIXEL), runs out of steps or is
// answered.
SSLR_FN int sslrWalkToPixel(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 vsP, vec3 vsR,
                            SSLR_INOUT(SslrWalk) w, SSLR_INOUT(SslrHit) hit) {
  for (; w.i < t.maxSteps; ++w.i) {
    int step = sslrWalkStep(p, s, t, vsP, vsR, w, hit);
    if (step != SSLR_WALK_ON) return step;
  }
  return SSLR_WALK_ENDED;
}

// The test of the pixel the walk reached (level 0): a hit (SSLR_WALK_ANSWERED), the ray inside
// what the pixel shows (SSLR_WALK_ENDED, w.inSlab), or on past it (SSLR_WALK_PIXEL: walk on).
// The walk ends inside what pixel px shows (vsSurface), behindNear deep behind it where the ray's
// segment there begins. Kept for sslrMetThinObject after the walk, outside its loop: a thin object's
// hidden side, not where the ray was already out of sight (the hidden guess's), nor behind a curved
// or measured solid (their depth is estimated or known; `thinTestable` is false for a measured one
// or a pixel without a normal).
SSLR_FN void sslrEnterSlab(SslrProjection p, SslrSurface s, SslrTraceParams t, SSLR_INOUT(SslrWalk) w, ivec2 px,
                           vec3 vsSurface, bool thinTestable, float behindNear, float tolerance) {
  w.inSlab = true;
  w.slabPx = px;
  w.slabBehind = max(behindNear, 0.0f);
  w.slabTolerance = tolerance;
  bool shallow = sslrThinEntryShallow(sslrPixelFootprint(p, s.height, sslrClipW(p, vsSurface)), w.slabBehind);
  w.thinCandidate = t.thinObjectHits != 0 && thinTestable && !w.hidden && !(w.extra > 0.0f) && shallow;
}

SSLR_FN int sslrTestPixel(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP, vec3 vsR,
                          SSLR_INOUT(SslrWalk) w, SSLR_INOUT(SslrHit) hit) {
  ivec2 px = ivec2(w.cell);
  vec3 vsSurface;
  if (!sslrLoadSurface(px, vsSurface)) {  // background: only a ray beyond the far plane gets here
    w.tRun = -1.0f;
    w.tRay = w.tExit + SSLR_HIZ_NUDGE;
    w.level = sslrHiZNextLevel(w.o, w.d, w.tRay, w.cell, 0, w.topLevel);
    return SSLR_WALK_PIXEL;
  }
  vec3 vsSurfaceNormal;
  bool normalOk = sslrDecodeNormal(s, sslrLoadNormal(px), vsSurfaceNormal);
  bool ownPixel = px.x == pxOrigin.x && px.y == pxOrigin.y;
  float L = 0.0f;
  // The hit: where the ray meets the pixel's tangent plane (sslrPlaneHit).
  float valid = normalOk && !ownPixel ? sslrPlaneHit(p, s, pxOrigin, vsP, vsR, px, vsSurface, vsSurfaceNormal, L)
                                      : 0.0f;
  if (valid >= 0.5f) {
    if (!(L > t.maxDistance)) hit = sslrFinishHit(p, hit, vsP, vsR, L, valid);
    return SSLR_WALK_ANSWERED;
  }
  // No hit here. How deep behind the pixel's surface does the ray get inside the pixel?
  float distSurface = -vsSurface.z;  // view depth, as sslrViewDepthFromDepth measures it
  float behind = sslrViewDepthFromDepth(p, w.keySign * w.segFar) - distSurface;
  float tolerance =
      sslrHitTolerance(p, s, distSurface, normalOk ? sslrSlopeTan(p, vsSurface, vsSurfaceNormal) : 16.0f);
  // What the pixel shows is taken to fill [surface, surface + slab] along the view: the slab is
  // objectDepthRelative x distance, thinner near the object's outline (sslrSlabNearOutline). A ray
  // inside it (deeper than the hit tolerance: pixel snapping) ran into the hidden part of the
  // object, from the front or from behind: nothing on screen is its reflection. Deeper than the
  // slab it passes behind; within the tolerance it goes on. Inside the slab just past an outline
  // it may have met the object's side, narrower than a pixel (sslrCornerHit).
  float slab = t.objectDepthRelative * distSurface;
  // A measured solid (back-face depth) holds the ray when any part of its segment in the pixel
  // lies inside [surface + tolerance, back]: a ray running along the view direction crosses a
  // box's depth within one pixel, its far end already behind the back.
  bool measured = sslrBackDepth(s) && w.extra != 0.0f;
  float behindNear = measured ? sslrViewDepthFromDepth(p, w.keySign * w.segNear) - distSurface : behind;
  if (behind > 0.0f && !ownPixel) {
    // A curved surface's solid reaches deeper; a flat face's gets thinner near its outline (the
    // outline rule reads the pyramid's far keys, which on curved surfaces hold their backs).
    if (measured) slab = max(slab + w.extra, 0.0f);
    else if (w.extra > 0.0f) slab += w.extra;
    else if (normalOk && behind > tolerance && behind < slab)
      slab = sslrSlabNearOutline(p, s, t, px, vsSurface, vsSurfaceNormal, w.segFar, w.keySign, slab);
    if (w.tRun < 0.0f) w.tRun = w.tRay;
    // A measured solid thinner than twice the tolerance (a face seen at a grazing angle has a
    // wide one) holds the ray once it is half the solid deep: the measurement says it is inside.
    float into = measured ? min(tolerance, 0.5f * slab) : tolerance;
    if (behind > into && behindNear < slab) {
      sslrEnterSlab(p, s, t, w, px, vsSurface, normalOk && !measured, behindNear, tolerance);
      w.measuredSlab = measured;
      return SSLR_WALK_ENDED;
    }
  }
  if (!(behind > 0.0f) || behindNear >= slab) w.tRun = -1.0f;
  if (!(behind > 0.0f)) {
    hit.LGuess = 0.0f;
    w.hidden = false;
  }
  if (behind > 0.0f && behindNear >= slab && !ownPixel) {  // passed behind what the pixel shows
    w.hidden = true;
    sslrNoteHiddenStart(p, t, w, (vec2(px) + 0.5f) / w.sizePx, vsP, vsR, hit);
  }
  w.tRay = w.tExit + SSLR_HIZ_NUDGE;
  w.level = sslrHiZNextLevel(w.o, w.d, w.tRay, w.cell, 0, w.topLevel);
  return SSLR_WALK_PIXEL;
}

SSLR_FN SslrHit sslrTraceHierarchical(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin,
                                      vec3 vsP, vec3 vsR) {
  SslrHit hit = sslrNoHit(SSLR_STATUS_MISS);
  hit.hierarchical = 1;
  SslrWalk w;
  if (!sslrWalkBegin(p, s, t, vsP, vsR, w)) return hit;
  // Two phases per pixel the ray reaches: the walk (skip, descend) over cells until the ray
  // reaches a pixel it does not pass in front of or far behind, then that pixel's test. In SIMD
  // lanes that run in step (CPU rasterizers run every instruction of a loop body under lane
  // masks) the test then runs once for the lanes' pixels together instead of in every step.
  // SSLR_HIZ_ONE_BODY (Settings::debug.traversalLoop = OneBody) runs the same steps in one loop body
  // instead: a lane tests its pixel as soon as it reaches one, without waiting for the others.
  while (w.i < t.maxSteps) {
#ifdef SSLR_HIZ_ONE_BODY
    int walked = sslrWalkStep(p, s, t, vsP, vsR, w, hit);
    if (walked == SSLR_WALK_ON) {
      ++w.i;
      continue;
    }
#else
    int walked = sslrWalkToPixel(p, s, t, vsP, vsR, w, hit);
#endif
    if (walked == SSLR_WALK_ANSWERED) return hit;
    if (walked == SSLR_WALK_ENDED) break;
    ++w.i;  // the test is the step that reached the pixel
    int tested = sslrTestPixel(p, s, t, pxOrigin, vsP, vsR, w, hit);
    if (tested == SSLR_WALK_ANSWERED) return hit;
    if (tested == SSLR_WALK_ENDED) break;
  }
  // Out of steps in front of what the screen shows: adaptive L may resume there
  // (sslrProbeAfterWalk), the segment before it walked.
  if (w.i >= t.maxSteps && !w.inSlab && !w.hidden)
    hit.LResume = sslrRayLengthAt(p, w.sizePx, w.keySign, w.o, w.d, w.tRay, vsP, vsR);
  // Ended inside an object's slab: its side, if the ray crossed an outline onto it.
  float Lc = 0.0f;
  if (w.inSlab && sslrCornerHit(p, s, t, w.o + w.d * w.tRun, w.d, vsP, vsR, Lc) && Lc <= t.maxDistance)
    return sslrFinishHit(p, hit, vsP, vsR, Lc, 1.0f);
  if (w.inSlab && sslrCurvedEntryHit(p, s, t, w.o + w.d * w.tRun, w.d, vsP, vsR, Lc) && Lc <= t.maxDistance)
    return sslrFinishHit(p, hit, vsP, vsR, Lc, 1.0f);
  // Inside a thin object's slab: it met the object's hidden side, shown by where it went in.
  vec3 vsSlab, vsSlabNormal;
  if (w.thinCandidate && sslrLoadSurface(w.slabPx, vsSlab) &&
      sslrDecodeNormal(s, sslrLoadNormal(w.slabPx), vsSlabNormal) &&
      sslrMetThinObject(p, s, w.slabPx, vsSlab, vsSlabNormal, w.slabTolerance, w.slabBehind)) {
    Lc = sslrRayLengthAt(p, w.sizePx, w.keySign, w.o, w.d, w.tRun, vsP, vsR);
    if (Lc <= t.maxDistance) {
      SslrHit met = sslrFinishHit(p, hit, vsP, vsR, Lc, 1.0f);
      met.guessed = 1;
      if (met.status == SSLR_STATUS_HIT) return met;
    }
  }
  if (w.measuredSlab) {  // known hidden: where the ray entered the solid's pixels (sslrProbeAfterWalk)
    hit.status = SSLR_STATUS_HIDDEN;
    hit.L = sslrRayLengthAt(p, w.sizePx, w.keySign, w.o, w.d, w.tRun, vsP, vsR);
  } else if (w.inSlab) {
    hit.LSlab = sslrRayLengthAt(p, w.sizePx, w.keySign, w.o, w.d, w.tRun, vsP, vsR);
  }
  return hit;
}

// The depth-only tracer of a pixel (t.hizMode): adaptive L alone (SSLR_HIZ_OFF), the traversal
// alone (SSLR_HIZ_ONLY), or both (SSLR_HIZ_TRAVERSAL_FIRST, the default): the traversal on every
// ray, adaptive L only where the traversal has no confident hit. The traversal walks every cell,
// so its hit is the first crossing; adaptive L converges on *a* crossing, not always the first
// (its probes can step over a thin occluder onto the surface behind), so it only answers rays the
// traversal left without one (docs/results/ray-work.md).
//
// Two stages, so that a pass can run the first alone and leave the second (with traversal first:
// adaptive L; traversal alone: the traversal) to a pass of its own (Settings::debug.traversalPass):
// sslrTraceFirstStage answers the pixel or says it needs the second.

// Rays that come back towards the camera, or run within ~17 degrees of the image plane, are where
// adaptive L jumps over what stands between (its probes see the front of the occluders, not the
// ray): the traversal's answer is final for them.
SSLR_FN bool sslrTraversalOnly(SslrProjection p, vec3 vsP, vec3 vsR) {
  return dot(vsR, -sslrViewDirection(p, vsP)) > -0.3f;
}

SSLR_FN bool sslrConfidentHit(SslrHit h) { return h.status == SSLR_STATUS_HIT && h.confidence >= 0.5f; }

// SSLR_HIZ_TRAVERSAL_FIRST: the traversal's hit where it has a confident one; where it stopped on
// the screen without one (inside an assumed slab, which adaptive L's probes carry past; at its
// step cap; a crossing it refused), adaptive L's, if confident and not beyond where the traversal
// found the ray hidden. The traversal's hit is the first crossing it walked to; adaptive L only
// fills a missing one. The two stages below: the traversal (`walked`), then adaptive L where
// sslrWalkedNeedsProbes says so.

// A ray the traversal walked off the screen (or out of the depth range) crossed nothing it could
// take: adaptive L there finds little and spends its whole iteration budget (design-notes.md,
// "Traversal first"). A ray that ran out of steps in front of what the screen shows gets adaptive
// L from there, whatever its direction: the segment before is walked, so its probes cannot jump
// over what stands there (the step cap's answer; results/ray-work.md).
SSLR_FN bool sslrWalkedNeedsProbes(SslrProjection p, vec3 vsP, vec3 vsR, SslrHit walked) {
  if (sslrConfidentHit(walked)) return false;
  return walked.LResume > 0.0f || (walked.status != SSLR_STATUS_OFF_SCREEN && !sslrTraversalOnly(p, vsP, vsR));
}

// The answer for a ray the traversal left (`walked`): adaptive L's (from walked.LResume, where the
// traversal ran out of steps), or the traversal's. hierarchical = 2 says both ran (the share
// TraversalPass::Auto follows).
SSLR_FN SslrHit sslrProbeAfterWalk(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                   vec3 vsR, SslrHit walked) {
  SslrHit probed = sslrTraceAdaptiveLFrom(p, s, t, pxOrigin, vsP, vsR, walked.LResume);
  bool useProbed = sslrConfidentHit(probed) ||
                   (probed.status == SSLR_STATUS_HIT && !(walked.status == SSLR_STATUS_HIT &&
                                                          walked.confidence >= probed.confidence));
  // Known hidden from walked.L on (a measured solid): a hit beyond that (by 3%: the same surface
  // found twice differs by less) lies behind what hid the ray.
  if (walked.status == SSLR_STATUS_HIDDEN && walked.L < 0.97f * probed.L) useProbed = false;
  SslrHit answer = useProbed ? probed : walked;
  // Where it found nothing beyond an assumed slab, the slab's colour as a guess (sslrSlabGuess).
  if (answer.status != SSLR_STATUS_HIT) answer.LSlab = walked.LSlab;
  answer.iterations = walked.iterations + probed.iterations;
  answer.hierarchical = 2;
  return answer;
}

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

// A ray the traversal stopped inside an object's assumed slab, past which adaptive L found nothing,
// passed behind the object (a miss: the fallback) or met its hidden side (the slab's colour): the
// answer is where it went into the slab, at the guesses' confidence (Settings::traversal.
// hiddenGuess). It runs after sslrHiddenGuess, whose guess (where the ray first went behind
// something) takes precedence.
SSLR_FN SslrHit sslrSlabGuess(SslrProjection p, SslrTraceParams t, vec3 vsP, vec3 vsR, SslrHit answer) {
  if (answer.status == SSLR_STATUS_HIT || !(answer.LSlab > 0.0f) || !(t.hiddenGuess > 0.0f) ||
      !(answer.LSlab <= t.maxDistance))
    return answer;
  SslrHit guess = sslrFinishHit(p, answer, vsP, vsR, answer.LSlab, t.hiddenGuess);
  guess.guessed = 1;
  return guess.status == SSLR_STATUS_HIT ? guess : answer;
}

// Whether the second stage ran for this answer (the pixels a deferred pass lists).
SSLR_FN bool sslrRanSecondStage(SslrTraceParams t, SslrHit h) {
  return sslrHiZMode(t) == SSLR_HIZ_TRAVERSAL_FIRST ? h.hierarchical == 2 : h.hierarchical != 0;
}

// The first stage's answer (traversal first: the traversal's; adaptive L alone: adaptive L's);
// needsTraversal: the pixel's answer is sslrTraceSecondStage's instead.
SSLR_FN SslrHit sslrTraceFirstStage(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                    vec3 vsR, SSLR_OUT(bool) needsTraversal) {
  needsTraversal = sslrHiZMode(t) != SSLR_HIZ_OFF;
  if (sslrHiZMode(t) == SSLR_HIZ_TRAVERSAL_FIRST) {  // the traversal first; the second stage probes
    SslrHit walked = sslrTraceHierarchical(p, s, t, pxOrigin, vsP, vsR);
    needsTraversal = sslrWalkedNeedsProbes(p, vsP, vsR, walked);
    return needsTraversal ? walked : sslrHiddenGuess(t, walked);
  }
  return needsTraversal ? sslrNoHit(SSLR_STATUS_MISS) : sslrTraceAdaptiveL(p, s, t, pxOrigin, vsP, vsR);
}

// The second stage (traversal first: adaptive L after the walk; the traversal alone: the walk),
// given the first stage's answer `first` for a pixel that needs it.
SSLR_FN SslrHit sslrTraceSecondStage(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                     vec3 vsR, SslrHit first) {
  if (sslrHiZMode(t) == SSLR_HIZ_TRAVERSAL_FIRST)
    return sslrSlabGuess(p, t, vsP, vsR, sslrHiddenGuess(t, sslrProbeAfterWalk(p, s, t, pxOrigin, vsP, vsR, first)));
  return sslrHiddenGuess(t, sslrTraceHierarchical(p, s, t, pxOrigin, vsP, vsR));
}

SSLR_FN SslrHit sslrTraceDepthOnly(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                   vec3 vsR) {
  bool needsTraversal;
  SslrHit first = sslrTraceFirstStage(p, s, t, pxOrigin, vsP, vsR, needsTraversal);
  return needsTraversal ? sslrTraceSecondStage(p, s, t, pxOrigin, vsP, vsR, first) : first;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_TRACE_HIZ_H
