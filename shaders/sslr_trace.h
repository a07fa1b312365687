// sslr_trace.h - the adaptive-L tracer, shared by the GPU pass and the CPU tests.
//
// Before including this file the includer defines two loaders over its G-buffer:
//   float sslrLoadDepth(ivec2 px);   // raw window depth at pixel px
//   vec4  sslrLoadNormal(ivec2 px);  // the texel normal/material texel at px
// The GLSL pass reads textures (and counts fetches); the C++ tests read arrays.
#ifndef SSLR_TRACE_H
#define SSLR_TRACE_H

#include "sslr_shared.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// Largest factor by which L may grow in one step before a bracket exists.
#ifndef SSLR_MAX_GROWTH
#define SSLR_MAX_GROWTH 2.0f
#endif
// Steps back after a probe left the screen or met the sky, before giving up. Each retreat costs a
// sky-bound ray one more iteration; a second one recovered almost no hits (docs/design-notes.md).
#ifndef SSLR_MAX_RETREATS
#define SSLR_MAX_RETREATS 1
#endif

struct SslrHit {
  vec2 uvHit;        // continuous uv of the final probe (texel centres at (i + 0.5) / size)
  float confidence;  // hit validation in [0,1] (the fades are in the weight, not here)
  float L;           // reflected ray length from P to the hit, view units
  int iterations;    // iterations run (adaptive L: each is one depth fetch)
  int status;        // SSLR_STATUS_*
  float fade;        // extra weight of the method (position buffer: the tutorial's fades), else 1
  int hierarchical;  // 1 when the hierarchical traversal ran for this pixel (alone or as fallback)
  vec2 uvGuess;      // the traversal: where the ray's current passage behind what the screen
  float LGuess;      // shows began, and its length there (0: in front; sslrHiddenGuess);
                     // adaptive L: its bracket's far end (0: no probe went behind; the uv is
                     // set by adaptive L alone's caller, sslrTraceFirstStage)
  float LResume;     // the traversal ran out of steps in front of what the screen shows: the
                     // ray's length there, where adaptive L resumes (0: it did not)
  float LSlab;       // the traversal ended inside what a pixel shows (an assumed slab): the ray's
                     // length where it went in (0: it did not)
  int guessed;       // 1: the answer is a guess where the ray went out of sight (sslrHiddenGuess,
                     // sslrSlabGuess), not a crossing: half resolution's other pixels do not reuse it
  int endedInside;   // 1: the traversal's walk ended inside what a pixel shows (sslrJudgeInside
                     // answers after it, in the second stage where that is a pass of its own)
};

// A hit record that says "nothing": the starting state of every tracer.
SSLR_FN SslrHit sslrNoHit(int status) {
  SslrHit hit;
  hit.uvHit = vec2(0.0f);
  hit.confidence = 0.0f;
  hit.L = 0.0f;
  hit.iterations = 0;
  hit.status = status;
  hit.fade = 1.0f;  // the depth-only tracers' weight; the tutorial's method sets its own
  hit.hierarchical = 0;
  hit.uvGuess = vec2(0.0f);
  hit.LGuess = 0.0f;
  hit.LResume = 0.0f;
  hit.LSlab = 0.0f;
  hit.guessed = 0;
  hit.endedInside = 0;
  return hit;
}

// Validates a candidate: the probe Q = P + R L must lie on the surface P' seen at its pixel,
// within a tolerance that grows with distance (depth precision) and with the pixel footprint
// stretched by the surface slope (pixel snapping on a steep surface moves P' along the view ray).
// Also rejects the back of surfaces and hits on the reflecting pixel itself.
// tan(angle) between a surface and the view ray that sees it, capped: a surface seen edge-on has
// no depth to speak of.
SSLR_FN float sslrSlopeTan(SslrProjection p, vec3 vsSurface, vec3 vsSurfaceNormal) {
  float cosView = abs(dot(vsSurfaceNormal, sslrViewDirection(p, vsSurface)));
  return min(sqrt(max(1.0f - cosView * cosView, 0.0f)) / max(cosView, 0.0625f), 16.0f);
}

// The traversal's role (SSLR_HIZ_*). The GPU passes get it compiled in (SSLR_HIZ_MODE, like the
// inputs in sslrDecodeNormal), so that the paths a mode never takes are not in the program; the
// C++ run reads the uniform. A stage a mode never runs is also left out of the source
// (#if SSLR_HIZ_MODE_MAY_BE(m)), so that the GLSL front end never inlines it.
SSLR_FN int sslrHiZMode(SslrTraceParams t) {
#ifdef SSLR_HIZ_MODE
  return SSLR_HIZ_MODE;
#else
  return t.hizMode;
#endif
}
#ifdef SSLR_HIZ_MODE
#define SSLR_HIZ_MODE_MAY_BE(m) (SSLR_HIZ_MODE == (m))
#else
#define SSLR_HIZ_MODE_MAY_BE(m) 1
#endif

// Whether adaptive L and the hierarchical traversal both trace (the traversal first).
SSLR_FN bool sslrHasHiZFallback(SslrTraceParams t) { return sslrHiZMode(t) == SSLR_HIZ_TRAVERSAL_FIRST; }

// Hit tolerance (view units) on a surface at view depth `dist` seen at tan(angle) `tanView`: a
// fraction of the distance (depth precision) plus pixel footprints stretched by the slope (pixel
// snapping on a steep surface moves the sample along the view ray).
SSLR_FN float sslrHitTolerance(SslrProjection p, SslrSurface s, float dist, float tanView) {
  float footprint = sslrPixelFootprint(p, s.height, sslrOrthographic(p) ? 1.0f : dist);
  return SSLR_HIT_TOLERANCE_RELATIVE * abs(dist) + SSLR_HIT_TOLERANCE_PIXELS * footprint * (1.0f + tanView);
}

// The hit tolerance at a surface point with its normal (its distance and slope as seen).
SSLR_FN float sslrSurfaceTolerance(SslrProjection p, SslrSurface s, vec3 vsSurface,
                                   vec3 vsSurfaceNormal) {
  float dist = sslrOrthographic(p) ? abs(vsSurface.z) : sslrViewDistance(p, vsSurface);
  return sslrHitTolerance(p, s, dist, sslrSlopeTan(p, vsSurface, vsSurfaceNormal));
}

SSLR_FN float sslrHitValidation(SslrProjection p, SslrSurface s, vec3 vsQ,
                                vec3 vsSurface, vec3 vsSurfaceNormal, vec3 vsR) {
  if (dot(vsSurfaceNormal, vsR) >= 0.0f) return 0.0f;  // the ray would hit the surface's back
  float tolerance = sslrSurfaceTolerance(p, s, vsSurface, vsSurfaceNormal);
  float miss = length(vsQ - vsSurface);
  return 1.0f - smoothstep(tolerance, 2.0f * tolerance, miss);
}

// How far a point vsQ lies from the tangent plane of a texel (its surface point and normal), in
// units of the hit tolerance there: below 1 the point is on that texel's surface.
SSLR_FN float sslrGapToTexelPlane(SslrProjection p, SslrSurface s, vec3 vsQ, vec3 vsTexel,
                                  vec3 vsTexelNormal) {
  return abs(dot(vsQ - vsTexel, vsTexelNormal)) / max(sslrSurfaceTolerance(p, s, vsTexel, vsTexelNormal), 1e-30f);
}

// Sub-pixel refinement (not in the article): the converged L is quantized by the pixel whose
// centre gave P'. Intersecting the ray with the tangent plane of that pixel (P', N') gives the
// exact hit on planar surfaces; it is used when it stays within the validated neighbourhood.
SSLR_FN float sslrRefineOnPlane(vec3 vsP, vec3 vsR, vec3 vsSurface, vec3 vsSurfaceNormal, float L) {
  float denom = dot(vsR, vsSurfaceNormal);
  if (!(denom < -0.05f)) return L;  // grazing or back-facing: the plane says little
  float tPlane = dot(vsSurface - vsP, vsSurfaceNormal) / denom;
  return (tPlane > 0.0f && abs(tPlane - L) <= 0.25f * L) ? tPlane : L;
}

// A window-space point: pixels and the depth key (window depth x keySign, -1 for reversed Z, so
// that a larger key is farther from the camera).
SSLR_FN vec3 sslrWindowFromView(SslrProjection p, vec2 sizePx, float keySign, vec3 vsPos) {
  vec3 ndc = sslrNdcFromView(p, vsPos);
  return vec3(sslrUvFromNdc(vec2(ndc.x, ndc.y)) * sizePx, keySign * sslrDepthFromNdcZ(p, ndc.z));
}

// The window-space direction of the ray from vsP along vsR (unnormalized): towards a second point
// of the ray, kept well in front of the camera plane (a point behind it would project to the
// wrong side); any such point gives the same window-space line. Orthographic: ~64 pixels of
// travel, so the direction keeps its precision at any scale.
SSLR_FN vec3 sslrWindowDirection(SslrProjection p, SslrSurface s, float keySign, vec3 vsP, vec3 vsR, vec3 wP) {
  float distP = sslrViewDistance(p, vsP);
  float probeL = sslrOrthographic(p) ? 64.0f * sslrPixelFootprint(p, s.height, 1.0f) : max(distP, 1e-6f);
  if (!sslrOrthographic(p) && vsR.z > 0.0f) probeL = min(probeL, 0.5f * distP / vsR.z);
  return sslrWindowFromView(p, vec2(s.width, s.height), keySign, vsP + vsR * probeL) - wP;
}

// Past a cell boundary, in pixels (exact in float up to 2^15 px).
#define SSLR_HIZ_NUDGE (1.0f / 256.0f)

// The ray's length L at window-space point o + d tRay (the traversal walks in window space).
SSLR_FN float sslrRayLengthAt(SslrProjection p, vec2 sizePx, float keySign, vec3 o, vec3 d, float tRay, vec3 vsP,
                              vec3 vsR) {
  vec3 w = o + d * tRay;
  return dot(sslrViewFromUvDepth(p, vec2(w.x, w.y) / sizePx, keySign * w.z) - vsP, vsR);
}

// The hit a candidate pixel stands for: where the ray meets the pixel's tangent plane, checked
// against the pixel it lands in. A pixel holds one depth sample, so a ray running along a surface
// seen at a grazing angle shows its crossing a few pixels late: the plane's hit is then re-planed
// once on the pixel it lands in (at most 4 px away). A silhouette the ray passes behind meets its
// plane far away: no hit. Returns the validation (sslrHitValidation) and L; a plane seen nearly
// edge-on by the ray (dot(R, N) >= -0.05) gives none.
SSLR_FN float sslrPlaneHit(SslrProjection p, SslrSurface s, ivec2 pxOrigin, vec3 vsP, vec3 vsR,
                           ivec2 px, vec3 vsSurface, vec3 vsSurfaceNormal, SSLR_OUT(float) L) {
  vec2 sizePx = vec2(s.width, s.height);
  float keySign = sslrReversedZ(s) ? -1.0f : 1.0f;
  ivec2 pxPlane = px;
  vec3 vsPlane = vsSurface;
  vec3 vsPlaneNormal = vsSurfaceNormal;
  L = 0.0f;
  for (int k = 0; k < 2; ++k) {
    float dn = dot(vsR, vsPlaneNormal);
    L = dn < -0.05f ? dot(vsPlane - vsP, vsPlaneNormal) / dn : -1.0f;
    vec3 vsQ = vsP + vsR * L;
    if (!(L > 0.0f) || sslrClipW(p, vsQ) <= 0.0f) return 0.0f;
    vec3 wQ = sslrWindowFromView(p, sizePx, keySign, vsQ);
    ivec2 pxQ = ivec2(floor(vec2(wQ.x, wQ.y)));
    ivec2 away = abs(pxQ - pxPlane);
    if (max(away.x, away.y) == 0) break;  // the hit lies in the pixel whose plane it is on
    // A contact line: another surface meets the reflecting one inside the reflecting pixel (a box
    // standing on a mirror). The hit lies on that surface's plane, a pixel away; refusing it left
    // a one-pixel row without reflection along every contact. Its length tells it from the
    // reflecting surface itself (whose own plane the ray leaves at L = 0). The plane's pixel must
    // touch the reflecting one: a plane from farther away reaches it only by extension (the
    // pixels between show something else). And the surface must rise from the reflecting one, not
    // face it (normals over 120 degrees apart): a face turned towards the mirror, a sphere's
    // underside, meets it at a point at most, and its plane extended down to the mirror is a gap
    // the ray passes through. (The reflecting surface's normal is R - V's direction.)
    if (pxQ.x == pxOrigin.x && pxQ.y == pxOrigin.y) {
      ivec2 fromOrigin = abs(pxPlane - pxOrigin);
      vec3 vsOriginNormal = normalize(vsR - sslrViewDirection(p, vsP));
      if (max(fromOrigin.x, fromOrigin.y) <= 1 && dot(vsPlaneNormal, vsOriginNormal) >= -0.5f &&
          L > 0.05f * sslrPixelFootprint(p, s.height, sslrOrthographic(p) ? 1.0f : sslrViewDistance(p, vsP)))
        break;
      return 0.0f;
    }
    // Re-planed once and still not landing in its own pixel: the surfaces disagree.
    if (k == 1 || max(away.x, away.y) > 4 || pxQ.x < 0 || pxQ.y < 0 || pxQ.x >= int(sizePx.x) ||
        pxQ.y >= int(sizePx.y))
      return 0.0f;
    pxPlane = pxQ;
    if (!sslrLoadSurface(pxPlane, vsPlane)) return 0.0f;
    if (!sslrDecodeNormal(s, sslrLoadNormal(pxPlane), vsPlaneNormal)) return 0.0f;
  }
  return sslrHitValidation(p, s, vsP + vsR * L, vsPlane, vsPlaneNormal, vsR);
}

// Fills in a tracer's final answer: the hit Q = P + R L, its uv, and the validation as the
// confidence. Confidence = how sure the hit is right; the screen-edge and camera-facing fades are
// presentation, not doubt (sslrReflectionWeights applies them).
SSLR_FN SslrHit sslrFinishHit(SslrProjection p, SslrHit hit, vec3 vsP, vec3 vsR, float L, float valid) {
  vec3 vsQ = vsP + vsR * L;
  if (sslrClipW(p, vsQ) <= 0.0f) {
    hit.status = SSLR_STATUS_OFF_SCREEN;
    return hit;
  }
  vec3 ndcQ = sslrNdcFromView(p, vsQ);
  hit.uvHit = sslrUvFromNdc(vec2(ndcQ.x, ndcQ.y));
  hit.L = L;
  // The refined hit may lie just outside the screen (its pixel was the border one): no colour.
  if (!sslrInsideUv(hit.uvHit)) {
    hit.uvHit = clamp(hit.uvHit, vec2(0.0f), vec2(1.0f));
    hit.status = SSLR_STATUS_OFF_SCREEN;
    return hit;
  }
  hit.confidence = sslrSaturate(valid);
  hit.status = hit.confidence > 0.0f ? SSLR_STATUS_HIT : SSLR_STATUS_MISS;
  return hit;
}

// Where a hit's colour is read: its uv, except for a contact line's hit (sslrPlaneHit), which
// lies inside the reflecting pixel itself. That pixel shows the mirror, not the surface standing on
// it (a box's foot, a sphere just above the floor), so its colour is read from the neighbouring
// pixel the ray heads into on screen (the larger axis of its window direction), at its centre.
SSLR_FN vec2 sslrColorUv(SslrProjection p, SslrSurface s, vec3 vsP, vec3 vsR, vec2 uvHit) {
  vec2 sizePx = vec2(s.width, s.height);
  vec3 wP = sslrWindowFromView(p, sizePx, 1.0f, vsP);
  ivec2 pxP = ivec2(floor(vec2(wP.x, wP.y)));
  ivec2 pxHit = ivec2(floor(uvHit * sizePx));
  if (pxHit.x != pxP.x || pxHit.y != pxP.y) return uvHit;
  vec3 wDir = sslrWindowDirection(p, s, 1.0f, vsP, vsR, wP);
  ivec2 step = abs(wDir.x) >= abs(wDir.y) ? ivec2(wDir.x >= 0.0f ? 1 : -1, 0) : ivec2(0, wDir.y >= 0.0f ? 1 : -1);
  ivec2 pxColor = clamp(pxP + step, ivec2(0), ivec2(int(s.width) - 1, int(s.height) - 1));
  return (vec2(pxColor) + 0.5f) / sizePx;
}

// Adaptive L's first length: long enough to move the probe initialLengthPixels on screen. A ray
// heading away from (or towards) the camera moves slowly on screen, so its first step is longer in
// view units (capped at 4x the surface's distance).
SSLR_FN float sslrAdaptiveLFirstLength(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 vsP, vec3 vsR) {
  vec2 sizePx = vec2(s.width, s.height);
  float distP = sslrOrthographic(p) ? 1.0f : sslrViewDistance(p, vsP);
  float footprintP = sslrPixelFootprint(p, s.height, distP);
  float delta = 0.01f * max(distP, footprintP);
  vec3 ndcP0 = sslrNdcFromView(p, vsP);
  vec3 vsP1 = vsP + vsR * delta;
  float pxPerUnit = 0.0f;
  if (sslrClipW(p, vsP1) > 0.0f) {
    vec3 ndcP1 = sslrNdcFromView(p, vsP1);
    pxPerUnit = length((vec2(ndcP1.x, ndcP1.y) - vec2(ndcP0.x, ndcP0.y)) * 0.5f * sizePx) / delta;
  }
  return max(t.initialLengthPixels, 0.5f) *
         (pxPerUnit > 0.0f ? min(1.0f / pxPerUnit, 4.0f * max(distP, footprintP) / max(t.initialLengthPixels, 0.5f))
                           : footprintP);
}

// What adaptive L knows of the ray: the lengths that bracket the hit, and the gaps measured there.
struct SslrBracket {
  float lo;                 // longest L seen in front of the depth surface
  float hi;                 // shortest L seen behind it (< 0: none yet)
  float gapLo, gapHi;       // signed view gaps measured at lo and hi
  float prevLo, prevGapLo;  // the free sample before lo, for the secant
  float limit;              // a length known to leave the screen or to look at the sky
  float from;               // where the iteration started (LFrom): growth is measured from there
  int retreats;
};

// A probe that left the screen or looked at the sky right after a long step from free space may
// have jumped over the hit: step back towards lo (SSLR_MAX_RETREATS times) instead of giving up.
SSLR_FN bool sslrRetreat(SSLR_INOUT(SslrBracket) b, SSLR_INOUT(float) L) {
  if (!(b.lo > 0.0f && b.hi < 0.0f && L > 1.05f * b.lo && b.retreats < SSLR_MAX_RETREATS)) return false;
  ++b.retreats;
  b.limit = L;
  L = 0.5f * (b.lo + L);
  return true;
}

// The probe at L found the signed gap `gap` (> 0: behind what its pixel shows). The reflecting
// pixel itself says nothing (it shows P): it never closes the bracket.
SSLR_FN void sslrBracketSample(SSLR_INOUT(SslrBracket) b, float L, float gap, bool ownPixel) {
  if (gap > 0.0f && !ownPixel) {
    if (b.hi < 0.0f || L < b.hi) {
      b.hi = L;
      b.gapHi = gap;
    }
  } else if (gap <= 0.0f && L > b.lo) {
    b.prevLo = b.lo;
    b.prevGapLo = b.gapLo;
    b.lo = L;
    b.gapLo = gap;
  }
}

// The next L after a probe at L whose pixel shows a surface at distance articleL from P (< 0: the
// article's update is stuck at a spurious fixed point and says nothing).
SSLR_FN float sslrAdaptiveLNext(SslrBracket b, float L, float articleL) {
  float newL;
  if (b.hi < 0.0f) {
    // No upper end yet. Two estimates of the hit, each capped at SSLR_MAX_GROWTH x L (a jump
    // to whatever far surface the probe's pixel shows overshoots nearer hits): the article's
    // step, and a secant on the gap of the last two free samples (it closes in on a surface
    // the article only crawls towards). Neither usable: double L.
    float grow = b.from + SSLR_MAX_GROWTH * (L - b.from);
    float article = articleL > b.lo ? min(articleL, grow) : -1.0f;
    float secant = -1.0f;
    if (b.prevLo > 0.0f && b.gapLo > b.prevGapLo)
      secant = min(b.lo - b.gapLo * (b.lo - b.prevLo) / (b.gapLo - b.prevGapLo), grow);
    // The article's step first; the secant only where the article is stuck or crawls
    // (less than 25% growth), and then at most 1.5 x the article's step.
    newL = article > 0.0f ? ((article < 1.25f * L && secant > article) ? min(secant, 1.5f * article) : article)
                          : secant;
    if (!(newL > L)) newL = b.from + 2.0f * (L - b.from);
    if (newL >= b.limit) newL = 0.5f * (L + b.limit);
  } else if (articleL > b.lo && articleL < b.hi) {
    newL = articleL;
  } else {
    // Regula falsi on the signed gap inside the bracket (midpoint if the gaps are degenerate).
    float denom = b.gapHi - b.gapLo;
    float f = denom > 0.0f ? clamp(-b.gapLo / denom, 0.1f, 0.9f) : 0.5f;
    newL = mix(b.lo, b.hi, f);
  }
  return newL;
}

// Adaptive L's answer for its last probe at L on pixel pxSurface (showing vsSurface): validated,
// and refined on the surface's plane (with the traversal behind it, a hit must also pass the plane
// check: a rejected one gets its second chance there).
SSLR_FN SslrHit sslrAdaptiveLAnswer(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                    vec3 vsR, SslrHit hit, float L, vec3 vsSurface, ivec2 pxSurface) {
  vec3 vsQ = vsP + vsR * L;
  vec3 vsSurfaceNormal;
  bool normalOk = sslrDecodeNormal(s, sslrLoadNormal(pxSurface), vsSurfaceNormal);
  bool selfHit = pxSurface.x == pxOrigin.x && pxSurface.y == pxOrigin.y;
  float valid = (normalOk && !selfHit && L <= t.maxDistance)
                    ? sslrHitValidation(p, s, vsQ, vsSurface, vsSurfaceNormal, vsR)
                    : 0.0f;
  if (valid > 0.0f && sslrHasHiZFallback(t) && dot(vsR, vsSurfaceNormal) < -0.05f) {
    float planeL;
    valid = sslrPlaneHit(p, s, pxOrigin, vsP, vsR, pxSurface, vsSurface, vsSurfaceNormal, planeL);
    if (valid > 0.0f) L = planeL;
  } else if (valid > 0.0f) {
    L = sslrRefineOnPlane(vsP, vsR, vsSurface, vsSurfaceNormal, L);
  }
  return sslrFinishHit(p, hit, vsP, vsR, L, valid);
}

// The article's adaptive-L iteration: Q = P + R L, project Q, read the depth there, rebuild P',
// L = |P' - P|. It is a fixed-point iteration that settles where the ray meets the depth surface.
// Guards added (docs/design-notes.md): off-screen / behind-near-plane / background exits, a
// convergence exit, a bracket safeguard, and validation of the final point (the article has none
// and always returns something).
//
// What is added to the article's update, all driven by the same one depth fetch per iteration:
// - Exit on a hit: Q lies on the surface its pixel shows (not merely |P' - P| settled).
// - Bracket: every probe tells on which side of the depth surface Q lies (in front: L too
//   short; behind: L too long). Inside a bracket [lo, hi] the article's step is taken when it
//   lands inside, else regula falsi on the signed gap.
// - Before a bracket exists the step grows L by at most SSLR_MAX_GROWTH (the article jumps to
//   whatever far surface the probe's pixel shows and overshoots nearer hits); where the
//   article's update collapses (L -> 0 onto the reflecting surface itself), settles on a
//   spurious fixed point, or crawls, a secant on the gap of the last two free samples steps on.
// - A probe that overshoots the screen from free space steps back before giving up.
// This keeps the article's fast steps where they work and converges where they oscillate or
// stall, e.g. for rays that come back towards the camera (docs/design-notes.md has the numbers).
//
// sslrTraceAdaptiveLFrom resumes the iteration at LFrom > 0, where the hierarchical traversal ran
// out of steps: the ray is known to be in front of what the screen shows up to there, so LFrom is
// the bracket's lower end, and the first step and the growth cap count from there.
SSLR_FN SslrHit sslrTraceAdaptiveLFrom(SslrProjection p, SslrSurface s, SslrTraceParams t,
                                       ivec2 pxOrigin, vec3 vsP, vec3 vsR, float LFrom) {
  SslrHit hit = sslrNoHit(SSLR_STATUS_MISS);
  vec2 sizePx = vec2(s.width, s.height);
  float L = LFrom + sslrAdaptiveLFirstLength(p, s, t, vsP + vsR * LFrom, vsR);
  SslrBracket b;
  b.lo = LFrom;
  b.hi = -1.0f;
  b.gapLo = 0.0f;
  b.gapHi = 0.0f;
  b.prevLo = 0.0f;
  b.prevGapLo = 0.0f;
  b.limit = 1e30f;
  b.from = LFrom;
  b.retreats = 0;
  vec3 vsSurface = vsP;
  ivec2 pxSurface = pxOrigin;
  for (int i = 0; i < t.maxIterations; ++i) {
    vec3 vsQ = vsP + vsR * L;
    // Behind the camera plane: treated like leaving the screen (the projection would flip).
    float wQ = sslrClipW(p, vsQ);
    vec3 ndcQ = wQ > 0.0f ? sslrNdcFromView(p, vsQ) : vec3(2.0f);
    vec2 uvQ = sslrUvFromNdc(vec2(ndcQ.x, ndcQ.y));
    float depthQ = sslrDepthFromNdcZ(p, ndcQ.z);
    // Written so that NaN fails: a probe outside the screen or the depth range (behind the
    // near plane, beyond a finite far plane) has nothing to read.
    if (!(sslrInsideUv(uvQ) && depthQ >= 0.0f && depthQ <= 1.0f)) {
      if (sslrRetreat(b, L)) continue;
      hit.status = SSLR_STATUS_OFF_SCREEN;
      return hit;
    }
    ivec2 px = sslrPixelFromUv(uvQ, sizePx);
    hit.iterations = i + 1;
    if (!sslrLoadSurface(px, vsSurface)) {  // the sky: nothing to reflect, unless a retreat finds it
      if (sslrRetreat(b, L)) continue;
      hit.status = SSLR_STATUS_SKY;
      return hit;
    }
    pxSurface = px;
    // Signed gap along the view: > 0 when Q is farther from the camera than what its pixel shows.
    float gap = vsSurface.z - vsQ.z;
    sslrBracketSample(b, L, gap, px.x == pxOrigin.x && px.y == pxOrigin.y);
    float articleL = length(vsSurface - vsP);
    // Done when Q lies on the surface its pixel shows (within the hit tolerance, without the
    // slope term; the final validation and the plane refinement do the rest).
    float distS = sslrOrthographic(p) ? abs(vsSurface.z) : -vsSurface.z;
    if (length(vsQ - vsSurface) <= sslrHitTolerance(p, s, distS, 0.0f)) break;
    // The article's update has settled (|P' - P| = L) but Q is not on the surface: a spurious
    // fixed point (the sphere of radius L around P meets the surface elsewhere). Not a hit:
    // move on with the bracket instead.
    if (abs(articleL - L) <= t.convergenceEps * L) articleL = -1.0f;
    float newL = sslrAdaptiveLNext(b, L, articleL);
#ifdef SSLR_TRACE_DEBUG_HOOK
    SSLR_TRACE_DEBUG_HOOK(i, L, b.lo, b.hi, articleL, newL, vsQ, vsSurface);
#endif
    bool bracketClosed = b.hi > 0.0f && b.hi - b.lo <= t.convergenceEps * b.hi;
    L = newL;
    if (bracketClosed) break;
  }
  if (hit.iterations == 0) return hit;
  // Where the ray went behind what the screen shows (the bracket's far end): adaptive L alone's
  // hidden guess, whose uv sslrTraceFirstStage takes (after the walk the walk's guess stands).
  hit.LGuess = max(b.hi, 0.0f);
  return sslrAdaptiveLAnswer(p, s, t, pxOrigin, vsP, vsR, hit, L, vsSurface, pxSurface);
}

SSLR_FN SslrHit sslrTraceAdaptiveL(SslrProjection p, SslrSurface s, SslrTraceParams t,
                                   ivec2 pxOrigin, vec3 vsP, vec3 vsR) {
  return sslrTraceAdaptiveLFrom(p, s, t, pxOrigin, vsP, vsR, 0.0f);
}

// What a hit contributes to its pixel (everything the pass does per pixel besides fetching).
//   coverage   how much of the pixel's specular the trace answers, 0..1: confidence x the tracer's
//              own fade x screen-edge fade x camera-facing fade (x the article's error term in
//              Classic mode). A host blends its fallback specular (probes, sky) by 1 - coverage.
//   reflection the weight applied to the hit's colour: Fresnel term x coverage, with the Fresnel
//              term reflectance x the article's Fresnel (Classic) or Schlick with F0 = reflectance;
//              coverage alone for OutputMode::Radiance (the host applies its own specular term).
//   blurWeight the roughness blur's radius / blur.maxRadiusPx (stored in the reflection's alpha).
struct SslrWeights {
  float reflection;
  float coverage;
  float blurWeight;
};

SSLR_FN SslrWeights sslrReflectionWeights(SslrProjection p, SslrSurface s, SslrTraceParams t, SslrHit hit,
                                          vec3 vsP, vec3 vsV, vec3 vsR, float cosVN, float reflectance,
                                          float roughness) {
  float distP = sslrViewDistance(p, vsP);
  bool classic = t.fresnel == SSLR_FRESNEL_CLASSIC;
  float fresnel = classic ? reflectance * sslrFresnelClassic(cosVN) : sslrFresnelSchlick(reflectance, cosVN);
  float errorWeight = classic ? sslrErrorWeight(p, vsP, hit.L, t.errorK) : 1.0f;
  float radius = sslrBlurRadiusPx(p, s.height, distP, hit.L, roughness, t.coneScale);
  SslrWeights w;
  w.coverage = sslrSaturate(hit.confidence * hit.fade * errorWeight * sslrEdgeFade(hit.uvHit, t.screenEdge) *
                            sslrCameraFacingFade(vsR, vsV, t.cameraStart, t.cameraEnd));
  // A surface rebuilt from a poisoned depth can make a fade NaN: then no reflection, not NaN.
  if (isnan(w.coverage) || isinf(w.coverage)) w.coverage = 0.0f;
  w.reflection = (t.outputRadiance != 0 ? 1.0f : fresnel) * w.coverage;
  if (isnan(w.reflection) || isinf(w.reflection)) w.reflection = 0.0f;
  w.blurWeight = t.maxRadiusPx > 0.0f ? sslrSaturate(radius / t.maxRadiusPx) : 0.0f;
  return w;
}

// The Fresnel term of a coloured F0, channel by channel: F0 x the article's term (Classic) or
// Schlick's; 1 for OutputMode::Radiance. (sslrReflectionWeights folds the grey-F0 term into
// `reflection` with the coverage.)
SSLR_FN vec3 sslrFresnelColored(SslrTraceParams t, vec3 f0, float cosVN) {
  if (t.outputRadiance != 0) return vec3(1.0f);
  if (t.fresnel == SSLR_FRESNEL_CLASSIC) return f0 * sslrFresnelClassic(cosVN);
  return vec3(sslrFresnelSchlick(f0.x, cosVN), sslrFresnelSchlick(f0.y, cosVN), sslrFresnelSchlick(f0.z, cosVN));
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_TRACE_H
