// The tile list written by classify.comp and consumed through indirect dispatch / draw.
#include "sslr_shared.h"

layout(std430, binding = SSLR_BINDING_TILE_SSBO) buffer SslrTiles {
  // DispatchIndirectCommand: x = number of listed tiles (incremented by classification).
  uint dispatchX;
  uint dispatchY;
  uint dispatchZ;
  // DrawArraysIndirectCommand for the composite: 6 vertices per listed tile, instanced.
  uint drawCount;
  uint drawInstances;
  uint drawFirst;
  uint drawBaseInstance;
  uint reserved;
  uint tileCoords[];  // tile x | tile y << 16
} tiles;

ivec2 sslrTileOrigin(uint index) {
  uint texel = tiles.tileCoords[index];
  return ivec2(int(texel & 0xffffu), int(texel >> 16)) * SSLR_TILE_SIZE;
}
