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

struct SslrHit {
  vec2 uvHit;        // continuous uv of the final probe (texel centres at (i + 0.5) / size)
  float confidence;  // hit validation x edge fade x camera-facing fade, in [0,1]
  float L;           // reflected ray length from P to the hit, view units
  int iterations;    // adaptive-L iterations run (each is one depth fetch)
  int status;        // SSLR_STATUS_*
};

// Validates a candidate: the probe Q = P + R L must lie on the surface P' seen at its pixel,
// within a tolerance that grows with distance (depth precision) and with the pixel footprint
// stretched by the surface slope (pixel snapping on a steep surface moves P' along the view ray).
// Also rejects the back of surfaces and hits on the reflecting pixel itself.
SSLR_FN float sslrHitValidation(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 vsQ,
                                vec3 vsSurface, vec3 vsR, ivec2 pxSurface, ivec2 pxOrigin) {
  if (pxSurface.x == pxOrigin.x && pxSurface.y == pxOrigin.y) return 0.0f;
  vec3 vsHitNormal;
  if (!sslrDecodeNormal(s, sslrLoadNormal(pxSurface), vsHitNormal)) return 0.0f;
  if (dot(vsHitNormal, vsR) >= 0.0f) return 0.0f;  // the ray would hit the surface's back side
  vec3 vsViewAtHit = sslrViewDirection(p, vsSurface);
  float cosView = abs(dot(vsHitNormal, vsViewAtHit));
  // tan(angle) of the surface seen from the camera, capped: a surface seen edge-on has no depth.
  float tanView = min(sqrt(max(1.0f - cosView * cosView, 0.0f)) / max(cosView, 0.0625f), 16.0f);
  float dist = sslrViewDistance(p, vsSurface);
  float footprint = sslrPixelFootprint(p, s.height, p.orthographic != 0 ? 1.0f : dist);
  float tolerance = t.thicknessRelative * (p.orthographic != 0 ? abs(vsSurface.z) : dist) +
                    t.thicknessPixels * footprint * (1.0f + tanView);
  float miss = length(vsQ - vsSurface);
  return 1.0f - smoothstep(tolerance, 2.0f * tolerance, miss);
}

// The article's adaptive-L iteration: Q = P + R L, project Q, read the depth there, rebuild P',
// L = |P' - P|. It is a fixed-point iteration that settles where the ray meets the depth surface.
// Guards added: off-screen / behind-near-plane / background exits, a convergence exit, and
// validation of the final point (the article has none and always returns something).
SSLR_FN SslrHit sslrTraceAdaptiveL(SslrProjection p, SslrSurface s, SslrTraceParams t,
                                   ivec2 pxOrigin, vec3 vsP, vec3 vsV, vec3 vsR) {
  SslrHit hit;
  hit.uvHit = vec2(0.0f);
  hit.confidence = 0.0f;
  hit.L = 0.0f;
  hit.iterations = 0;
  hit.status = SSLR_STATUS_MISS;

  vec2 sizePx = vec2(s.width, s.height);
  float distP = p.orthographic != 0 ? 1.0f : sslrViewDistance(p, vsP);
  float L = max(t.initialLengthPixels, 0.5f) * sslrPixelFootprint(p, s.height, distP);
  vec3 vsSurface = vsP;
  ivec2 pxSurface = pxOrigin;
  for (int i = 0; i < t.maxIterations; ++i) {
    vec3 vsQ = vsP + vsR * L;
    if (sslrClipW(p, vsQ) <= 0.0f) {
      hit.status = SSLR_STATUS_OFF_SCREEN;
      return hit;
    }
    vec3 ndcQ = sslrNdcFromView(p, vsQ);
    vec2 uvQ = sslrUvFromNdc(vec2(ndcQ.x, ndcQ.y));
    float depthQ = sslrDepthFromNdcZ(p, ndcQ.z);
    // Written so that NaN fails: a probe outside the screen or the depth range (behind the
    // near plane, beyond a finite far plane) has nothing to read.
    if (!(uvQ.x >= 0.0f && uvQ.x <= 1.0f && uvQ.y >= 0.0f && uvQ.y <= 1.0f && depthQ >= 0.0f &&
          depthQ <= 1.0f)) {
      hit.status = SSLR_STATUS_OFF_SCREEN;
      return hit;
    }
    ivec2 px = sslrPixelFromUv(uvQ, sizePx);
    float depth = sslrLoadDepth(px);
    hit.iterations = i + 1;
    if (!sslrIsGeometryDepth(s, depth)) {
      hit.status = SSLR_STATUS_MISS;  // the probe looks at the sky: nothing to reflect
      return hit;
    }
    vsSurface = sslrViewFromUvDepth(p, sslrUvFromPixel(px, sizePx), depth);
    pxSurface = px;
    float newL = length(vsSurface - vsP);
    bool converged = abs(newL - L) <= t.convergenceEps * L;
    L = newL;
    if (converged) break;
  }
  if (hit.iterations == 0) return hit;

  vec3 vsQ = vsP + vsR * L;
  if (sslrClipW(p, vsQ) <= 0.0f) {
    hit.status = SSLR_STATUS_OFF_SCREEN;
    return hit;
  }
  vec3 ndcQ = sslrNdcFromView(p, vsQ);
  hit.uvHit = sslrUvFromNdc(vec2(ndcQ.x, ndcQ.y));
  hit.L = L;
  float valid = L <= t.maxDistance
                    ? sslrHitValidation(p, s, t, vsQ, vsSurface, vsR, pxSurface, pxOrigin)
                    : 0.0f;
  float fades = sslrEdgeFade(hit.uvHit, t.edgeFade) *
                sslrCameraFacingFade(vsR, vsV, t.cameraFadeStart, t.cameraFadeEnd);
  hit.confidence = sslrSaturate(valid * fades);
  hit.status = hit.confidence > 0.0f ? SSLR_STATUS_HIT : SSLR_STATUS_MISS;
  return hit;
}

// Everything the pass does per pixel besides fetching: returns rgb weight (applied to the hit's
// colour) in .x and the blur alpha in .y, given the traced hit and the pixel's material.
// classic: reflectance * article Fresnel * article error term; schlick: Schlick(F0 = reflectance).
SSLR_FN vec2 sslrReflectionWeights(SslrProjection p, SslrSurface s, SslrTraceParams t, SslrHit hit,
                                   float cosVN, float reflectance, float roughness, float distP) {
  float fresnel = t.fresnelMode == SSLR_FRESNEL_CLASSIC
                      ? reflectance * sslrFresnelClassic(cosVN) * sslrErrorWeight(hit.L, t.errorK)
                      : sslrFresnelSchlick(reflectance, cosVN);
  float radius = sslrBlurRadiusPx(p, s.height, distP, hit.L, roughness, t.blurConeScale);
  float alpha = t.blurMaxRadiusPx > 0.0f ? sslrSaturate(radius / t.blurMaxRadiusPx) : 0.0f;
  return vec2(fresnel * hit.confidence, alpha);
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_TRACE_H
