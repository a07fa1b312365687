// What every trace pass shares: its outputs, the G-buffer loaders (which count fetches for
// FrameStats), the configured tracer and the test of whether a pixel gets a ray.
// Tracer: the depth-only tracer (adaptive L, with the hierarchical traversal as fallback, check or
// alone: frame.trace.hizMode), or with SSLR_METHOD_POSITION_BUFFER the position-buffer march of
// "3D Game Shaders For Beginners" on a stored position texture, with SSLR_METHOD_DDA McGuire &
// Mara's screen-space DDA on the depth buffer, with SSLR_METHOD_FFX FidelityFX SSSR's
// hierarchical raymarch.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#ifdef SSLR_STOCHASTIC  // GlossyMode::Stochastic: rough pixels' rays drawn from the GGX lobe
#include "shared/ggx.h"
#endif

layout(binding = SSLR_IMAGE_REFLECTION, rgba16f) uniform writeonly SSLR_IMAGE uReflection;
// The resolved image gets the reflection too: tiles without a pixel to blur are final here,
// and the blur passes then run only over the tiles listed for them.
layout(binding = SSLR_IMAGE_RESOLVED, rgba16f) uniform writeonly SSLR_IMAGE uResolved;
// The hit record: a debug output, and what temporal reuse (SSLR_TEMPORAL_HITS) reprojects by.
#if defined(SSLR_DEBUG_OUTPUTS) || defined(SSLR_TEMPORAL_HITS)
layout(binding = SSLR_IMAGE_HIT, rgba32f) uniform writeonly SSLR_IMAGE uHit;
#endif
#ifdef SSLR_DEBUG_OUTPUTS
layout(binding = SSLR_IMAGE_ITERATIONS, r32f) uniform writeonly SSLR_IMAGE uIterations;
#endif
#ifdef SSLR_HIT_DISTANCE  // Settings::hitDistance
layout(binding = SSLR_IMAGE_HIT_DISTANCE, r32f) uniform writeonly SSLR_IMAGE uHitDistance;
#endif
#ifdef SSLR_COLLECT_STATS
layout(std430, binding = SSLR_BINDING_STATS_SSBO) buffer SslrStats {
  uint tracedPixels;
  uint fetches;
  uint hierarchicalPixels;
  uint hostCopies[SSLR_STATS_RAY_WORK - 3];  // listed and blurred tiles (copied by the host's finish pass)
  // Per trace dispatch (SSLR_RAY_WORK_*): SSLR_RAY_WORK_FIELDS counters (passes/ray_work.glsl).
  uint rayWork[SSLR_RAY_WORK_DISPATCHES * SSLR_RAY_WORK_FIELDS];
} stats;
#endif

uint gFetches = 0u;  // depth (or position) texels read by this invocation (stats)
float sslrLoadDepth(ivec2 px) {
  gFetches += 1u;
  return texelFetch(uDepth, sslrTexel(px), 0).r;
}
bool sslrLoadSurface(ivec2 px, out vec3 vsPos) {
  return sslrSurfaceFromDepth(frame.proj, frame.surface, px, sslrLoadDepth(px), vsPos);
}
vec4 sslrLoadNormal(ivec2 px) { return texelFetch(uNormal, sslrTexel(px), 0); }
#include "passes/ray_work.glsl"  // sslrCountRayWork (a no-op without SSLR_COLLECT_STATS)

#ifdef SSLR_METHOD_POSITION_BUFFER
layout(binding = SSLR_UNIT_POSITION) uniform SSLR_SAMPLER uPosition;  // view-space position, w = 1 on geometry
bool sslrLoadPosition(ivec2 px, out vec4 vsPosition) {
  gFetches += 1u;
  vsPosition = texelFetch(uPosition, sslrTexel(px), 0);
  return vsPosition.w > 0.0f;
}
#include "sslr_trace_position.h"
#elif defined(SSLR_METHOD_DDA)
#include "sslr_trace_dda.h"
#else
// The min-max depth pyramid (pass 2): mip m holds level m.
layout(binding = SSLR_UNIT_PYRAMID) uniform SSLR_SAMPLER uHiZ;
vec2 sslrLoadPyramidTexel(int level, ivec2 cell) {
  gFetches += 1u;
  return texelFetch(uHiZ, SSLR_AT(cell), level).rg;
}
#include "sslr_trace_hiz.h"
#ifdef SSLR_METHOD_FFX
#include "sslr_trace_ffx.h"
#endif
#endif

// The configured tracer for one ray from pixel px, under trace parameters t (sslrRayParams).
SslrHit sslrTraceRay(SslrTraceParams t, ivec2 px, vec3 vsP, vec3 vsV, vec3 vsR) {
#ifdef SSLR_METHOD_POSITION_BUFFER
  return sslrTracePositionBuffer(frame.proj, frame.surface, frame.positionBuffer, vsP, vsV, vsR);
#elif defined(SSLR_METHOD_DDA)
  return sslrTraceDda(frame.proj, frame.surface, frame.dda, px, vsP, vsR);
#elif defined(SSLR_METHOD_FFX)
  return sslrTraceFfx(frame.proj, frame.surface, t, px, vsP, vsR);
#else
  return sslrTraceDepthOnly(frame.proj, frame.surface, t, px, vsP, vsR);
#endif
}

// What shading pixel px needs, when it is to be traced: a reflective surface (mask, material,
// a normal that decodes) facing the camera. The position comes from depth, or from the stored
// positions for the tutorial's method.
struct SslrPixel {
  vec4 texel;     // the normal texel
  vec4 material;  // the texel of the material channels (sslrMaterialAt)
  vec3 vsP, vsN, vsV, vsR;
  float cosVN;    // dot(-V, N)
  bool stochastic;  // vsR was drawn from the lobe (GlossyMode::Stochastic), not the mirror ray
};
bool sslrPixelToTrace(ivec2 px, out SslrPixel q) {
  q.texel = sslrLoadNormal(px);
  float depth = sslrLoadDepth(px);
#ifdef SSLR_METHOD_POSITION_BUFFER
  vec4 stored;
  bool geometry = sslrLoadPosition(px, stored);
  q.vsP = stored.xyz;
#else
  bool geometry = sslrSurfaceFromDepth(frame.proj, frame.surface, px, depth, q.vsP);
#endif
  q.material = sslrMaterialAt(px, q.texel);
  if (!geometry || !sslrShouldTracePixel(px, depth, q.texel, q.material)) return false;
  sslrDecodeNormal(frame.surface, q.texel, q.vsN);
  q.vsV = sslrViewDirection(frame.proj, q.vsP);
  q.cosVN = dot(-q.vsV, q.vsN);
  if (!(q.cosVN > 0.0f)) return false;  // a normal facing away from the camera has nothing to reflect
  q.vsR = reflect(q.vsV, q.vsN);
  q.stochastic = false;
#ifdef SSLR_STOCHASTIC  // GlossyMode::Stochastic: a rough pixel's ray from its lobe, another each frame
  float roughness = sslrRoughness(frame.surface, q.material);
  q.stochastic = roughness >= frame.trace.stochasticFrom;
  if (q.stochastic)
    q.vsR = sslrGgxReflectionSample(q.vsV, q.vsN, max(roughness * roughness, 1e-4f),
                                    sslrPixelRandom(px, frame.trace.frameIndex));
#endif
  return true;
}

#ifdef SSLR_STOCHASTIC
// Whether pixel q's ray was drawn from its lobe in a frame with temporal history: it takes no guess
// (sslrRayParams).
bool sslrStochasticWithHistory(SslrPixel q) { return q.stochastic && frame.temporal.history != 0; }
#endif

// Whether pixel q's value skips the blur: such a ray, with the blur on (SSLR_STOCHASTIC_FILTER),
// which the temporal blend filters over its neighbours instead (sslrStochasticNeighbourhood in
// 5_temporal_blend.comp; docs/results/glossy.md, "0.9.3").
bool sslrFilteredByTemporalBlend(SslrPixel q) {
#ifdef SSLR_STOCHASTIC_FILTER
  return sslrStochasticWithHistory(q);
#else
  return false;
#endif
}

// The trace parameters of pixel q's ray. A ray drawn from the lobe takes no guess
// (Settings::traversal.hiddenGuess, thin objects' hits) where temporal reuse has a history: the pixel's
// colour is then the mean over the frames' rays that found something (rgb / a), which a miss leaves
// alone and a guessed colour pulls away. A frame without history (temporal reuse off, the first frame, a
// reset) keeps the guess: its one ray is all the pixel shows (docs/results/glossy.md, "0.9.1").
SslrTraceParams sslrRayParams(SslrPixel q) {
  SslrTraceParams t = frame.trace;
#ifdef SSLR_STOCHASTIC
  if (sslrStochasticWithHistory(q)) {
    t.hiddenGuess = 0.0f;
    t.thinObjectHits = 0;
  }
#endif
  return t;
}
