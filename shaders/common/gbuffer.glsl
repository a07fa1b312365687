// The host's G-buffer as the passes see it (sampler objects of sslr's own are bound with them,
// so the host's texture parameters do not matter).
#include "sslr_shared.h"

layout(binding = 0) uniform sampler2D uDepth;   // raw window depth (nearest)
layout(binding = 1) uniform sampler2D uNormal;  // texel normal + material (nearest)
layout(binding = 2) uniform sampler2D uColor;   // lit colour (bilinear, clamped)
layout(binding = 7) uniform sampler2D uMaterial;  // optional material texture (nearest)

layout(binding = 8) uniform sampler2D uMask;      // optional: where rays may start (nearest)

// The texel holding pixel px's material channels: the host's material texture if it gave one,
// else the normal texel itself (read already).
vec4 sslrMaterialAt(ivec2 px, vec4 normalTexel) {
#ifdef SSLR_SEPARATE_MATERIAL  // FrameInputs::materialTexture given (frame.surface.separateMaterial)
  return texelFetch(uMaterial, px, 0);
#else
  return normalTexel;
#endif
}

// sslrShouldTrace for pixel px of the G-buffer, with the host's mask (FrameInputs::maskTexture):
// classification, the trace and the blur's neighbour test all ask this one question. `material`
// is sslrMaterialAt(px, normalTexel), read by the caller (the trace needs it again).
bool sslrShouldTracePixel(ivec2 px, float depth, vec4 normalTexel, vec4 material) {
#ifdef SSLR_HAS_MASK  // FrameInputs::maskTexture given (frame.surface.hasMask)
  if (!(texelFetch(uMask, px, 0).r > 0.5f)) return false;
#endif
  return sslrShouldTrace(frame.surface, frame.trace, depth, normalTexel, material);
}

vec2 sslrSizePx() { return vec2(frame.surface.width, frame.surface.height); }

bool sslrInside(ivec2 px) {
  return px.x >= 0 && px.y >= 0 && px.x < int(frame.surface.width) && px.y < int(frame.surface.height);
}

// View-space position of a pixel from its depth (caller checked sslrIsGeometryDepth).
vec3 sslrViewAtPixel(ivec2 px, float depth) {
  return sslrViewFromUvDepth(frame.proj, sslrUvFromPixel(px, sslrSizePx()), depth);
}
