// Composite: one instanced quad per listed tile, so untouched tiles cost nothing. With several
// views the list holds every view's tiles: those of other views than uView collapse to a point.
#include "common/tiles.glsl"
#if SSLR_VIEWS > 1
layout(location = SSLR_COMPOSITE_VIEW_LOCATION) uniform int uView;
#endif

void main() {
  const vec2 corners[6] = vec2[](vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(1.0f, 1.0f),
                                 vec2(0.0f, 0.0f), vec2(1.0f, 1.0f), vec2(0.0f, 1.0f));
  // The tile's corner in the frame, clamped to it, then in the framebuffer (the textures' size,
  // with the frame at FrameInputs::viewport's origin).
  ivec2 origin = sslrTileOrigin(uint(gl_InstanceID));  // (enters the tile's view)
#if SSLR_VIEWS > 1
  if (sslrView != uView) {
    gl_Position = vec4(-2.0f, -2.0f, 0.0f, 1.0f);  // outside the clip volume, zero area
    return;
  }
#endif
  vec2 sizePx = vec2(frame.surface.width, frame.surface.height);
  vec2 px = min(vec2(origin) + corners[gl_VertexID] * float(SSLR_TILE_SIZE),
                sizePx);
  vec2 texel = px + vec2(frame.surface.originX, frame.surface.originY);
  gl_Position = vec4(texel / vec2(frame.surface.textureWidth, frame.surface.textureHeight) * 2.0f - 1.0f, 0.0f, 1.0f);
}
