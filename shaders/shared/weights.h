// shared/weights.h - Weights: Fresnel, fades, coverage and the blur weight.
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_WEIGHTS_H
#define SSLR_SHARED_WEIGHTS_H

#include "language.h"
#include "projection.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- Weights ------------------------------------------------------------------------------
// cosVN = dot(-V, N) = cosine of the angle between the normal and the direction to the camera.
// The article writes 2.8 * pow(1 + dot(V, N), 2) with V pointing into the surface: the same.
SSLR_FN float sslrFresnelClassic(float cosVN) {
  float x = 1.0f - sslrSaturate(cosVN);
  return sslrSaturate(2.8f * x * x);
}
SSLR_FN float sslrFresnelSchlick(float f0, float cosVN) {
  float x = 1.0f - sslrSaturate(cosVN);
  float x2 = x * x;
  return f0 + (1.0f - f0) * x2 * x2 * x;
}
// The article's error term, long reflections fade out: 1 - saturate(L k). The article's L is in
// world units, so its k ties the look to the scene's unit (a scene modelled in centimetres loses
// its reflections). Here L is measured relative to the reflecting point's distance from the
// camera (orthographic: its depth), which is the same at every scale.
SSLR_FN float sslrErrorWeight(SslrProjection p, vec3 vsP, float L, float k) {
  float distance = p.orthographic != 0 ? abs(vsP.z) : length(vsP);
  return 1.0f - sslrSaturate(L / max(distance, 1e-30f) * k);
}

// 1 inside, falling linearly to 0 over `width` (fraction of the screen) at each border.
SSLR_FN float sslrEdgeFade(vec2 uv, float width) {
  if (width <= 0.0f) return sslrInsideUv(uv) ? 1.0f : 0.0f;
  vec2 d = min(uv, 1.0f - uv) / width;
  return sslrSaturate(min(d.x, d.y));
}

// Rays heading back towards the camera see the back of what the screen shows: fade them. The fade
// is presentation (it weights the colour), never part of the hit decision or its confidence.
SSLR_FN float sslrCameraFacingFade(vec3 vsR, vec3 vsV, float start, float end) {
  float towardsCamera = dot(vsR, -vsV);
  return 1.0f - smoothstep(start, max(end, start + 1e-4f), towardsCamera);
}

// Blur radius in pixels for a reflection of length L seen from a surface at view distance
// `dist`: a cone of tan(half angle) = roughness^2 * coneScale spreads to L * tan at the hit,
// which the camera sees at the mirror image's distance dist + L.
SSLR_FN float sslrBlurRadiusPx(SslrProjection p, float heightPx, float dist, float L,
                               float roughness, float coneScale) {
  float spread = L * roughness * roughness * coneScale;
  float imageDist = p.orthographic != 0 ? 1.0f : dist + L;
  return spread / sslrPixelFootprint(p, heightPx, imageDist);
}

// The blur pass's bilateral weight of a neighbour `offsetPx` pixels away along the blur's axis,
// for a centre pixel of blur radius `radiusPx` (>= 0.5) at view distance z0 with normal n0 and a
// neighbour at z1 with n1:
//   exp(-offset^2 / (2 sigma^2)) * exp(-|z1 - z0| / (blur.depthSigma z0)) * max(0, n0.n1)^blur.normalPower
// with sigma = max(radius / 2, 0.5): a Gaussian, a depth term relative to the centre's distance (so
// the same surface step counts the same near and far) and a normal term, so a reflection does not
// bleed across an edge or a crease. Evaluated as one exp2 of a sum of logarithms (one exp2 and one
// log2 per tap, not two exps and a pow); the per-centre factors are computed once per pixel.
struct SslrBlurCentre {
  float gaussianLog2;  // log2(e) * -1 / (2 sigma^2): times offset^2
  float depthLog2;     // log2(e) * -1 / (blur.depthSigma z0): times |z1 - z0|
  float z;             // view distance z0
  float normalPower;   // blur.normalPower
  vec3 normal;         // n0
};

SSLR_FN SslrBlurCentre sslrBlurCentre(SslrTraceParams t, float radiusPx, float z0, vec3 n0) {
  const float log2e = 1.44269504f;
  float sigma = max(radiusPx * 0.5f, 0.5f);
  SslrBlurCentre c;
  c.gaussianLog2 = -0.5f * log2e / (sigma * sigma);
  c.depthLog2 = -log2e / max(t.depthSigma * z0, 1e-6f);
  c.z = z0;
  c.normalPower = t.normalPower;
  c.normal = n0;
  return c;
}

// Settings::radianceClamp: `color` scaled down (hue kept) to a Rec. 709 luminance of at most
// `maxLuminance`; unchanged when that is 0 (off) or the colour is below it.
SSLR_FN vec3 sslrClampLuminance(vec3 color, float maxLuminance) {
  float luminance = dot(color, vec3(0.2126f, 0.7152f, 0.0722f));
  return maxLuminance > 0.0f && luminance > maxLuminance ? color * (maxLuminance / luminance) : color;
}

// One tap's weight in the blur's sum (not the "blur weight", the reflection's alpha that sets
// the radius): Gaussian in the offset, falling with the depth and normal differences. For a tap
// `offset` pixels away in both axes (the stochastic mode's filter in the temporal blend,
// 5_temporal_blend.comp) the Gaussian is in the squared distance.
SSLR_FN float sslrBlurTapWeight2d(SslrBlurCentre c, ivec2 offset, float z1, vec3 n1) {
  float normalLog2 = 0.0f;  // blur.normalPower 0: no normal term
  if (c.normalPower > 0.0f) {
    float cosine = dot(c.normal, n1);
    if (!(cosine > 0.0f)) return 0.0f;  // max(0, n0.n1)^power = 0 (log2 would be undefined)
    normalLog2 = c.normalPower * log2(cosine);
  }
  return exp2(c.gaussianLog2 * float(offset.x * offset.x + offset.y * offset.y) + c.depthLog2 * abs(z1 - c.z) +
              normalLog2);
}
SSLR_FN float sslrBlurTapWeight(SslrBlurCentre c, int offsetPx, float z1, vec3 n1) {
  return sslrBlurTapWeight2d(c, ivec2(offsetPx, 0), z1, n1);
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_WEIGHTS_H
