// Pass 2, levels 0 and 1 alone (passes/pyramid.cpp runPyramid): in a frame after one that listed no
// tile, classification skips them; this pass, dispatched through the pyramid's arguments, writes
// them only when this frame lists a tile. One invocation per level-1 cell.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#include "passes/pyramid_levels01.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

void main() {
  SSLR_SET_VIEW(gl_WorkGroupID.z);  // (the dispatch's z: one a view)
  ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
  sslrWriteLevels01(cell, SSLR_GATHER_QUAD(uDepth, cell, 0), true);
}
