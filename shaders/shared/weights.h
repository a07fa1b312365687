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
  float distance = sslrOrthographic(p) ? abs(vsP.z) : length(vsP);
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
  float imageDist = sslrOrthographic(p) ? 1.0f : dist + L;
  return spread / sslrPixelFootprint(p, heightPx, imageDist);
}

// Settings::radianceClamp: `color` scaled down (hue kept) to a Rec. 709 luminance of at most
// `maxLuminance`; unchanged when that is 0 (off) or the colour is below it.
SSLR_FN vec3 sslrClampLuminance(vec3 color, float maxLuminance) {
  float luminance = dot(color, vec3(0.2126f, 0.7152f, 0.0722f));
  return maxLuminance > 0.0f && luminance > maxLuminance ? color * (maxLuminance / luminance) : color;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_WEIGHTS_H
