// shared/normals.h - Normals: decoding the host's packing into view space.
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_NORMALS_H
#define SSLR_SHARED_NORMALS_H

#include "language.h"
#include "projection.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- Normals ------------------------------------------------------------------------------
// Whether stored normal channels hold 0..1 (the default unpack, value * 2 - 1): the decode keeps
// that exact formula then; other scale/bias pairs (signed formats: 1, 0) go through the general one.
SSLR_FN bool sslrUnsignedNormalUnpack(SslrSurface s) { return s.normalScale == 2.0f && s.normalBias == -1.0f; }

// Octahedral mapping (Meyer et al. 2010 / Cigolle et al. 2014) into [0,1]^2.
SSLR_FN vec2 sslrOctWrap(vec2 v) {
  return (1.0f - abs(vec2(v.y, v.x))) * vec2(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f);
}
SSLR_FN vec2 sslrOctEncode(vec3 n) {
  n /= (abs(n.x) + abs(n.y) + abs(n.z));
  vec2 e = n.z >= 0.0f ? vec2(n.x, n.y) : sslrOctWrap(vec2(n.x, n.y));
  return e * 0.5f + 0.5f;
}
SSLR_FN vec3 sslrOctDecode(vec2 e01) {
  vec2 f = e01 * 2.0f - 1.0f;
  vec3 n = vec3(f.x, f.y, 1.0f - abs(f.x) - abs(f.y));
  float t = max(-n.z, 0.0f);
  n.x += n.x >= 0.0f ? -t : t;
  n.y += n.y >= 0.0f ? -t : t;
  return normalize(n);
}

// Decodes the host's texel normal. Returns false for a normal that cannot be trusted (zero,
// NaN/Inf, or far from unit length for the xyz packing): such pixels are not traced.
//
// sslr's compute passes get the encoding and the world-space flag as #defines (the dispatch's
// inputDefines, equal to these uniforms): a CPU rasterizer runs both sides of a uniform branch
// under lane masks.
SSLR_FN bool sslrDecodeNormal(SslrSurface s, vec4 texel, SSLR_OUT(vec3) vsNormal) {
#ifdef SSLR_NORMAL_ENCODING
  const bool octahedral = SSLR_NORMAL_ENCODING == SSLR_NORMALS_OCTAHEDRAL;
  const bool worldNormals = SSLR_WORLD_NORMALS != 0;
  const bool unsignedUnpack = SSLR_NORMAL_UNSIGNED != 0;
#else
  bool octahedral = s.normalEncoding == SSLR_NORMALS_OCTAHEDRAL;
  bool worldNormals = s.normalFromStored0.w != 0.0f;
  bool unsignedUnpack = sslrUnsignedNormalUnpack(s);
#endif
  vec3 n;
  if (octahedral) {
    // The octahedral coordinates in [0, 1]: stored so by unsigned formats, else unpacked first.
    vec2 e = vec2(texel.x, texel.y);
    if (!unsignedUnpack) e = (e * s.normalScale + s.normalBias) * 0.5f + 0.5f;
    e = clamp(e, vec2(0.0f), vec2(1.0f));
    n = sslrOctDecode(e);
  } else {
    n = unsignedUnpack ? vec3(texel.x, texel.y, texel.z) * 2.0f - 1.0f
                       : vec3(texel.x, texel.y, texel.z) * s.normalScale + s.normalBias;
    float len2 = dot(n, n);
    // 8-bit packing of a unit vector keeps |n| within ~1.5%; zero or garbage fails this.
    if (!(len2 > 0.8f && len2 < 1.2f)) {
      vsNormal = vec3(0.0f, 0.0f, 1.0f);
      return false;
    }
    n = normalize(n);
  }
  if (worldNormals) {  // world-space normals: into view space
    n = normalize(vec3(s.normalFromStored0.x, s.normalFromStored0.y, s.normalFromStored0.z) * n.x +
                  vec3(s.normalFromStored1.x, s.normalFromStored1.y, s.normalFromStored1.z) * n.y +
                  vec3(s.normalFromStored2.x, s.normalFromStored2.y, s.normalFromStored2.z) * n.z);
  }
  bool finite = !(isnan(n.x) || isnan(n.y) || isnan(n.z) || isinf(n.x) || isinf(n.y) || isinf(n.z));
  vsNormal = finite ? n : vec3(0.0f, 0.0f, 1.0f);
  return finite;
}

// Whether two neighbouring pixels' unit shading normals turn as on one curved surface: by more than
// their encoding's noise (8-bit xyz: ~0.5 deg per component; octahedral much less) and less than
// an edge's ~20 deg. |N_a - N_b|^2 is the squared chord of the turn.
SSLR_FN bool sslrNormalsTurnAsCurved(SslrSurface s, vec3 vsNa, vec3 vsNb) {
#ifdef SSLR_NORMAL_ENCODING
  const bool octahedral = SSLR_NORMAL_ENCODING == SSLR_NORMALS_OCTAHEDRAL;
#else
  bool octahedral = s.normalEncoding == SSLR_NORMALS_OCTAHEDRAL;
#endif
  float minTurn2 = octahedral ? 3e-5f : 1.2e-3f;  // (0.3 deg)^2, (2 deg)^2 in radians^2
  vec3 dN = vsNa - vsNb;
  float dn2 = dot(dN, dN);
  return dn2 > minTurn2 && dn2 < 0.12f;
}

SSLR_FN float sslrChannel(vec4 v, int channel) {
  return channel == 0 ? v.x : (channel == 1 ? v.y : (channel == 2 ? v.z : v.w));
}
SSLR_FN float sslrRoughness(SslrSurface s, vec4 texel) {
  return s.roughnessChannel < 0 ? s.constantRoughness : sslrChannel(texel, s.roughnessChannel);
}
SSLR_FN float sslrReflectance(SslrSurface s, vec4 texel) {
  return s.reflectanceChannel < 0 ? s.constantReflectance : sslrChannel(texel, s.reflectanceChannel);
}

// Coloured F0 (metalness workflow, SurfaceLayout::metalnessChannel): the reflectance for
// dielectrics, the base colour for metals, mixed by metalness. Metalness and base colour are
// clamped to [0, 1] (NaN reads as 0), so a poisoned input cannot leave the Fresnel range.
SSLR_FN float sslrUnitOrZero(float x) { return x > 0.0f ? min(x, 1.0f) : 0.0f; }  // [0, 1], NaN -> 0
SSLR_FN vec3 sslrF0FromMetalness(float reflectance, vec3 baseColor, float metalness) {
  float m = sslrUnitOrZero(metalness);
  vec3 base = vec3(sslrUnitOrZero(baseColor.x), sslrUnitOrZero(baseColor.y), sslrUnitOrZero(baseColor.z));
  return vec3(reflectance) * (1.0f - m) + base * m;
}

// Whether a pixel's material is worth a ray: reflective enough and smooth enough. Written so that
// NaN material values fail.
SSLR_FN bool sslrMaterialTraced(SslrTraceParams t, float reflectance, float roughness) {
  return reflectance > t.minReflectance && roughness <= t.roughnessCutoff;
}

// A pixel that may need a ray: geometry (not background) of a traced material. Classification
// lists tiles by this test (1_classify.comp), which needs no normal; the passes after it ask
// sslrShouldTrace of each pixel.
SSLR_FN bool sslrTraceCandidate(SslrSurface s, SslrTraceParams t, float depth, float reflectance,
                                float roughness) {
  return sslrIsGeometryDepth(s, depth) && sslrMaterialTraced(t, reflectance, roughness);
}

// The per-pixel test shared by tracing, the blur's neighbour test and temporal reuse: a candidate
// (above) whose normal decodes. `material` is the texel holding the material channels: the normal
// texel itself unless the host gave a separate material texture (SslrSurface::separateMaterial).
SSLR_FN bool sslrShouldTrace(SslrSurface s, SslrTraceParams t, float depth, vec4 packedNormal, vec4 material) {
  // A branch of its own, not one && chain: shader compilers evaluate such a chain whole, and the
  // normal decode is most of the test's cost.
  if (!sslrTraceCandidate(s, t, depth, sslrReflectance(s, material), sslrRoughness(s, material))) return false;
  vec3 n;
  return sslrDecodeNormal(s, packedNormal, n);
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_NORMALS_H
