// The clean-up passes run one group per tile traced in the previous frame (its list, kept after
// this frame's): a tile this frame did not list again gets its pixels cleared, so that after a
// frame only its listed tiles can hold non-zero values and no output is ever cleared whole. One
// invocation per pixel of the tile (SSLR_TILE_SIZE x SSLR_TILE_SIZE groups).
// This invocation's pixel, when its tile was traced last frame and not in this one.
bool sslrUntracedPixel(out ivec2 px) {
  uint entry = tiles.tileCoords[4u * sslrTileCapacity() + gl_WorkGroupID.x];
  uvec2 tile = uvec2(sslrEnterCoord(entry));
  px = ivec2(tile) * SSLR_TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  if (tiles.tileCoords[sslrTileListedStamp(tile)] == uint(frame.trace.frameIndex)) return false;  // traced again
  return sslrInside(px);
}
