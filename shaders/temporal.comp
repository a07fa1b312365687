// Pass 6 (Settings::temporal), over the listed tiles: blends this frame's resolved output with the
// previous frame's, reprojected through FrameInputs::previousClipFromView.
//   default:              resolved (+ history, history keys) -> blurTemp
//   SSLR_TEMPORAL_STORE:  blurTemp -> resolved and history; this frame's keys -> history keys
// (two passes: the blend reads history and resolved around each pixel, so it cannot write them).
// History is used where the reprojected point lands on the same surface (its key, the view depth,
// within keyTolerance on one of the four texels around it; only those texels are interpolated),
// clipped to this frame's 3x3 neighbourhood (mean +- one standard deviation: what moved or
// appeared cannot drag old colour along), then mixed in with historyWeight. The reprojection
// follows the surface, not the reflected image (docs/algorithm.md, "Temporal reuse", has what
// that costs on fast motion and curved mirrors).
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

#ifdef SSLR_TEMPORAL_STORE
layout(binding = 3) uniform sampler2D uBlended;
layout(binding = 0, rgba16f) uniform writeonly image2D uResolved;
layout(binding = 1, rgba16f) uniform writeonly image2D uHistory;
layout(binding = 2, r32f) uniform writeonly image2D uHistoryKey;

void main() {
  ivec2 px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;
  vec4 value = texelFetch(uBlended, px, 0);
  imageStore(uResolved, px, value);
  imageStore(uHistory, px, value);
  float depth = texelFetch(uDepth, px, 0).r;
  vec4 packedNormal = texelFetch(uNormal, px, 0);
  float key = 0.0f;
  if (sslrShouldTracePixel(px, depth, packedNormal, sslrMaterialAt(px, packedNormal)))
    key = sslrHistoryKey(frame.proj, sslrViewAtPixel(px, depth));
  imageStore(uHistoryKey, px, vec4(key));
}
#else
layout(binding = 3) uniform sampler2D uCurrent;     // resolved: this frame, blurred
layout(binding = 4) uniform sampler2D uHistory;     // the previous frame's output
layout(binding = 5) uniform sampler2D uHistoryKey;  // its keys
layout(binding = 6) uniform sampler2D uMotion;      // optional: uv now - uv then (host motion vectors)
layout(binding = 0, rgba16f) uniform writeonly image2D uBlended;

void main() {
  ivec2 px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;
  vec4 current = texelFetch(uCurrent, px, 0);
  vec4 blended = current;
  float depth = texelFetch(uDepth, px, 0).r;
  vec4 packedNormal = texelFetch(uNormal, px, 0);
  vec2 uvPrevious;
  float keyPrevious;
  bool found = false;
  if (frame.temporal.history != 0 && sslrShouldTracePixel(px, depth, packedNormal, sslrMaterialAt(px, packedNormal))) {
    found = sslrReproject(frame.proj, frame.temporal.previousClipFromView, sslrViewAtPixel(px, depth), uvPrevious,
                          keyPrevious);
    if (frame.temporal.hasMotion != 0) {
      // The host's motion vectors say where the point was; the matrices still give the depth a
      // static point would have had there: an object that also moved in depth by more than the
      // key tolerance starts afresh (no history rather than a ghost).
      uvPrevious = sslrUvFromPixel(px, sslrSizePx()) - texelFetch(uMotion, px, 0).xy;
      found = keyPrevious > 0.0f && all(greaterThanEqual(uvPrevious, vec2(0.0f))) &&
              all(lessThanEqual(uvPrevious, vec2(1.0f)));
    }
  }
  if (found) {
    // Bilinear over the texels of the same surface only.
    vec2 sizePx = sslrSizePx();
    vec2 f = uvPrevious * sizePx - 0.5f;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - floor(f);
    vec4 sum = vec4(0.0f);
    float weightSum = 0.0f;
    for (int i = 0; i < 4; ++i) {
      ivec2 o = ivec2(i & 1, i >> 1);
      ivec2 q = clamp(base + o, ivec2(0), ivec2(sizePx) - 1);
      float w = (o.x == 1 ? t.x : 1.0f - t.x) * (o.y == 1 ? t.y : 1.0f - t.y);
      if (w > 0.0f && sslrHistoryKeyMatches(texelFetch(uHistoryKey, q, 0).r, keyPrevious, frame.temporal.keyTolerance)) {
        sum += texelFetch(uHistory, q, 0) * w;
        weightSum += w;
      }
    }
    if (weightSum > 1e-3f) {
      // Variance clipping (Salvi 2016): the neighbourhood's mean +- one standard deviation, a
      // tighter box than its min-max where the reflection has detail; widened to hold this
      // pixel's own value (a history equal to it must pass unchanged).
      vec4 m1 = vec4(0.0f), m2 = vec4(0.0f);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          vec4 v = texelFetch(uCurrent, clamp(px + ivec2(dx, dy), ivec2(0), ivec2(sizePx) - 1), 0);
          m1 += v;
          m2 += v * v;
        }
      vec4 mean = m1 / 9.0f;
      vec4 sigma = sqrt(max(m2 / 9.0f - mean * mean, vec4(0.0f)));
      vec4 lo = min(mean - sigma, current), hi = max(mean + sigma, current);
      blended = mix(current, clamp(sum / weightSum, lo, hi), frame.temporal.historyWeight);
    }
  }
  imageStore(uBlended, px, blended);
}
#endif
