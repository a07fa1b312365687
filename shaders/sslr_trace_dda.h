// sslr_trace_dda.h - McGuire & Mara 2014, "Efficient GPU Screen-Space Ray Tracing" (JCGT 3(4)),
// written from the paper as a comparison method: a perspective-correct DDA in screen space with
// stride, jitter, a constant depth thickness and (optional) pixel-exact refinement of the last
// stride. Shared by the GPU pass and the CPU.
//
// The includer defines:  float sslrLoadDepth(ivec2 px);   (raw window depth; the paper reads a
// linear camera-space z buffer, we rebuild that z from the hardware depth at each fetch.)
#ifndef SSLR_TRACE_DDA_H
#define SSLR_TRACE_DDA_H

#include "sslr_trace.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// Camera-space z of what pixel px shows (negative in front of the camera), or -1e30 for the
// background: the paper's "sceneZMax". A background that far never overlaps a ray.
SSLR_FN float sslrDdaSceneZ(SslrProjection p, SslrSurface s, ivec2 px) {
  float depth = sslrLoadDepth(px);
  if (!sslrIsGeometryDepth(s, depth)) return -1.0e30f;
  return -sslrViewDepthFromDepth(p, depth);
}

// The paper's ray/depth-slab overlap: the ray's z extent over one step [zMin, zMax] reaches
// behind the visible surface but not deeper than thickness behind it.
SSLR_FN bool sslrDdaOverlaps(float rayZMin, float rayZMax, float sceneZ, float thickness) {
  return rayZMax >= sceneZ - thickness && rayZMin < sceneZ;
}

// One DDA sample: the ray's z extent over the step ending at (Qz, k) reaches from where the last
// step ended (prevZ, updated) to `ahead` (half a step) further: the paper's estimate, covering the pixel
// sampled; true when it overlaps that pixel's depth slab.
SSLR_FN bool sslrDdaStepOverlaps(SslrProjection p, SslrSurface s, float Qz, float k, float dQz, float dk, float ahead,
                                 ivec2 px, float thickness, SSLR_INOUT(float) prevZ) {
  float zA = prevZ;
  float zB = (dQz * ahead + Qz) / (dk * ahead + k);
  prevZ = zB;
  return sslrDdaOverlaps(min(zA, zB), max(zA, zB), sslrDdaSceneZ(p, s, px), thickness);
}

// Screen-space DDA. The ray runs from vsP along vsR for at most d.maxDistance (clipped at the near
// plane); P (pixels), Q = vs/w and k = 1/w are linear in screen space and step together, one
// depth fetch per step. Deviations from the paper's listing, each only a guard or bookkeeping:
// - the march starts one step out from the reflecting pixel (the paper leaves self-intersection
//   to the caller's origin bias) and stops at the screen border (outside there is no depth);
// - "unlimited" maxDistance is capped at 1e4 x the origin's distance (the projected end point is
//   then the direction's vanishing point to within a pixel);
// - refinement: after a hit with stride > 1 the last stride and the next are re-marched one pixel
//   at a time (the paper suggests refining by a binary search or a finer re-march; the re-march
//   keeps its exact overlap test). Without a finer hit the coarse one stands.
// The ray's segment as the DDA steps it: in pixels along the major axis (x after `permute`), with
// Q = vs / w and k = 1 / w interpolated linearly (orthographic: w = 1).
struct SslrDdaSegment {
  vec2 P0, dP;   // start and step per pixel of the major axis, in (permuted) pixels
  vec3 Q0, dQ;
  float k0, dk;
  float stepDir;  // +-1: the major axis' direction
  float end;      // the end's major coordinate times stepDir
  bool permute;   // y is the major axis
};

SSLR_FN SslrDdaSegment sslrDdaSegment(SslrProjection p, SslrSurface s, SslrDdaParams d, vec3 vsP, vec3 vsR) {
  vec2 sizePx = vec2(s.width, s.height);
  // Ray length: clipped so that the end stays in front of the near plane (perspective).
  float nearZ = sslrViewFromUvDepth(p, vec2(0.5f), sslrReversedZ(s) ? 1.0f : 0.0f).z;
  float rayLength = min(d.maxDistance, 1.0e4f * max(length(vsP), 1.0e-6f));
  if (vsP.z + vsR.z * rayLength > nearZ && vsR.z > 0.0f) rayLength = max((nearZ - vsP.z) / vsR.z, 0.0f);
  vec3 vsEnd = vsP + vsR * rayLength;

  // Homogeneous end points: P in pixels, Q = vs / w, k = 1 / w (orthographic: w = 1).
  SslrDdaSegment g;
  g.k0 = 1.0f / sslrClipW(p, vsP);
  float k1 = 1.0f / max(sslrClipW(p, vsEnd), 1.0e-30f);
  g.Q0 = vsP * g.k0;
  vec3 Q1 = vsEnd * k1;
  vec3 ndc0 = sslrNdcFromView(p, vsP);
  vec3 ndc1 = sslrNdcFromView(p, vsEnd);
  vec2 P0 = sslrUvFromNdc(vec2(ndc0.x, ndc0.y)) * sizePx;
  vec2 P1 = sslrUvFromNdc(vec2(ndc1.x, ndc1.y)) * sizePx;
  // A degenerate (single-point) segment gets a minimal extent so the DDA divides by something.
  vec2 delta0 = P1 - P0;
  if (dot(delta0, delta0) < 0.0001f) P1 += vec2(0.01f);
  vec2 delta = P1 - P0;

  // Step along the major axis: permute so that x is it.
  g.permute = abs(delta.x) < abs(delta.y);
  if (g.permute) {
    delta = vec2(delta.y, delta.x);
    P0 = vec2(P0.y, P0.x);
    P1 = vec2(P1.y, P1.x);
  }
  g.stepDir = delta.x < 0.0f ? -1.0f : 1.0f;
  float invdx = g.stepDir / delta.x;
  g.dQ = (Q1 - g.Q0) * invdx;
  g.dk = (k1 - g.k0) * invdx;
  g.dP = vec2(g.stepDir, delta.y * invdx);
  g.P0 = P0;
  g.end = P1.x * g.stepDir;
  return g;
}

SSLR_FN SslrHit sslrTraceDda(SslrProjection p, SslrSurface s, SslrDdaParams d, ivec2 pxOrigin, vec3 vsP,
                             vec3 vsR) {
  SslrHit hit = sslrNoHit(SSLR_STATUS_MISS);
  vec2 sizePx = vec2(s.width, s.height);
  SslrDdaSegment g = sslrDdaSegment(p, s, d, vsP, vsR);
  bool permute = g.permute;
  float stepDir = g.stepDir;
  vec2 dP = g.dP;
  vec3 dQ = g.dQ;
  float dk = g.dk;

  float stride = max(d.stride, 1.0f);
  // The paper's checkerboard jitter: half a stride on every other pixel hides the stride's
  // banding as noise (only meaningful with stride > 1).
  float jitter = (d.jitter != 0 && stride > 1.0f) ? float((pxOrigin.x + pxOrigin.y) & 1) * 0.5f : 0.0f;
  float start = 1.0f + jitter;  // in strides: the first sample is one stride out
  vec2 P = g.P0 + dP * stride * start;
  vec3 Q = g.Q0 + dQ * stride * start;
  float k = g.k0 + dk * stride * start;
  float end = g.end;

  float prevZ = vsP.z;  // the ray's z where the last step ended
  bool found = false;
  vec2 hitP = P;
  for (int i = 0; i < d.maxSteps; ++i) {
    if (!(P.x * stepDir <= end)) break;
    vec2 px2 = permute ? vec2(P.y, P.x) : P;
    if (!(px2.x >= 0.0f && px2.y >= 0.0f && px2.x < sizePx.x && px2.y < sizePx.y)) {
      hit.status = SSLR_STATUS_OFF_SCREEN;
      break;
    }
    hit.iterations += 1;
    if (sslrDdaStepOverlaps(p, s, Q.z, k, dQ.z, dk, stride * 0.5f, ivec2(floor(px2)), d.objectDepth, prevZ)) {
      found = true;
      hitP = P;
      break;
    }
    P += dP * stride;
    Q += dQ * stride;
    k += dk * stride;
  }

  if (found && d.refine != 0 && stride > 1.0f) {
    // Re-march one pixel at a time from the previous coarse sample.
    vec2 Pf = P - dP * stride;
    vec3 Qf = Q - dQ * stride;
    float kf = k - dk * stride;
    float prevFine = (Qf.z + dQ.z * 0.5f) / (kf + dk * 0.5f);
    // The coarse step's z extent reached half a stride past its sample, so the crossing it saw may
    // lie up to a stride beyond it: re-march two strides.
    int fineSteps = 2 * int(stride);
    for (int j = 1; j <= fineSteps; ++j) {
      Pf += dP;
      Qf += dQ;
      kf += dk;
      vec2 pxf = permute ? vec2(Pf.y, Pf.x) : Pf;
      if (!(pxf.x >= 0.0f && pxf.y >= 0.0f && pxf.x < sizePx.x && pxf.y < sizePx.y)) break;
      hit.iterations += 1;
      if (sslrDdaStepOverlaps(p, s, Qf.z, kf, dQ.z, dk, 0.5f, ivec2(floor(pxf)), d.objectDepth, prevFine)) {
        hitP = Pf;
        Q = Qf;
        k = kf;
        break;
      }
    }
  }
  if (!found) return hit;

  vec2 pxHit = permute ? vec2(hitP.y, hitP.x) : hitP;
  vec3 vsHit = Q / k;  // the ray's point at the hit step (Q.xy kept in step with Q.z above)
  hit.uvHit = clamp(pxHit / sizePx, vec2(0.0f), vec2(1.0f));
  hit.L = length(vsHit - vsP);
  hit.confidence = 1.0f;
  hit.status = SSLR_STATUS_HIT;
  return hit;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_TRACE_DDA_H
