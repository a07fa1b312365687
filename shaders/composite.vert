// Composite: one instanced quad per listed tile, so untouched tiles cost nothing.
#include "common/tiles.glsl"

void main() {
  const vec2 corners[6] = vec2[](vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(1.0f, 1.0f),
                                 vec2(0.0f, 0.0f), vec2(1.0f, 1.0f), vec2(0.0f, 1.0f));
  vec2 sizePx = vec2(frame.surface.width, frame.surface.height);
  vec2 px = min(vec2(sslrTileOrigin(uint(gl_InstanceID))) + corners[gl_VertexID] * float(SSLR_TILE_SIZE),
                sizePx);
  gl_Position = vec4(px / sizePx * 2.0f - 1.0f, 0.0f, 1.0f);
}
