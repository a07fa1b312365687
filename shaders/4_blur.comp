// Pass 4, blur (passes/blur.cpp runBlur; run twice: SSLR_BLUR_AXIS = ivec2(1,0) then ivec2(0,1)): separable bilateral blur of
// the resolved output (rgb = reflection, a = coverage: both blurred with the same weights, so the
// reflection stays premultiplied by its coverage) over the tiles the trace listed for blurring
// (tiles with a pixel whose radius is at least half a pixel). The radius comes from the reflection's
// alpha (the cone footprint written by the trace); neighbours count only if they are traced pixels
// on a similar surface (sslrBlurTapWeight: depth and normal terms), so reflections do not bleed
// across edges.
//
// H pass: unblurred resolved -> scratch. V pass: scratch -> resolved. The V pass reads a
// neighbour's unblurred value from resolved itself where the neighbour's radius is below half a
// pixel: such a texel, if it lies in a blur tile, is rewritten by this pass with the very value it
// holds (both passes pass a sub-half-pixel radius through unchanged), so read-before-write and
// read-after-write agree bit for bit.
//
// Each work group blurs one tile. It first stages the tile's rows (H) or columns (V), widened by
// the largest radius in the tile on both sides, in shared memory: value, view distance, normal and
// whether the pixel was traced, read and decoded once per pixel. Every tap then reads shared
// memory. Reading the G-buffer per tap instead (up to five fetches, a depth reconstruction and a
// normal decode for each of up to 65 taps) made this pass most of a frame with rough surfaces on
// llvmpipe (docs/design-notes.md, "Blur (roughness) and composite").
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#include "shared/blur.h"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = SSLR_UNIT_BLUR_INPUT) uniform SSLR_SAMPLER uBlurInput;   // unblurred resolved (H pass) or the scratch image (V pass)
layout(binding = SSLR_UNIT_BLUR_REFLECTION) uniform SSLR_SAMPLER uReflectionIn;  // the reflection: its alpha is the blur radius
#ifdef SSLR_BLUR_VERTICAL
layout(binding = SSLR_UNIT_BLUR_UNBLURRED) uniform SSLR_SAMPLER uUnblurred;     // V pass: resolved before this pass
#endif
layout(binding = SSLR_IMAGE_BLUR_OUTPUT, rgba16f) uniform writeonly SSLR_IMAGE uBlurOutput;

// Settings cap blur.maxRadiusPx at 32 (sslr::validate): taps reach ceil(radius) <= 32 pixels out.
#define SSLR_BLUR_MAX_TAPS 32
#define SSLR_BLUR_SPAN (SSLR_TILE_SIZE + 2 * SSLR_BLUR_MAX_TAPS)
// Staged pixels: [line across the axis][position along it, offset by the apron]. 2 x 8 x 72 x 16
// bytes = 18 KiB, within the 32 KiB of shared memory GL 4.5 guarantees a work group.
shared vec4 sValue[SSLR_TILE_SIZE][SSLR_BLUR_SPAN];
shared vec4 sGuide[SSLR_TILE_SIZE][SSLR_BLUR_SPAN];  // xyz = view-space normal, w = view distance (< 0: not a neighbour)
shared uint sTaps;

float sslrBlurRadiusAt(ivec2 px) { return texelFetch(uReflectionIn, sslrTexel(px), 0).a * frame.trace.maxRadiusPx; }

void main() {
  ivec2 local = ivec2(gl_LocalInvocationID.xy);
  ivec2 origin = sslrBlurTileOrigin(gl_WorkGroupID.x);
  ivec2 px = origin + local;
  bool inside = sslrInside(px);
  float radius = inside ? sslrBlurRadiusAt(px) : 0.0f;
  bool blurred = radius >= 0.5f;  // false for NaN too
  int ownTaps = blurred ? min(int(ceil(radius)), SSLR_BLUR_MAX_TAPS) : 0;

  // The apron: the largest tap count any pixel of the tile needs.
  if (local == ivec2(0)) sTaps = 0u;
  barrier();
  if (blurred) atomicMax(sTaps, uint(ownTaps));
  barrier();
  int taps = int(sTaps);

  // Stage line `line` (the row or column across the axis at offset `line` in the tile) from
  // -taps to SSLR_TILE_SIZE + taps along the axis: every invocation loads every 64th entry.
  ivec2 across = ivec2(1) - SSLR_BLUR_AXIS;
  int span = SSLR_TILE_SIZE + 2 * taps;
  for (int entry = local.y * SSLR_TILE_SIZE + local.x; entry < span * SSLR_TILE_SIZE;
       entry += SSLR_TILE_SIZE * SSLR_TILE_SIZE) {
    int line = entry / span, along = entry - line * span;
    ivec2 q = origin + across * line + SSLR_BLUR_AXIS * (along - taps);
    vec4 guide = vec4(0.0f, 0.0f, 0.0f, -1.0f);
    vec4 value = vec4(0.0f);
    if (sslrInside(q)) {
      float depth = texelFetch(uDepth, sslrTexel(q), 0).r;
      vec4 normalTexel = texelFetch(uNormal, sslrTexel(q), 0);
      if (sslrShouldTracePixel(q, depth, normalTexel, sslrMaterialAt(q, normalTexel))) {
        sslrDecodeNormal(frame.surface, normalTexel, guide.xyz);
        guide.w = abs(sslrViewAtPixel(q, depth).z);
#ifdef SSLR_BLUR_VERTICAL
        // the scratch image is written only in blur tiles; a pixel with a sub-half-pixel radius is its own value.
        value = sslrBlurRadiusAt(q) >= 0.5f ? texelFetch(uBlurInput, sslrTexel(q), 0) : texelFetch(uUnblurred, sslrTexel(q), 0);
#else
        value = texelFetch(uBlurInput, sslrTexel(q), 0);
#endif
      }
    }
    sValue[line][SSLR_BLUR_MAX_TAPS - taps + along] = value;
    sGuide[line][SSLR_BLUR_MAX_TAPS - taps + along] = guide;
  }
  barrier();
  if (!inside) return;

  vec4 center = texelFetch(uBlurInput, sslrTexel(px), 0);
  if (!blurred) {
    imageStore(uBlurOutput, sslrTexel(px), center);
    return;
  }
  // This pixel in the staged lines: line = its offset across the axis, at = along it.
  int line = local.x * across.x + local.y * across.y;
  int at = SSLR_BLUR_MAX_TAPS + local.x * SSLR_BLUR_AXIS.x + local.y * SSLR_BLUR_AXIS.y;
  // A blurred pixel was traced, so its own guide is valid (its depth is geometry, its normal read).
  vec4 guide0 = sGuide[line][at];
  SslrBlurCentre centre = sslrBlurCentre(frame.trace, radius, guide0.w, guide0.xyz);
  vec4 sum = center;
  float weightSum = 1.0f;
  for (int i = -ownTaps; i <= ownTaps; ++i) {
    vec4 guide1 = sGuide[line][at + i];
    if (i == 0 || guide1.w < 0.0f) continue;
    float w = sslrBlurTapWeight(centre, i, guide1.w, guide1.xyz);
    sum += sValue[line][at + i] * w;
    weightSum += w;
  }
  imageStore(uBlurOutput, sslrTexel(px), sum / weightSum);
}
