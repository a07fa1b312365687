// The host's G-buffer as the passes see it (sampler objects of sslr's own are bound with them,
// so the host's texture parameters do not matter).
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

// ---- A 2x2 quad's texels, one channel per textureGather --------------------------------------
// Level 1's cell `cell` covers pixels 2 cell + (0..1, 0..1); a gather at their shared corner
// returns one channel of all four. Where the quad straddles the frame's edge the last column or
// row is repeated, as sslrQuadPixel does (the sampler's clamp to edge does so at the textures'
// edge; sslrQuadInFrame at a viewport's). A quad wholly past the edge reads nothing of use: its
// callers leave it out. Classification reads the
// channels it needs this way: three gathers per quad in place of eight fetches and four normal
// decodes.
// Components in pixel order p0 = (0, 0), p1 = (1, 0), p2 = (0, 1), p3 = (1, 1): a gather returns
// (0, 1), (1, 1), (1, 0), (0, 0).
SSLR_UV sslrQuadCornerUv(ivec2 cell) {
  ivec2 texel = cell * 2 + ivec2(frame.surface.originX, frame.surface.originY);
  return SSLR_UV_AT((vec2(texel) + 1.0f) / vec2(frame.surface.textureWidth, frame.surface.textureHeight));
}
vec4 sslrQuadInFrame(vec4 v, ivec2 cell) {
  if (frame.surface.viewportInside == 0) return v;  // the textures' clamp to edge did it (uniform)
  bvec2 past = greaterThanEqual(cell * 2 + 1, ivec2(frame.surface.width, frame.surface.height));
  if (past.x) v.yw = v.xz;
  if (past.y) v.zw = v.xy;
  return v;
}
#define SSLR_GATHER_QUAD(tex, cell, channel) \
  (sslrQuadInFrame(textureGather(tex, sslrQuadCornerUv(cell), channel).wzxy, cell))

// The material channels of a quad (sslrRoughness, sslrReflectance): the channel is compiled in
// (SSLR_ROUGHNESS_CHANNEL, SSLR_REFLECTANCE_CHANNEL), as a gather needs; -1 is the layout's
// constant (the compiler drops the gather: the condition is constant).
#ifdef SSLR_SEPARATE_MATERIAL
#define SSLR_MATERIAL_SOURCE uMaterial
#else
#define SSLR_MATERIAL_SOURCE uNormal
#endif
#define SSLR_QUAD_MATERIAL(cell, channel, constant) \
  ((channel) < 0 ? vec4(constant) : SSLR_GATHER_QUAD(SSLR_MATERIAL_SOURCE, cell, max(channel, 0)))
vec4 sslrQuadRoughness(ivec2 cell) {
  return SSLR_QUAD_MATERIAL(cell, SSLR_ROUGHNESS_CHANNEL, frame.surface.constantRoughness);
}
vec4 sslrQuadReflectance(ivec2 cell) {
  return SSLR_QUAD_MATERIAL(cell, SSLR_REFLECTANCE_CHANNEL, frame.surface.constantReflectance);
}

bool sslrInside(ivec2 px) {
  return px.x >= 0 && px.y >= 0 && px.x < int(frame.surface.width) && px.y < int(frame.surface.height);
}

// View-space position of a pixel from its depth (caller checked sslrIsGeometryDepth).
vec3 sslrViewAtPixel(ivec2 px, float depth) {
  return sslrViewFromUvDepth(frame.proj, sslrUvFromPixel(px, sslrSizePx()), depth);
}
