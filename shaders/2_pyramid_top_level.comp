// Pass 2, the pyramid's level 8 (passes/pyramid.cpp runPyramid): only a screen 2048 pixels wide or high
// or more has one; each cell reduces its 2x2 children in level 7.
#include "common/gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = SSLR_UNIT_PYRAMID) uniform SSLR_SAMPLER uHiZ;  // the pyramid: the level(s) read
layout(location = 0) uniform int uTopLevel;   // the pyramid's top level (sslrHiZLevelCount)

layout(binding = SSLR_IMAGE_PYRAMID_BLOCK, rg32f) uniform writeonly SSLR_IMAGE uLevel;  // level uTopLevel, from the one below

void main() {
  SSLR_SET_VIEW(gl_WorkGroupID.z);  // (the dispatch's z: one a view)
  ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
  // The frame's cells of the level below (past them: neutral, as in 2_pyramid_levels2to7.comp).
  int side = 1 << (uTopLevel - 1);
  ivec2 below = (ivec2(frame.surface.width, frame.surface.height) + side - 1) / side;
  vec2 m = sslrHiZEmpty();
  for (int k = 0; k < 4; ++k) {
    ivec2 c = cell * 2 + ivec2(k & 1, k >> 1);
    if (all(lessThan(c, below))) m = sslrHiZReduce(m, texelFetch(uHiZ, SSLR_AT(c), uTopLevel - 1).rg);
  }
  imageStore(uLevel, SSLR_AT(cell), vec4(m, 0.0f, 0.0f));  // (a store outside the level does nothing)
}
