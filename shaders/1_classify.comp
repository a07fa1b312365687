// Pass 1, classification (passes/classify.cpp runClassify), DeviceProfile::Software's shape: one
// invocation per 2x2 quad, a group per tile (16 invocations along x: llvmpipe fills its SIMD lanes
// along x), no shared memory and no barrier (on CPU rasterizers a barrier splits the shader). The
// first quad of a tile found to need tracing appends the tile to the tile list (a per-tile stamp
// says "listed this frame"); every later pass runs over listed tiles only. With
// SSLR_CLASSIFY_LEVEL1 (the pyramid is on) each quad also writes the pyramid's levels 0 and 1
// from the depths it reads anyway (passes/pyramid_levels01.glsl). The clean-up
// (1_clear_untraced.comp) and the pyramid's arguments (2_pyramid_arguments.comp) are passes of
// their own; 1_classify_wide.comp does both inside one dispatch, with the same outputs.
#include "passes/classify_tiles.glsl"

layout(local_size_x = SSLR_TILE_QUADS) in;  // the tile's quads (sslrTileQuad)

void main() {
  SSLR_SET_VIEW(gl_WorkGroupID.z);  // (the dispatch's z: one a view)
  uvec2 tile = gl_WorkGroupID.xy;
  ivec2 cell = ivec2(tile) * (SSLR_TILE_SIZE / 2) + sslrTileQuad(gl_LocalInvocationIndex);
  uint slot;
  if (classifyQuad(cell, false)) listTile(tile, slot);
}
