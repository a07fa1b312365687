// shared/half_resolution.h - Half resolution: the quad record.
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_HALF_RESOLUTION_H
#define SSLR_SHARED_HALF_RESOLUTION_H

#include "language.h"
#include "projection.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- Half resolution (Settings::halfResolution) ----------------------------------------------
// One ray per 2x2 quad; the quad's other pixels reuse its hit when they lie on the traced pixel's
// surface, and trace their own ray otherwise.

// Pixel offsets within a quad, in the order the traced pixel rotates through (one per frame).
SSLR_FN ivec2 sslrQuadOffset(int index) {
  return index == 0 ? ivec2(0, 0) : (index == 1 ? ivec2(1, 1) : (index == 2 ? ivec2(1, 0) : ivec2(0, 1)));
}

// What a quad's ray says to the quad's other pixels (the quad record's w, one float):
// SSLR_QUAD_HIT       its hit, re-planed for each of them (a record no ray wrote is this, with no hit);
// SSLR_QUAD_OWN_RAYS  adaptive L did not converge and no traversal ran: each traces its own ray
//                     (adaptive L may converge for it);
// SSLR_QUAD_MISS      no hit (the ray left the screen, met the sky, or the traversal found nothing):
//                     a miss for them too, unless a neighbouring quad's ray hit. There the miss may
//                     be a band along an edge (rays passing behind a box, beyond a mirror's end,
//                     leaving the screen just past its border) that a pixel's own ray escapes.
//                     A guess (SslrHit::guessed) is this kind with its confidence: the traced
//                     pixel shows it, the others take it as a miss's band rule allows (adaptive L
//                     alone's guess is SSLR_QUAD_OWN_RAYS with its confidence).
#define SSLR_QUAD_HIT 0
#define SSLR_QUAD_OWN_RAYS 1
#define SSLR_QUAD_MISS 2
struct SslrQuadCode {
  float confidence;  // the quad ray's, in [0, 0.999]
  int index;         // the traced pixel (sslrQuadOffset)
  int kind;          // SSLR_QUAD_*
};
// w = confidence + 2 index + 8 kind: index and kind exact, the confidence to one float step of w
// (< 2e-6), clamped below 1 so that it cannot carry into the index.
SSLR_FN float sslrPackQuadCode(float confidence, int index, int kind) {
  return min(max(confidence, 0.0f), 0.999f) + 2.0f * float(index) + 8.0f * float(kind);
}
SSLR_FN SslrQuadCode sslrUnpackQuadCode(float w) {
  SslrQuadCode c;
  c.kind = clamp(int(floor(w * 0.125f)), 0, 2);
  float rest = w - 8.0f * float(c.kind);
  c.index = clamp(int(floor(rest * 0.5f)), 0, 3);
  c.confidence = rest - 2.0f * float(c.index);
  return c;
}

// Whether P (normal N) lies on the surface of the quad's traced pixel (Pc, Nc): on its tangent
// plane within depth precision and a quarter pixel, with normals within about 1.8 degrees. Exact
// for planes whatever their slope (a depth comparison is not: a floor seen at a grazing angle
// changes depth by many percent from one pixel to the next).
SSLR_FN bool sslrSameSurface(SslrProjection p, SslrSurface s, vec3 vsP, vec3 vsN, vec3 vsPc, vec3 vsNc) {
  float dist = sslrOrthographic(p) ? abs(vsP.z) : sslrViewDistance(p, vsP);
  float tolerance = 0.002f * dist + 0.25f * sslrPixelFootprint(p, s.height, sslrOrthographic(p) ? 1.0f : dist);
  return dot(vsN, vsNc) > 0.9995f && abs(dot(vsP - vsPc, vsNc)) <= tolerance;
}

// The length along P's ray R to the plane of the quad's hit (point H, normal Nh): a neighbouring
// pixel of a plane sees the same reflected surface, shifted. A plane seen edge-on by the ray
// keeps the quad's point; a plane behind the ray gives -1 (no reuse).
SSLR_FN float sslrReusedLength(vec3 vsP, vec3 vsR, vec3 vsH, vec3 vsNh) {
  float dn = dot(vsR, vsNh);
  if (!(dn < -0.05f)) return length(vsH - vsP);
  float L = dot(vsH - vsP, vsNh) / dn;
  return L > 0.0f ? L : -1.0f;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_HALF_RESOLUTION_H
