// Pass 3 (run twice: SSLR_BLUR_AXIS = ivec2(1,0) then ivec2(0,1)): separable bilateral blur of
// the resolved output (rgb = reflection, a = coverage: both blurred with the same weights, so the
// reflection stays premultiplied by its coverage) over the tiles the trace listed for blurring
// (tiles with a pixel whose radius is at least half a pixel). The radius comes from the reflection's
// alpha (the cone footprint written by the trace); neighbours count only if they are traced pixels
// on a similar surface (depth and normal weights), so reflections do not bleed across edges.
//
// H pass: unblurred resolved -> blurTemp. V pass: blurTemp -> resolved. The V pass reads a
// neighbour's unblurred value from resolved itself where the neighbour's radius is below half a
// pixel: such a texel, if it lies in a blur tile, is rewritten by this pass with the very value it
// holds (both passes pass a sub-half-pixel radius through unchanged), so read-before-write and
// read-after-write agree bit for bit.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = 3) uniform sampler2D uBlurInput;   // unblurred resolved (H pass) or blurTemp (V pass)
layout(binding = 4) uniform sampler2D uReflectionIn;  // the reflection: its alpha is the blur radius
#ifdef SSLR_BLUR_VERTICAL
layout(binding = 5) uniform sampler2D uUnblurred;     // V pass: resolved before this pass
#endif
layout(binding = 0, rgba16f) uniform writeonly image2D uBlurOutput;

void main() {
  ivec2 px = sslrBlurTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;
  vec4 center = texelFetch(uBlurInput, px, 0);
  float radius = texelFetch(uReflectionIn, px, 0).a * frame.trace.blurMaxRadiusPx;
  if (!(radius >= 0.5f)) {
    imageStore(uBlurOutput, px, center);
    return;
  }
  float depth0 = texelFetch(uDepth, px, 0).r;
  vec3 n0;
  sslrDecodeNormal(frame.surface, texelFetch(uNormal, px, 0), n0);
  float z0 = abs(sslrViewAtPixel(px, depth0).z);
  float sigma = max(radius * 0.5f, 0.5f);
  float depthScale = 1.0f / max(frame.trace.blurDepthSigma * z0, 1e-6f);
  int taps = int(ceil(radius));
  vec4 sum = center;
  float weightSum = 1.0f;
  for (int i = -taps; i <= taps; ++i) {
    ivec2 q = px + SSLR_BLUR_AXIS * i;
    if (i == 0 || !sslrInside(q)) continue;
    float depth1 = texelFetch(uDepth, q, 0).r;
    vec4 packed1 = texelFetch(uNormal, q, 0);
    if (!sslrShouldTracePixel(q, depth1, packed1, sslrMaterialAt(q, packed1))) continue;
    vec3 n1;
    sslrDecodeNormal(frame.surface, packed1, n1);
    float z1 = abs(sslrViewAtPixel(q, depth1).z);
    float w = exp(-0.5f * float(i * i) / (sigma * sigma)) * exp(-abs(z1 - z0) * depthScale) *
              pow(max(dot(n0, n1), 0.0f), frame.trace.blurNormalPower);
#ifdef SSLR_BLUR_VERTICAL
    // blurTemp exists only in blur tiles; a pixel with a sub-half-pixel radius is its own value.
    vec4 value = texelFetch(uReflectionIn, q, 0).a * frame.trace.blurMaxRadiusPx >= 0.5f
                     ? texelFetch(uBlurInput, q, 0)
                     : texelFetch(uUnblurred, q, 0);
#else
    vec4 value = texelFetch(uBlurInput, q, 0);
#endif
    sum += value * w;
    weightSum += w;
  }
  imageStore(uBlurOutput, px, sum / weightSum);
}
