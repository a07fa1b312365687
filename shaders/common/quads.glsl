// A 2x2 quad's texels, one channel per textureGather: classification and the pyramid's levels 0
// and 1 read the G-buffer a quad at a time (the trace reads pixels, and does not include this).
#ifndef SSLR_COMMON_QUADS_GLSL
#define SSLR_COMMON_QUADS_GLSL
#include "common/gbuffer.glsl"

// Level 1's cell `cell` covers pixels 2 cell + (0..1, 0..1); a gather at their shared corner
// returns one channel of all four. Where the quad straddles the frame's edge the last column or
// row is repeated, as sslrQuadPixel does (the sampler's clamp to edge does so at the textures'
// edge; sslrQuadInFrame at a viewport's). A quad wholly past the edge reads nothing of use: its
// callers leave it out. Classification reads the channels it needs this way: three gathers per
// quad in place of eight fetches and four normal decodes.
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

#endif  // SSLR_COMMON_QUADS_GLSL
