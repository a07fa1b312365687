// The host's G-buffer as the passes see it (sampler objects of sslr's own are bound with them,
// so the host's texture parameters do not matter).
#ifndef SSLR_COMMON_GBUFFER_GLSL
#define SSLR_COMMON_GBUFFER_GLSL
#include "sslr_shared.h"

layout(binding = SSLR_UNIT_DEPTH) uniform SSLR_SAMPLER uDepth;   // raw window depth (nearest)
layout(binding = SSLR_UNIT_NORMAL) uniform SSLR_SAMPLER uNormal;  // texel normal + material (nearest)
layout(binding = SSLR_UNIT_COLOR) uniform SSLR_SAMPLER uColor;   // lit colour (bilinear, clamped)
layout(binding = SSLR_UNIT_MATERIAL) uniform SSLR_SAMPLER uMaterial;  // optional material texture (nearest)

layout(binding = SSLR_UNIT_MASK) uniform SSLR_SAMPLER uMask;      // optional: where rays may start (nearest)
#if defined(SSLR_BACK_DEPTH) && SSLR_BACK_DEPTH
layout(binding = SSLR_UNIT_BACK_DEPTH) uniform SSLR_SAMPLER uBackDepth;  // optional: the nearest back face's depth (nearest)
#endif
#ifdef SSLR_COLORED_F0
layout(binding = SSLR_UNIT_BASE_COLOR) uniform SSLR_SAMPLER uBaseColor;  // optional: base colour, metals' F0 (nearest)
#endif

// Pixel px of the frame as a texel of the host's textures and of the outputs (the frame is
// FrameInputs::viewport's rectangle of them). sslr's own pyramid and quad images are the frame's
// and read at px itself.
// (With several views: of the current view's layer, SSLR_AT.)
SSLR_COORD sslrTexel(ivec2 px) { return SSLR_AT(px + ivec2(frame.surface.originX, frame.surface.originY)); }

// A uv of the frame as a uv of the textures, for a bilinear read: clamped to the frame's edge
// texels' centres, as the sampler's clamp to edge does at the textures' own edge.
SSLR_UV sslrTextureUv(vec2 uv) {
  if (frame.surface.viewportInside == 0) return SSLR_UV_AT(uv);  // (uniform: the same branch for every pixel)
  vec2 size = vec2(frame.surface.width, frame.surface.height);
  vec2 texel = clamp(uv * size, vec2(0.5f), size - 0.5f) + vec2(frame.surface.originX, frame.surface.originY);
  return SSLR_UV_AT(texel / vec2(frame.surface.textureWidth, frame.surface.textureHeight));
}

// The texel holding pixel px's material channels: the host's material texture if it gave one,
// else the normal texel itself (read already).
vec4 sslrMaterialAt(ivec2 px, vec4 normalTexel) {
#ifdef SSLR_SEPARATE_MATERIAL  // FrameInputs::materialTexture given (frame.surface.separateMaterial)
  return texelFetch(uMaterial, sslrTexel(px), 0);
#else
  return normalTexel;
#endif
}

#ifdef SSLR_COLORED_F0
// Pixel px's coloured F0 (SurfaceLayout::metalnessChannel, FrameInputs::baseColorTexture).
vec3 sslrColoredF0At(ivec2 px, vec4 material, float reflectance) {
  return sslrF0FromMetalness(reflectance, texelFetch(uBaseColor, sslrTexel(px), 0).rgb,
                             sslrChannel(material, frame.surface.metalnessChannel));
}
#endif

// sslrShouldTrace for pixel px of the G-buffer, with the host's mask (FrameInputs::maskTexture):
// the trace, the blur's neighbour test and temporal reuse all ask this one question
// (classification asks its first half of whole quads: 1_classify.comp). `material` is
// sslrMaterialAt(px, normalTexel), read by the caller (the trace needs it again).
bool sslrShouldTracePixel(ivec2 px, float depth, vec4 normalTexel, vec4 material) {
#ifdef SSLR_HAS_MASK  // FrameInputs::maskTexture given (frame.surface.hasMask)
  if (!(texelFetch(uMask, sslrTexel(px), 0).r > 0.5f)) return false;
#endif
  return sslrShouldTrace(frame.surface, frame.trace, depth, normalTexel, material);
}

vec2 sslrSizePx() { return vec2(frame.surface.width, frame.surface.height); }

// The four texels a bilinear read at frame uv mixes (clamped to the frame, as the sampler's clamp
// to edge) and their weights: texel i is (i & 1, i >> 1) from the lower-left one.
struct SslrBilinear {
  ivec2 texel[4];
  float weight[4];
};
SslrBilinear sslrBilinearTexels(vec2 uv) {
  vec2 f = uv * sslrSizePx() - 0.5f;
  ivec2 base = ivec2(floor(f));
  vec2 t = f - floor(f);
  SslrBilinear b;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    b.texel[i] = clamp(base + o, ivec2(0), ivec2(sslrSizePx()) - 1);
    b.weight[i] = (o.x == 1 ? t.x : 1.0f - t.x) * (o.y == 1 ? t.y : 1.0f - t.y);
  }
  return b;
}

bool sslrInside(ivec2 px) {
  return px.x >= 0 && px.y >= 0 && px.x < int(frame.surface.width) && px.y < int(frame.surface.height);
}

// View-space position of a pixel from its depth (caller checked sslrIsGeometryDepth).
vec3 sslrViewAtPixel(ivec2 px, float depth) {
  return sslrViewFromUvDepth(frame.proj, sslrUvFromPixel(px, sslrSizePx()), depth);
}

#endif  // SSLR_COMMON_GBUFFER_GLSL
