// Pass 2, the pyramid's levels 2 to 7 (passes/pyramid.cpp runPyramid; sslr_shared.h, "Min-max depth
// pyramid"): each cell is the (min, max) raw depth of its 2x2 children. One dispatch: each work
// group takes one level-7 cell, a 64x64 block of level-1 cells (128x128 pixels). Each of its 8x8
// invocations reduces an 8x8 block of level 1 into its level-4 cell, writing the 16 level-2 and
// 4 level-3 cells on the way; the level-4 cells then meet in shared memory for levels 5, 6 and 7.
// Levels 0 and 1 are classification's; a level 8 (a screen 2048 pixels or more across) is
// 2_pyramid_top_level.comp's.
#include "common/gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = SSLR_UNIT_PYRAMID) uniform SSLR_SAMPLER uHiZ;  // the pyramid: the level(s) read
layout(location = 0) uniform int uTopLevel;   // the pyramid's top level (sslrHiZLevelCount)

// Levels 2..7 (a level above the top is bound to the top's image and never stored to). Stores
// outside a level's image do nothing: a group's block may reach past the (padded) screen.
layout(binding = SSLR_IMAGE_PYRAMID_BLOCK + 0, rg32f) uniform writeonly SSLR_IMAGE uLevel2;
layout(binding = SSLR_IMAGE_PYRAMID_BLOCK + 1, rg32f) uniform writeonly SSLR_IMAGE uLevel3;
layout(binding = SSLR_IMAGE_PYRAMID_BLOCK + 2, rg32f) uniform writeonly SSLR_IMAGE uLevel4;
layout(binding = SSLR_IMAGE_PYRAMID_BLOCK + 3, rg32f) uniform writeonly SSLR_IMAGE uLevel5;
layout(binding = SSLR_IMAGE_PYRAMID_BLOCK + 4, rg32f) uniform writeonly SSLR_IMAGE uLevel6;
layout(binding = SSLR_IMAGE_PYRAMID_BLOCK + 5, rg32f) uniform writeonly SSLR_IMAGE uLevel7;

shared vec2 sLevel4[8][8];
shared vec2 sLevel5[4][4];
shared vec2 sLevel6[2][2];

// A level-1 cell; past the frame's cells (`size`) neutral: the texture's padding, and under a
// FrameInputs::viewport smaller than the textures whatever a larger frame left there. The size is passed, not
// kept in a global set by main(): Mesa's compiler warns of a global read before it is set (a
// KHR_debug message of high severity on a fresh compile).
vec2 level1(ivec2 c, ivec2 size) {
  return all(lessThan(c, size)) ? texelFetch(uHiZ, SSLR_AT(c), 1).rg : sslrHiZEmpty();
}
vec2 reduce4(vec2 a, vec2 b, vec2 c, vec2 d) { return sslrHiZReduce(sslrHiZReduce(a, b), sslrHiZReduce(c, d)); }

void main() {
  SSLR_SET_VIEW(gl_WorkGroupID.z);  // (the dispatch's z: one a view)
  ivec2 level1Size = (ivec2(frame.surface.width, frame.surface.height) + 1) / 2;
  ivec2 local = ivec2(gl_LocalInvocationID.xy);
  ivec2 cell4 = ivec2(gl_WorkGroupID.xy) * 8 + local;
  vec2 m4 = sslrHiZEmpty();
  for (int j = 0; j < 4; ++j) {  // the four level-3 cells of this level-4 cell
    ivec2 cell3 = cell4 * 2 + ivec2(j & 1, j >> 1);
    vec2 m3 = sslrHiZEmpty();
    for (int k = 0; k < 4; ++k) {  // the four level-2 cells of that level-3 cell
      ivec2 cell2 = cell3 * 2 + ivec2(k & 1, k >> 1);
      ivec2 c = cell2 * 2;
      vec2 m2 = reduce4(level1(c, level1Size), level1(c + ivec2(1, 0), level1Size), level1(c + ivec2(0, 1), level1Size),
                        level1(c + ivec2(1, 1), level1Size));
      imageStore(uLevel2, SSLR_AT(cell2), vec4(m2, 0.0f, 0.0f));
      m3 = sslrHiZReduce(m3, m2);
    }
    if (uTopLevel >= 3) imageStore(uLevel3, SSLR_AT(cell3), vec4(m3, 0.0f, 0.0f));
    m4 = sslrHiZReduce(m4, m3);
  }
  if (uTopLevel >= 4) imageStore(uLevel4, SSLR_AT(cell4), vec4(m4, 0.0f, 0.0f));
  // Levels 5..7 from shared memory (barriers outside any branch, as GLSL requires).
  sLevel4[local.y][local.x] = m4;
  barrier();
  if (all(lessThan(local, ivec2(4)))) {
    ivec2 c = local * 2;
    vec2 m5 = reduce4(sLevel4[c.y][c.x], sLevel4[c.y][c.x + 1], sLevel4[c.y + 1][c.x], sLevel4[c.y + 1][c.x + 1]);
    if (uTopLevel >= 5) imageStore(uLevel5, SSLR_AT(ivec2(gl_WorkGroupID.xy) * 4 + local), vec4(m5, 0.0f, 0.0f));
    sLevel5[local.y][local.x] = m5;
  }
  barrier();
  if (all(lessThan(local, ivec2(2)))) {
    ivec2 c = local * 2;
    vec2 m6 = reduce4(sLevel5[c.y][c.x], sLevel5[c.y][c.x + 1], sLevel5[c.y + 1][c.x], sLevel5[c.y + 1][c.x + 1]);
    if (uTopLevel >= 6) imageStore(uLevel6, SSLR_AT(ivec2(gl_WorkGroupID.xy) * 2 + local), vec4(m6, 0.0f, 0.0f));
    sLevel6[local.y][local.x] = m6;
  }
  barrier();
  if (local == ivec2(0) && uTopLevel >= 7) {
    vec2 m7 = reduce4(sLevel6[0][0], sLevel6[0][1], sLevel6[1][0], sLevel6[1][1]);
    imageStore(uLevel7, SSLR_AT(ivec2(gl_WorkGroupID.xy)), vec4(m7, 0.0f, 0.0f));
  }
}
