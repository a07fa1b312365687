// Pass 1: tile classification. One work group per 8x8 tile: a tile with at least one pixel that
// needs tracing is appended to the tile list; all later passes run over listed tiles only, so a
// frame without reflective pixels costs this one cheap pass.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

shared uint sAnyTraced;

void main() {
  if (gl_LocalInvocationIndex == 0u) sAnyTraced = 0u;
  barrier();
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (sslrInside(px)) {
    float depth = texelFetch(uDepth, px, 0).r;
    vec4 packedNormal = texelFetch(uNormal, px, 0);
    if (sslrShouldTrace(frame.surface, frame.trace, depth, packedNormal)) atomicOr(sAnyTraced, 1u);
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u && sAnyTraced != 0u) {
    uint slot = atomicAdd(tiles.dispatchX, 1u);
    atomicAdd(tiles.drawInstances, 1u);
    tiles.tileCoords[slot] = gl_WorkGroupID.x | (gl_WorkGroupID.y << 16);
  }
}
