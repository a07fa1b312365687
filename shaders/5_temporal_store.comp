// Pass 5, temporal store (passes/temporal.cpp runTemporal; Settings::temporal), over the listed tiles: the
// blended value (5_temporal_blend.comp) becomes the resolved output and the next frame's history,
// and this frame's keys (view depth where the pixel is traced) its history keys.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#include "shared/temporal.h"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = SSLR_UNIT_TEMPORAL_CURRENT) uniform SSLR_SAMPLER uBlended;
layout(binding = SSLR_IMAGE_TEMPORAL_OUTPUT, rgba16f) uniform writeonly SSLR_IMAGE uResolved;
layout(binding = SSLR_IMAGE_HISTORY, rgba16f) uniform writeonly SSLR_IMAGE uHistory;
layout(binding = SSLR_IMAGE_HISTORY_KEY, r32f) uniform writeonly SSLR_IMAGE uHistoryKey;

void main() {
  ivec2 px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;
  vec4 value = texelFetch(uBlended, sslrTexel(px), 0);
  imageStore(uResolved, sslrTexel(px), value);
  imageStore(uHistory, sslrTexel(px), value);
  float depth = texelFetch(uDepth, sslrTexel(px), 0).r;
  vec4 packedNormal = texelFetch(uNormal, sslrTexel(px), 0);
  float key = 0.0f;
  if (sslrShouldTracePixel(px, depth, packedNormal, sslrMaterialAt(px, packedNormal)))
    key = sslrHistoryKey(frame.proj, sslrViewAtPixel(px, depth));
  imageStore(uHistoryKey, sslrTexel(px), vec4(key));
}
