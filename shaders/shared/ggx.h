// shared/ggx.h - The GGX lobe (stochastic glossy rays, the glossy reference).
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_GGX_H
#define SSLR_SHARED_GGX_H

#include "language.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- GGX lobe (the glossy reference, tools/truth) ----------------------------------------------
// alpha = roughness^2 (perceptual roughness, as the blur's cone). Directions in a tangent frame
// with the normal along +z.
// Smith's masking for GGX: G1(v) = 2 cos / (cos + sqrt(alpha^2 + (1 - alpha^2) cos^2)).
SSLR_FN float sslrSmithG1(float cosTheta, float alpha) {
  if (!(cosTheta > 0.0f)) return 0.0f;
  float a2 = alpha * alpha;
  return 2.0f * cosTheta / (cosTheta + sqrt(a2 + (1.0f - a2) * cosTheta * cosTheta));
}
// A microfacet normal drawn from GGX's distribution of normals visible from `ve` (unit, z > 0),
// by Heitz 2018 ("Sampling the GGX Distribution of Visible Normals", JCGT 7(4)), from two
// uniform numbers in [0, 1). Reflecting ve about it gives a light direction whose weight, for the
// lobe's mean radiance, is G1 of that direction (sslrSmithG1).
SSLR_FN vec3 sslrSampleGgxVndf(vec3 ve, float alpha, vec2 u) {
  vec3 vh = normalize(vec3(alpha * ve.x, alpha * ve.y, ve.z));  // the view in the hemisphere configuration
  float lensq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = 6.28318531f * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * p2;
  vec3 nh = t1 * p1 + t2 * p2 + vh * sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2));
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0f, nh.z)));  // back to the ellipsoid
}

// Point k of an n-point Hammersley set in [0, 1)^2 (stratified: (k + 0.5) / n, then k's bits
// reversed).
SSLR_FN vec2 sslrHammersley(int k, int n) {
  uint bits = uint(k);
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return vec2((float(k) + 0.5f) / float(n), float(bits) * 2.3283064365386963e-10f);
}

// A pixel's ray in GlossyMode::Stochastic: the reflection of the view (vsV, towards the surface)
// about a normal drawn from the lobe's visible normals around vsN; a direction below the surface
// (the lobe's masked part) falls back to the mirror ray.
SSLR_FN vec3 sslrGgxReflectionSample(vec3 vsV, vec3 vsN, float alpha, vec2 u) {
  vec3 t = normalize(abs(vsN.z) < 0.999f ? cross(vec3(0.0f, 0.0f, 1.0f), vsN) : cross(vec3(1.0f, 0.0f, 0.0f), vsN));
  vec3 b = cross(vsN, t);
  vec3 ve = vec3(dot(-vsV, t), dot(-vsV, b), dot(-vsV, vsN));
  vec3 l = reflect(-ve, sslrSampleGgxVndf(ve, alpha, u));
  if (!(l.z > 0.0f)) return reflect(vsV, vsN);
  return normalize(t * l.x + b * l.y + vsN * l.z);
}

// Integer hash (Wellons' lowbias32) and two uniform numbers in [0, 1) per pixel and frame.
SSLR_FN uint sslrHash(uint x) {
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}
SSLR_FN vec2 sslrPixelRandom(ivec2 px, int frameIndex) {
  uint h = sslrHash(uint(px.x) * 1973u + uint(px.y) * 9277u + uint(frameIndex) * 26699u);
  return vec2(float(h >> 8u), float(sslrHash(h ^ 0x9e3779b9u) >> 8u)) * (1.0f / 16777216.0f);
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_GGX_H
