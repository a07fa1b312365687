// Builds one level of the min-max depth pyramid (sslr_shared.h, "Min-max depth pyramid"): each
// cell is the (min, max) raw depth of its 2x2 children. Level 1 reads the depth texture (background
// and NaN become the clear value, pixels outside the screen are neutral); level l > 1 reads level
// l - 1 (mip l - 2 of the same texture, while mip l - 1 is written).
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = 0, rg32f) uniform writeonly image2D uLevel;  // the level being written
layout(binding = 6) uniform sampler2D uHiZ;                     // the pyramid (previous level)
layout(location = 0) uniform int uSourceLevel;  // 0: the depth texture; l >= 1: pyramid level l (mip l - 1)

vec2 sourceCell(ivec2 c, ivec2 sourceSize) {
  if (c.x >= sourceSize.x || c.y >= sourceSize.y) return sslrHiZEmpty();
  if (uSourceLevel == 0) return sslrHiZTexel(frame.surface, texelFetch(uDepth, c, 0).r);
  return texelFetch(uHiZ, c, uSourceLevel - 1).rg;
}

void main() {
  // Dispatched indirectly: with no tile listed, no group runs (common/tiles.glsl).
  ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(cell, imageSize(uLevel)))) return;
  ivec2 n = uSourceLevel == 0 ? textureSize(uDepth, 0) : textureSize(uHiZ, uSourceLevel - 1);
  ivec2 c = cell * 2;
  vec2 m = sslrHiZReduce(sslrHiZReduce(sourceCell(c, n), sourceCell(c + ivec2(1, 0), n)),
                         sslrHiZReduce(sourceCell(c + ivec2(0, 1), n), sourceCell(c + ivec2(1, 1), n)));
  imageStore(uLevel, cell, vec4(m, 0.0f, 0.0f));
}
