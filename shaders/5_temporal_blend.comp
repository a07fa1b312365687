// Pass 5, temporal blend (passes/temporal.cpp runTemporal; Settings::temporal), over the listed tiles:
// blends this frame's resolved output with the previous frame's, reprojected through
// FrameInputs::previousClipFromView, into the scratch image (5_temporal_store.comp copies it back: this
// pass reads history and resolved around each pixel, so it cannot write them).
// History is used where the reprojected point lands on the same surface (its key, the view depth,
// within keyTolerance on one of the four texels around it; only those texels are interpolated),
// clipped to this frame's 3x3 neighbourhood (mean +- one standard deviation: what moved or
// appeared cannot drag old colour along), then mixed in with historyWeight. Where the pixel has a
// hit, history is first looked up where the reflected image was (its virtual point, seen by the
// previous camera through the mirror plane), else where the surface was (docs/algorithm.md,
// "Temporal reuse").
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#include "shared/blur.h"
#include "shared/temporal.h"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = SSLR_UNIT_TEMPORAL_CURRENT) uniform SSLR_SAMPLER uCurrent;     // resolved: this frame, blurred
layout(binding = SSLR_UNIT_HISTORY) uniform SSLR_SAMPLER uHistory;     // the previous frame's output
layout(binding = SSLR_UNIT_HISTORY_KEY) uniform SSLR_SAMPLER uHistoryKey;  // its keys
layout(binding = SSLR_UNIT_MOTION) uniform SSLR_SAMPLER uMotion;      // optional: uv now - uv then (host motion vectors)
layout(binding = SSLR_UNIT_HIT_RECORD) uniform SSLR_SAMPLER uHitRecord;   // this frame's hits: uv, confidence, L
layout(binding = SSLR_IMAGE_TEMPORAL_OUTPUT, rgba16f) uniform writeonly SSLR_IMAGE uBlended;
#ifdef SSLR_HISTORY_CONFIDENCE  // Settings::temporal.outputConfidence
layout(binding = SSLR_IMAGE_HISTORY_CONFIDENCE, r8) uniform writeonly SSLR_IMAGE uHistoryConfidence;
#endif

// The history at uvPrevious, bilinear over the four texels around it whose key matches
// keyPrevious (the same surface); false when none does.
bool sslrHistoryAt(vec2 uvPrevious, float keyPrevious, out vec4 history) {
  SslrBilinear b = sslrBilinearTexels(uvPrevious);
  vec4 sum = vec4(0.0f);
  float weightSum = 0.0f;
  for (int i = 0; i < 4; ++i) {
    ivec2 q = b.texel[i];
    float w = b.weight[i];
    if (w > 0.0f && sslrHistoryKeyMatches(texelFetch(uHistoryKey, sslrTexel(q), 0).r, keyPrevious, frame.temporal.keyTolerance)) {
      sum += texelFetch(uHistory, sslrTexel(q), 0) * w;
      weightSum += w;
    }
  }
  history = weightSum > 1e-3f ? sum / weightSum : vec4(0.0f);
  return weightSum > 1e-3f;
}

// The history of pixel px (a traced surface; `current` this frame's value there), looked up where
// the point was last frame. fullWeight: it may take the whole historyWeight (a plane, or a pixel
// that reprojects onto itself); else a quarter.
bool sslrFindHistory(ivec2 px, vec4 current, float depth, vec4 packedNormal, out vec4 history, out bool fullWeight) {
  history = vec4(0.0f);
  fullWeight = false;
  vec3 vsP = sslrViewAtPixel(px, depth);
  // Where the surface point was: through the matrices, or the host's motion vectors when given
  // (the matrices still give the depth a static point would have had there: an object that
  // also moved in depth starts afresh).
  vec2 uvSurface;
  float keySurface;
  bool surfaceOnScreen = sslrReproject(frame.proj, frame.temporal.previousClipFromView, vsP, uvSurface, keySurface);
  bool staticSurface = true;
  if (frame.temporal.hasMotion != 0) {
    vec2 uvMoved = sslrUvFromPixel(px, sslrSizePx()) - texelFetch(uMotion, sslrTexel(px), 0).xy;
    staticSurface = length((uvMoved - uvSurface) * sslrSizePx()) < 0.5f;
    uvSurface = uvMoved;
    surfaceOnScreen = keySurface > 0.0f && sslrInsideUv(uvSurface);
  }
  // 1. A reflection in a static plane moves with its virtual point (behind the mirror), not with
  //    the mirror: look where the previous camera saw that point through the mirror plane. Only
  //    on planes (the normal one pixel right and up agrees): on a curved mirror the tangent
  //    plane sends the lookup astray.
  vec3 vsN;
  bool planar = false;
  if (sslrDecodeNormal(frame.surface, packedNormal, vsN)) {
    ivec2 maxPx = ivec2(sslrSizePx()) - 1;
    vec3 nRight, nUp;
    planar = sslrDecodeNormal(frame.surface, texelFetch(uNormal, sslrTexel(min(px + ivec2(1, 0), maxPx)), 0), nRight) &&
             sslrDecodeNormal(frame.surface, texelFetch(uNormal, sslrTexel(min(px + ivec2(0, 1), maxPx)), 0), nUp) &&
             dot(nRight, vsN) > 0.9999f && dot(nUp, vsN) > 0.9999f;
  }
  vec3 vsX;
  vec2 uvVirtual;
  float keyVirtual;
  bool found = false;
  if (current.a > 0.0f && staticSurface && planar &&
      sslrVirtualPointOnMirror(frame.temporal.previousEye, vsP, vsN, texelFetch(uHitRecord, sslrTexel(px), 0).a, vsX) &&
      sslrReproject(frame.proj, frame.temporal.previousClipFromView, vsX, uvVirtual, keyVirtual))
    found = sslrHistoryAt(uvVirtual, keyVirtual, history);
  // 2. Else the surface point itself. On a curved mirror only where this frame found a hit (a
  //    neighbour's old hit there is another reflection), or where the point reprojects onto its
  //    own texel's centre (a camera and surface standing still): that history is unresampled, the
  //    pixel's own reflection.
  bool still = surfaceOnScreen && staticSurface &&
               length((uvSurface - sslrUvFromPixel(px, sslrSizePx())) * sslrSizePx()) < 1.0f / 64.0f;
  if (!found && surfaceOnScreen && (planar || still || current.a > 0.0f))
    found = sslrHistoryAt(uvSurface, keySurface, history);
  // A curved mirror's reflection changes within a pixel, and resampled history blurs it: there
  // history gets a quarter of the weight, unless nothing was resampled (docs/design-notes.md,
  // "Temporal reuse").
  fullWeight = planar || still;
  return found;
}

// Variance clipping (Salvi 2016): history clamped to the 3x3 neighbourhood's mean +- one standard
// deviation, a tighter box than its min-max where the reflection has detail; widened to hold this
// pixel's own value (a history equal to it must pass unchanged).
vec4 sslrClipToNeighbourhood(ivec2 px, vec4 current, vec4 history) {
  ivec2 maxPx = ivec2(sslrSizePx()) - 1;
  vec4 m1 = vec4(0.0f), m2 = vec4(0.0f);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      vec4 v = texelFetch(uCurrent, sslrTexel(clamp(px + ivec2(dx, dy), ivec2(0), maxPx)), 0);
      m1 += v;
      m2 += v * v;
    }
  vec4 mean = m1 / 9.0f;
  vec4 sigma = sqrt(max(m2 / 9.0f - mean * mean, vec4(0.0f)));
  vec4 lo = min(mean - sigma, current), hi = max(mean + sigma, current);
  return clamp(history, lo, hi);
}

#ifdef SSLR_STOCHASTIC_FILTER
// Whether a traced pixel with these material channels drew its ray from its lobe.
bool sslrStochasticPixel(vec4 material) {
  return sslrRoughness(frame.surface, material) >= frame.trace.stochasticFrom;
}

// GlossyMode::Stochastic with the blur, in a frame with history: a rough pixel's one ray is not
// blurred (the trace gave it no blur weight, sslrFilteredByTemporalBlend) but averaged here with
// those of its 3x3 neighbours that drew theirs too, by the blur's tap weights (sslrBlurTapWeight2d:
// the surface's depth and normal, a Gaussian of one pixel). Temporal reuse then accumulates that
// over frames: one pass over nine pixels in place of the blur's two (docs/results/glossy.md,
// "0.9.3").
vec4 sslrStochasticNeighbourhood(ivec2 px, vec4 current, float depth, vec4 packedNormal) {
  vec3 n0;
  if (!sslrDecodeNormal(frame.surface, packedNormal, n0)) return current;
  SslrBlurCentre centre = sslrBlurCentre(frame.trace, 2.0f, abs(sslrViewAtPixel(px, depth).z), n0);
  vec4 sum = current;
  float weightSum = 1.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = px + ivec2(dx, dy);
      if ((dx == 0 && dy == 0) || !sslrInside(q)) continue;
      float depth1 = texelFetch(uDepth, sslrTexel(q), 0).r;
      vec4 normal1 = texelFetch(uNormal, sslrTexel(q), 0);
      vec4 material1 = sslrMaterialAt(q, normal1);
      vec3 n1;
      if (!sslrShouldTracePixel(q, depth1, normal1, material1) || !sslrStochasticPixel(material1) ||
          !sslrDecodeNormal(frame.surface, normal1, n1))
        continue;
      float w = sslrBlurTapWeight2d(centre, ivec2(dx, dy), abs(sslrViewAtPixel(q, depth1).z), n1);
      sum += texelFetch(uCurrent, sslrTexel(q), 0) * w;
      weightSum += w;
    }
  return sum / weightSum;
}
#endif

void main() {
  ivec2 px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;
  vec4 current = texelFetch(uCurrent, sslrTexel(px), 0);
  float historyShare = 0.0f;  // how much of `blended` is history
  float depth = texelFetch(uDepth, sslrTexel(px), 0).r;
  vec4 packedNormal = texelFetch(uNormal, sslrTexel(px), 0);
  vec4 material = sslrMaterialAt(px, packedNormal);
  bool traced = sslrShouldTracePixel(px, depth, packedNormal, material);
#ifdef SSLR_STOCHASTIC_FILTER
  if (frame.temporal.history != 0 && traced && sslrStochasticPixel(material))
    current = sslrStochasticNeighbourhood(px, current, depth, packedNormal);
#endif
  vec4 blended = current;
  vec4 history;
  bool fullWeight;
  if (frame.temporal.history != 0 && traced && sslrFindHistory(px, current, depth, packedNormal, history, fullWeight)) {
    historyShare = frame.temporal.historyWeight * (fullWeight ? 1.0f : 0.25f);
    blended = mix(current, sslrClipToNeighbourhood(px, current, history), historyShare);
  }
  imageStore(uBlended, sslrTexel(px), blended);
#ifdef SSLR_HISTORY_CONFIDENCE
  imageStore(uHistoryConfidence, sslrTexel(px), vec4(historyShare));
#endif
}
