// Pass 1, classification (passes/classify.cpp runClassify), DeviceProfile::Gpu's shape: the outputs of
// 1_classify.comp (the tile list; with SSLR_CLASSIFY_LEVEL1 the pyramid's levels 0 and 1), from a
// group per 2x2 tiles (64 invocations: no half-empty warp). After a barrier each tile knows
// whether it was listed, and a tile traced last frame and not now clears its pixels of the
// outputs here; the first tile listed sets the pyramid's dispatches (SSLR_CLASSIFY_ARGS). One
// dispatch and one barrier where Software has three of each.
#include "passes/classify_tiles.glsl"

#define SSLR_CLASSIFY_TILES 4  // 2x2 tiles a group
layout(binding = SSLR_IMAGE_CLASSIFY_REFLECTION, rgba16f) uniform writeonly SSLR_IMAGE uReflection;
layout(binding = SSLR_IMAGE_CLASSIFY_RESOLVED, rgba16f) uniform writeonly SSLR_IMAGE uResolved;
shared uint sTileListed[SSLR_CLASSIFY_TILES];

layout(local_size_x = SSLR_CLASSIFY_TILES * SSLR_TILE_QUADS) in;  // the tiles' quads (sslrTileQuad)

// The clean-up of 1_clear_untraced.comp for this quad's pixels: zeros where the tile was traced in
// the previous frame (its stamp holds that frame's index: not overwritten, as this frame did not
// list it) and is not listed in this one.
void clearIfUntraced(uvec2 tile, ivec2 cell, bool listed) {
  uint frameIndex = uint(frame.trace.frameIndex);
  uint previous = frameIndex == 1u ? 0x7fffffffu : frameIndex - 1u;  // dispatch() wraps the index to 1
  if (listed || tiles.tileCoords[sslrTileListedStamp(tile)] != previous) return;
  for (int i = 0; i < 4; ++i) {
    ivec2 px = cell * 2 + ivec2(i & 1, i >> 1);
    if (!sslrInside(px)) continue;
    imageStore(uReflection, sslrTexel(px), vec4(0.0f));
    imageStore(uResolved, sslrTexel(px), vec4(0.0f));
  }
}

void main() {
  SSLR_SET_VIEW(gl_WorkGroupID.z);  // (the dispatch's z: one a view)
  uint tileInGroup = gl_LocalInvocationIndex / uint(SSLR_TILE_QUADS);
  uvec2 tile = gl_WorkGroupID.xy * 2u + uvec2(tileInGroup & 1u, tileInGroup >> 1);
  ivec2 cell = ivec2(tile) * (SSLR_TILE_SIZE / 2) + sslrTileQuad(gl_LocalInvocationIndex % uint(SSLR_TILE_QUADS));
  // The grid's last row and column of groups may hold tiles past the screen: they do nothing but
  // take part in the barriers.
  bool onGrid = tile.x < sslrTilesX() && tile.y < sslrTilesY();
  if (gl_LocalInvocationIndex % uint(SSLR_TILE_QUADS) == 0u) sTileListed[tileInGroup] = 0u;
  barrier();
  bool trace = onGrid && classifyQuad(cell, true);
  uint slot;
  if (trace && listTile(tile, slot)) {
    if ((slot & 3u) == 0u) atomicAdd(tiles.quadDispatchX, 1u);  // half resolution's quad pass: 4 tiles a group
#ifdef SSLR_CLASSIFY_ARGS
    // The frame traces: the pyramid's dispatches get their group counts (else they stay at zero).
    if (slot == 0u)
      for (int i = 0; i < 3 * SSLR_HIZ_MAX_LEVELS; ++i) tiles.hizDispatch[i] = tiles.hizGroups[i];
#endif
  }
  if (trace) atomicOr(sTileListed[tileInGroup], 1u);
  memoryBarrierShared();
  barrier();
  if (onGrid) clearIfUntraced(tile, cell, sTileListed[tileInGroup] != 0u);
}
