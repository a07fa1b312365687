// Pass 2: trace over listed tiles. Writes the reflection (rgb = hit colour x weights, a = blur
// weight) and, with SSLR_DEBUG_OUTPUTS, the hit and iteration images.
// Tracer: the depth-only tracer (adaptive L, with the hierarchical traversal as fallback or alone,
// frame.trace.hizMode), or with SSLR_METHOD_POSITION_BUFFER the position-buffer march of
// "3D Game Shaders For Beginners" on a stored position texture, or with SSLR_METHOD_DDA McGuire &
// Mara's screen-space DDA on the depth buffer.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = 0, rgba16f) uniform writeonly image2D uReflection;
// The resolved image gets the reflection too: tiles without a pixel to blur are final here,
// and the blur passes then run only over the tiles listed for them.
layout(binding = 3, rgba16f) uniform writeonly image2D uResolved;
#ifdef SSLR_DEBUG_OUTPUTS
layout(binding = 1, rgba32f) uniform writeonly image2D uHit;
layout(binding = 2, r32f) uniform writeonly image2D uIterations;
#endif
#ifdef SSLR_COLLECT_STATS
layout(std430, binding = SSLR_BINDING_STATS_SSBO) buffer SslrStats {
  uint tracedPixels;
  uint fetches;
  uint hierarchicalPixels;
} stats;
#endif

uint gFetches = 0u;  // depth (or position) texels read by this invocation (stats)
float sslrLoadDepth(ivec2 px) {
  gFetches += 1u;
  return texelFetch(uDepth, px, 0).r;
}
bool sslrLoadSurface(ivec2 px, out vec3 vsPos) {
  return sslrSurfaceFromDepth(frame.proj, frame.surface, px, sslrLoadDepth(px), vsPos);
}
vec4 sslrLoadNormal(ivec2 px) { return texelFetch(uNormal, px, 0); }

#ifdef SSLR_METHOD_POSITION_BUFFER
layout(binding = 5) uniform sampler2D uPosition;  // view-space position, w = 1 on geometry
bool sslrLoadPosition(ivec2 px, out vec4 vsPosition) {
  gFetches += 1u;
  vsPosition = texelFetch(uPosition, px, 0);
  return vsPosition.w > 0.0f;
}
#include "sslr_trace_position.h"
#elif defined(SSLR_METHOD_DDA)
#include "sslr_trace_dda.h"
#else
// The min-max depth pyramid built by hiz.comp: mip m holds level m + 1.
layout(binding = 6) uniform sampler2D uHiZ;
vec2 sslrLoadDepthMinMax(int level, ivec2 cell) {
  gFetches += 1u;
  if (level == 0) return sslrHiZTexel(frame.surface, texelFetch(uDepth, cell, 0).r);
  return texelFetch(uHiZ, cell, level - 1).rg;
}
#include "sslr_trace_hiz.h"
#endif

void main() {
  ivec2 px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;

  SslrHit hit = sslrNoHit(SSLR_STATUS_NOT_TRACED);
  vec4 reflection = vec4(0.0f);

  vec4 texel = sslrLoadNormal(px);
  float depth = sslrLoadDepth(px);
  vec3 vsP;
#ifdef SSLR_METHOD_POSITION_BUFFER
  // The position-buffer method takes its position from the stored texture, as the tutorial.
  vec4 stored;
  bool geometry = sslrLoadPosition(px, stored);
  vsP = stored.xyz;
#else
  bool geometry = sslrSurfaceFromDepth(frame.proj, frame.surface, px, depth, vsP);
#endif
  if (geometry && sslrShouldTrace(frame.surface, frame.trace, depth, texel)) {
    vec3 vsN;
    sslrDecodeNormal(frame.surface, texel, vsN);
    vec3 vsV = sslrViewDirection(frame.proj, vsP);
    float cosVN = dot(-vsV, vsN);
    if (cosVN > 0.0f) {  // a normal facing away from the camera has nothing to reflect
      vec3 vsR = reflect(vsV, vsN);
#ifdef SSLR_METHOD_POSITION_BUFFER
      hit = sslrTracePositionBuffer(frame.proj, frame.surface, frame.positionBuffer, vsP, vsV, vsR);
#elif defined(SSLR_METHOD_DDA)
      hit = sslrTraceDda(frame.proj, frame.surface, frame.dda, px, vsP, vsR);
#else
      hit = sslrTraceDepthOnly(frame.proj, frame.surface, frame.trace, px, vsP, vsR);
#endif
      if (hit.status == SSLR_STATUS_HIT) {
        vec2 w = sslrReflectionWeights(frame.proj, frame.surface, frame.trace, hit, vsP, vsV, vsR, cosVN,
                                       sslrReflectance(frame.surface, texel),
                                       sslrRoughness(frame.surface, texel));
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
  imageStore(uResolved, px, reflection);
#ifdef SSLR_DEBUG_OUTPUTS
  imageStore(uHit, px, vec4(hit.uvHit, hit.confidence, hit.L));
  imageStore(uIterations, px, vec4(float(hit.iterations)));
#endif
#ifdef SSLR_COLLECT_STATS
  if (hit.status != SSLR_STATUS_NOT_TRACED) atomicAdd(stats.tracedPixels, 1u);
  atomicAdd(stats.fetches, gFetches);
  if (hit.hierarchical != 0) atomicAdd(stats.hierarchicalPixels, 1u);
#endif
  // The first pixel of a tile that needs blurring lists the tile (no group barrier: on CPU
  // rasterizers barriers split the shader and cost more than this atomic).
  if (reflection.a * frame.trace.blurMaxRadiusPx >= 0.5f) sslrListTileForBlur(px);
}
