// The tile list written by classification (1_classify.comp) and consumed through indirect dispatch / draw.
#include "sslr_shared.h"

layout(std430, binding = SSLR_BINDING_TILE_SSBO) buffer SslrTiles {
  SSLR_TILE_HEADER_FIELDS  // sslr_shared.h: the indirect commands and the pyramid's group counts
  // [0, cap): traced tiles; [cap, 2 cap): tiles to blur (each entry sslrPackCoord(tile), its view
  // in bits 14-15; cap: every view's tiles);
  // [2 cap, 3 cap): per tile, the frame index in which it was last listed for blurring; [3 cap,
  // 4 cap): per tile, the frame index in which classification last listed it for tracing (stamps:
  // no per-frame clear needed); [4 cap, 5 cap): the previous frame's traced tiles (copied);
  // [5 cap, 6 cap): per traced tile's slot, how many of its quads (half resolution) the quad pass
  // listed for the quad retrace pass (zeroed by classification as it lists the tile).
  uint tileCoords[];
} tiles;

uint sslrTilesX() { return (uint(frame.surface.width) + uint(SSLR_TILE_SIZE) - 1u) / uint(SSLR_TILE_SIZE); }
uint sslrTilesY() { return (uint(frame.surface.height) + uint(SSLR_TILE_SIZE) - 1u) / uint(SSLR_TILE_SIZE); }
// Tiles of one view; the lists and per-tile arrays hold every view's (every view is the same size).
uint sslrViewTiles() { return sslrTilesX() * sslrTilesY(); }
uint sslrTileCapacity() { return sslrViewTiles() * uint(SSLR_VIEWS); }
// Tile `tile` of the current view in the per-tile arrays.
uint sslrTileIndex(uvec2 tile) { return uint(sslrView) * sslrViewTiles() + tile.y * sslrTilesX() + tile.x; }

// The lists' entries: a tile's, quad's or pixel's coordinates (< 2^14) as x | view << 14 | y << 16,
// the view the current one (sslrView) when packed.
uint sslrPackCoord(ivec2 c) { return uint(c.x) | (uint(sslrView) << 14) | (uint(c.y) << 16); }
ivec2 sslrUnpackCoord(uint entry) { return ivec2(int(entry & 0x3fffu), int(entry >> 16)); }
// An entry's coordinates, its view made the current one.
ivec2 sslrEnterCoord(uint entry) {
  SSLR_SET_VIEW((entry >> 14) & 3u);
  return sslrUnpackCoord(entry);
}

// (Enters the tile's view.)
ivec2 sslrTileOriginFromEntry(uint entry) { return sslrEnterCoord(entry) * SSLR_TILE_SIZE; }
ivec2 sslrTileOrigin(uint index) { return sslrTileOriginFromEntry(tiles.tileCoords[index]); }
ivec2 sslrBlurTileOrigin(uint index) {
  return sslrTileOriginFromEntry(tiles.tileCoords[sslrTileCapacity() + index]);
}

// Quad `index` of a tile (row by row), for the passes that run one invocation per quad in groups
// of SSLR_TILE_QUADS along x alone: llvmpipe fills its SIMD lanes along x only, so 4x4 groups
// would run every batch of eight lanes half empty.
ivec2 sslrTileQuad(uint index) {
  return ivec2(int(index) % (SSLR_TILE_SIZE / 2), int(index) / (SSLR_TILE_SIZE / 2));
}

uint sslrQuadRetraceCountIndex(uint slot) { return 5u * sslrTileCapacity() + slot; }

uint sslrTileListedStamp(uvec2 tile) { return 3u * sslrTileCapacity() + sslrTileIndex(tile); }

// Appends the tile holding px to the blur list, once per frame.
void sslrListTileForBlur(ivec2 px) {
  uvec2 tile = uvec2(px) / uint(SSLR_TILE_SIZE);
  uint flag = 2u * sslrTileCapacity() + sslrTileIndex(tile);
  if (atomicExchange(tiles.tileCoords[flag], uint(frame.trace.frameIndex)) != uint(frame.trace.frameIndex)) {
    uint slot = atomicAdd(tiles.blurDispatchX, 1u);
    tiles.tileCoords[sslrTileCapacity() + slot] = sslrPackCoord(ivec2(tile));
  }
}
