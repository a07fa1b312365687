// Pass 1: tile classification, one invocation per pixel: the first pixel of an 8x8 tile found to
// need tracing appends the tile to the tile list (a per-tile stamp says "listed this frame"); all
// later passes run over listed tiles only. No shared memory and no barrier: on CPU rasterizers a
// barrier splits the shader (an empty frame took 1.12x as long with the group flag and barriers,
// in an interleaved A/B).
//
// With SSLR_CLEANUP the same file is the clean-up pass, run after classification over the
// previous frame's traced tiles: those not listed again are zeroed. The outputs are never cleared
// whole: the trace writes every pixel of a listed tile, so after a frame only its listed tiles
// can be non-zero, and an empty frame after an empty frame only reads the G-buffer.
//
// With SSLR_PYRAMID_ARGS it is a one-group pass that turns the pyramid's dispatches on when a
// tile was listed. That copy is not in the classification itself: llvmpipe runs every
// instruction of a shader under lane masks, taken branch or not, and the 24-word copy there made
// classification 2.5x slower (measured).
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

#ifdef SSLR_CLEANUP
#ifdef SSLR_CLEANUP_HISTORY
// Temporal reuse, after this frame's history is stored: the tiles traced last frame and not now
// lose their history keys, so next frame finds history only where this frame stored it.
layout(binding = 2, r32f) uniform writeonly image2D uHistoryKey;
#else
layout(binding = 0, rgba16f) uniform writeonly image2D uReflection;
layout(binding = 3, rgba16f) uniform writeonly image2D uResolved;
#endif

void main() {
  uint entry = tiles.tileCoords[4u * sslrTileCapacity() + gl_WorkGroupID.x];
  uvec2 tile = uvec2(entry & 0xffffu, entry >> 16);
  if (tiles.tileCoords[sslrTileListedStamp(tile)] == uint(frame.trace.frameIndex)) return;  // traced again
  ivec2 px = ivec2(tile) * SSLR_TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;
#ifdef SSLR_CLEANUP_HISTORY
  imageStore(uHistoryKey, px, vec4(0.0f));
#else
  imageStore(uReflection, px, vec4(0.0f));
  imageStore(uResolved, px, vec4(0.0f));
#endif
}
#elif defined(SSLR_PYRAMID_ARGS)
void main() {
  // A frame that traces needs the pyramid: its dispatches get their real group counts.
  if (gl_LocalInvocationIndex == 0u && tiles.dispatchX != 0u)
    for (int i = 0; i < 3 * SSLR_HIZ_MAX_LEVELS; ++i) tiles.hizDispatch[i] = tiles.hizGroups[i];
}
#else
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (!sslrInside(px)) return;
  float depth = texelFetch(uDepth, px, 0).r;
  vec4 packedNormal = texelFetch(uNormal, px, 0);
  if (!sslrShouldTracePixel(px, depth, packedNormal, sslrMaterialAt(px, packedNormal))) return;
  uint stamp = sslrTileListedStamp(gl_WorkGroupID.xy);
  uint frameIndex = uint(frame.trace.frameIndex);
  // The plain read spares the atomic to all but the first few pixels of a listed tile.
  if (tiles.tileCoords[stamp] == frameIndex || atomicExchange(tiles.tileCoords[stamp], frameIndex) == frameIndex)
    return;
  uint slot = atomicAdd(tiles.dispatchX, 1u);
  atomicAdd(tiles.drawInstances, 1u);
  tiles.tileCoords[slot] = gl_WorkGroupID.x | (gl_WorkGroupID.y << 16);
}
#endif
