// Pass 5, history clean-up (passes/temporal.cpp runTemporal, after the history is stored): the tiles traced
// last frame and not in this one lose their history keys, so the next frame finds history only
// where this frame stored it.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#include "passes/untraced_tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = SSLR_IMAGE_HISTORY_KEY, r32f) uniform writeonly SSLR_IMAGE uHistoryKey;

void main() {
  ivec2 px;
  if (!sslrUntracedPixel(px)) return;
  imageStore(uHistoryKey, sslrTexel(px), vec4(0.0f));
}
