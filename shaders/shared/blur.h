// shared/blur.h - The blur pass's bilateral tap weight (4_blur.comp; the stochastic filter in
// 5_temporal_blend.comp). The radius it blurs by is the trace's (weights.h, sslrBlurRadiusPx).
// Part of sslr_shared.h for C++; the GLSL passes that blur include it themselves.
#ifndef SSLR_SHARED_BLUR_H
#define SSLR_SHARED_BLUR_H

#include "language.h"
#include "frame.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

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

#endif  // SSLR_SHARED_BLUR_H
