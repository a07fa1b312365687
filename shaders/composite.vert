// Composite: one instanced quad per listed tile, so untouched tiles cost nothing.
#include "common/tiles.glsl"

void main() {
  const vec2 corners[6] = vec2[](vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(1.0f, 1.0f),
                                 vec2(0.0f, 0.0f), vec2(1.0f, 1.0f), vec2(0.0f, 1.0f));
  // The tile's corner in the frame, clamped to it, then in the framebuffer (the textures' size,
  // with the frame at FrameInputs::viewport's origin).
  vec2 sizePx = vec2(frame.surface.width, frame.surface.height);
  vec2 px = min(vec2(sslrTileOrigin(uint(gl_InstanceID))) + corners[gl_VertexID] * float(SSLR_TILE_SIZE),
                sizePx);
  vec2 texel = px + vec2(frame.surface.originX, frame.surface.originY);
  gl_Position = vec4(texel / vec2(frame.surface.textureWidth, frame.surface.textureHeight) * 2.0f - 1.0f, 0.0f, 1.0f);
}
