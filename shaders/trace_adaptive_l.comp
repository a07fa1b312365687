// Pass 2: the adaptive-L trace over listed tiles. Writes the reflection (rgb = hit colour x
// weights, a = blur weight) and, with SSLR_DEBUG_OUTPUTS, the hit and iteration images.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = 0, rgba16f) uniform writeonly image2D uReflection;
#ifdef SSLR_DEBUG_OUTPUTS
layout(binding = 1, rgba32f) uniform writeonly image2D uHit;
layout(binding = 2, r32f) uniform writeonly image2D uIterations;
#endif
#ifdef SSLR_COLLECT_STATS
layout(std430, binding = SSLR_BINDING_STATS_SSBO) buffer SslrStats {
  uint tracedPixels;
  uint depthFetches;
} stats;
#endif

uint gDepthFetches = 0u;
float sslrLoadDepth(ivec2 px) {
  gDepthFetches += 1u;
  return texelFetch(uDepth, px, 0).r;
}
vec4 sslrLoadNormal(ivec2 px) { return texelFetch(uNormal, px, 0); }

#include "sslr_trace.h"

void main() {
  ivec2 px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;

  SslrHit hit;
  hit.uvHit = vec2(0.0f);
  hit.confidence = 0.0f;
  hit.L = 0.0f;
  hit.iterations = 0;
  hit.status = SSLR_STATUS_NOT_TRACED;
  vec4 reflection = vec4(0.0f);

  float depth = sslrLoadDepth(px);
  vec4 packedNormal = sslrLoadNormal(px);
  if (sslrShouldTrace(frame.surface, frame.trace, depth, packedNormal)) {
    vec3 vsN;
    sslrDecodeNormal(frame.surface, packedNormal, vsN);
    vec3 vsP = sslrViewAtPixel(px, depth);
    vec3 vsV = sslrViewDirection(frame.proj, vsP);
    float cosVN = dot(-vsV, vsN);
    if (cosVN > 0.0f) {  // a normal facing away from the camera has nothing to reflect
      vec3 vsR = reflect(vsV, vsN);
      hit = sslrTraceAdaptiveL(frame.proj, frame.surface, frame.trace, px, vsP, vsV, vsR);
      if (hit.status == SSLR_STATUS_HIT) {
        float distP = sslrViewDistance(frame.proj, vsP);
        vec2 w = sslrReflectionWeights(frame.proj, frame.surface, frame.trace, hit, cosVN,
                                       sslrReflectance(frame.surface, packedNormal),
                                       sslrRoughness(frame.surface, packedNormal), distP);
        vec3 color = textureLod(uColor, hit.uvHit, 0.0f).rgb;
        // Poisoned colour must not spread through the blur: NaN/Inf become 0, and the value is
        // kept inside RGBA16F's range.
        if (any(isnan(color)) || any(isinf(color))) color = vec3(0.0f);
        color = clamp(color, vec3(0.0f), vec3(60000.0f));
        reflection = vec4(color * w.x, w.y);
      }
    }
  }
  imageStore(uReflection, px, reflection);
#ifdef SSLR_DEBUG_OUTPUTS
  imageStore(uHit, px, vec4(hit.uvHit, hit.confidence, hit.L));
  imageStore(uIterations, px, vec4(float(hit.iterations)));
#endif
#ifdef SSLR_COLLECT_STATS
  if (hit.status != SSLR_STATUS_NOT_TRACED) atomicAdd(stats.tracedPixels, 1u);
  atomicAdd(stats.depthFetches, gDepthFetches);
#endif
}
