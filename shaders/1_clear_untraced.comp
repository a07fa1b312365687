// Pass 1, clean-up (passes/classify.cpp runClassify, after classification): zeroes the reflection and the
// resolved output in the tiles traced last frame and not listed in this one.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#include "passes/untraced_tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = SSLR_IMAGE_REFLECTION, rgba16f) uniform writeonly SSLR_IMAGE uReflection;
layout(binding = SSLR_IMAGE_RESOLVED, rgba16f) uniform writeonly SSLR_IMAGE uResolved;

void main() {
  ivec2 px;
  if (!sslrUntracedPixel(px)) return;
  imageStore(uReflection, sslrTexel(px), vec4(0.0f));
  imageStore(uResolved, sslrTexel(px), vec4(0.0f));
}
