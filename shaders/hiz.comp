// Builds one or two levels of the min-max depth pyramid (sslr_shared.h, "Min-max depth pyramid"):
// each cell is the (min, max) raw depth of its 2x2 children. Levels 0 and 1 are classification's
// (classify.comp reads every depth anyway); level l > 1 reads level l - 1 (mip l - 1 of the same
// texture, while mip l is written).
// With uTwoLevels each invocation also writes the next level up: it reads the 4x4 source cells
// under one cell of that level, writes its four children and the cell itself. Half the
// dispatches and barriers, and the middle level is never read back (on an H100 a dispatch with
// its barrier costs ~3.5 us whatever it does: the pyramid of an empty frame cost 0.025 ms).
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = 0, rg32f) uniform writeonly image2D uLevel;       // the level being written
layout(binding = 1, rg32f) uniform writeonly image2D uUpperLevel;  // the one above (uTwoLevels)
layout(binding = 6) uniform sampler2D uHiZ;                        // the pyramid (previous level)
layout(location = 0) uniform int uSourceLevel;  // l >= 1: pyramid level l (mip l)
layout(location = 1) uniform int uTwoLevels;    // 1: also write the level above

vec2 sourceCell(ivec2 c, ivec2 sourceSize) {
  if (c.x >= sourceSize.x || c.y >= sourceSize.y) return sslrHiZEmpty();
  return texelFetch(uHiZ, c, uSourceLevel).rg;
}

// The (min, max) of level cell `cell` from its four source cells.
vec2 levelCell(ivec2 cell, ivec2 sourceSize) {
  ivec2 c = cell * 2;
  return sslrHiZReduce(sslrHiZReduce(sourceCell(c, sourceSize), sourceCell(c + ivec2(1, 0), sourceSize)),
                       sslrHiZReduce(sourceCell(c + ivec2(0, 1), sourceSize), sourceCell(c + ivec2(1, 1), sourceSize)));
}

void main() {
  // Dispatched indirectly: with no tile listed, no group runs (common/tiles.glsl).
  ivec2 cell = ivec2(gl_GlobalInvocationID.xy);  // of the top level written
  ivec2 n = textureSize(uHiZ, uSourceLevel);
  if (uTwoLevels == 0) {
    if (any(greaterThanEqual(cell, imageSize(uLevel)))) return;
    imageStore(uLevel, cell, vec4(levelCell(cell, n), 0.0f, 0.0f));
    return;
  }
  if (any(greaterThanEqual(cell, imageSize(uUpperLevel)))) return;
  // Each mip is exactly half the one below (sslr.depthPyramid is padded), so the four children lie
  // inside uLevel.
  vec2 upper = sslrHiZEmpty();
  for (int k = 0; k < 4; ++k) {
    ivec2 child = cell * 2 + ivec2(k & 1, k >> 1);
    vec2 m = levelCell(child, n);
    imageStore(uLevel, child, vec4(m, 0.0f, 0.0f));
    upper = sslrHiZReduce(upper, m);
  }
  imageStore(uUpperLevel, cell, vec4(upper, 0.0f, 0.0f));
}
