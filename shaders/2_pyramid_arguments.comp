// Pass 2, the pyramid's arguments (passes/pyramid.cpp runPyramid): one group. In a frame that lists a
// tile, the pyramid's indirect dispatches (and the curved pass's) get their real group counts;
// otherwise they stay at zero groups. A pass of its own because llvmpipe runs every instruction
// of a shader under lane masks: the copy inside classification cost every quad.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#if defined(SSLR_CURVED_SOLIDS) && SSLR_CURVED_SOLIDS
#include "passes/curved_quads.glsl"
#endif

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

void main() {
  if (gl_LocalInvocationIndex == 0u && tiles.dispatchX != 0u) {
    for (int i = 0; i < 3 * SSLR_HIZ_MAX_LEVELS; ++i) tiles.hizDispatch[i] = tiles.hizGroups[i];
#if defined(SSLR_CURVED_SOLIDS) && SSLR_CURVED_SOLIDS
    curved.dispatchX = curved.groups;
#endif
  }
}
