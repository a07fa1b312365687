// Pass 3 (trace; passes.cpp runTrace): trace over listed tiles. Writes the reflection (rgb = hit colour x weights, a = blur
// weight), the unblurred resolved output (same rgb, a = coverage) and, with SSLR_DEBUG_OUTPUTS,
// the hit and iteration images.
// Tracer: the depth-only tracer (adaptive L, with the hierarchical traversal as fallback or alone,
// frame.trace.hizMode), or with SSLR_METHOD_POSITION_BUFFER the position-buffer march of
// "3D Game Shaders For Beginners" on a stored position texture, or with SSLR_METHOD_DDA McGuire &
// Mara's screen-space DDA on the depth buffer.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

// Half resolution (Settings::halfResolution) runs this file three times: SSLR_HALF_QUADS traces
// one ray per 2x2 quad; SSLR_HALF_RES shades every pixel of the listed tiles from its quad's ray
// where the pixel lies on the traced pixel's surface and lists the others; SSLR_HALF_RETRACE
// traces and shades the listed pixels. The middle pass holds no tracer code: llvmpipe would run
// it under lane masks for every pixel (measured: with the tracer inline, half resolution was
// slower than full on mirror-room).
// A deferred traversal (Settings::traversalPass, SSLR_DEFER_TRAVERSAL) works the same way at full
// resolution: this pass runs adaptive L alone (sslrTraceFirstStage) and lists the pixels that need
// the traversal; SSLR_HALF_RETRACE traces those with the whole tracer. The traversal's code is
// then in no program that every pixel runs. Half resolution defers it the same way: the quad pass
// lists the quads whose ray needs the traversal, and SSLR_HALF_QUAD_RETRACE traces those before
// the full-resolution pass reads the quads.
#ifdef SSLR_HALF_QUADS
layout(local_size_x = SSLR_TILE_QUADS) in;  // one listed tile's quads (sslrTileQuad)
layout(binding = SSLR_IMAGE_QUAD_HIT, rgba32f) uniform writeonly image2D uQuadHitOut;      // see uQuadHit
layout(binding = SSLR_IMAGE_QUAD_SURFACE, rgba16f) uniform writeonly image2D uQuadSurfaceOut;  // see uQuadSurface
#elif defined(SSLR_HALF_RETRACE)
layout(local_size_x = SSLR_RETRACE_GROUP) in;
#else
layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;
#endif
#ifdef SSLR_HALF_RES
layout(binding = SSLR_UNIT_QUAD_HIT) uniform sampler2D uQuadHit;      // xyz: view-space hit point; w: see SSLR_HALF_QUADS
layout(binding = SSLR_UNIT_QUAD_SURFACE) uniform sampler2D uQuadSurface;  // xy: traced pixel's octahedral normal; zw: hit surface's
#endif
#if defined(SSLR_HALF_RES) || defined(SSLR_HALF_RETRACE) || defined(SSLR_DEFER_TRAVERSAL) || \
    defined(SSLR_HALF_QUAD_RETRACE) || defined(SSLR_COUNT_TRAVERSAL)
layout(std430, binding = SSLR_BINDING_RETRACE_SSBO) buffer SslrRetrace {
  // DispatchIndirectCommand: the retrace pass's ceil(count / SSLR_RETRACE_GROUP) groups, or the
  // quad retrace pass's one group per tile with a quad listed.
  uint dispatchX;
  uint dispatchY;
  uint dispatchZ;
  uint count;  // pixels listed; inline under Auto: pixels the traversal ran for; in the quad
               // passes under Auto: quads listed, or that the traversal ran for (inline)
  // Pixels: x | y << 16 in the order listed. Quads: [0, cap) the slots of the tiles with a quad
  // listed, then per slot a region of its listed quads, x | y << 16, as many as
  // sslrQuadRetraceCountIndex says.
  uint entries[];
} retrace;

#ifdef SSLR_HALF_QUADS
// Lists a quad of this group's tile (the quad pass runs one group per traced tile, in list slot
// gl_WorkGroupID.x) for the quad retrace pass, which runs one group per tile with a quad listed:
// the rays of a group start side by side, as they would inline. In the one list the pixels use,
// the quads of the tiles that ran at the same time (llvmpipe's threads) interleaved, and SIMD
// batches of rays from far apart diverged: half resolution's quad rays cost 1.5x full
// resolution's per ray on mirror-walls (docs/algorithm.md). The pixels keep the one list: they are
// few and scattered (edges, rays the quad's did not answer), and grouping them by tile left most
// invocations idle (thin-objects 13-20% slower).
uint sslrQuadRetraceRegion(uint slot) { return sslrTileCapacity() + slot * uint(SSLR_TILE_QUADS); }
void sslrListForRetrace(ivec2 quad) {
#ifdef SSLR_COUNT_TRAVERSAL
  atomicAdd(retrace.count, 1u);  // TraversalPass::Auto's feedback: quads that needed the traversal
#endif
  uint slot = gl_WorkGroupID.x;
  uint k = atomicAdd(tiles.tileCoords[sslrQuadRetraceCountIndex(slot)], 1u);
  retrace.entries[sslrQuadRetraceRegion(slot) + k] = sslrPackCoord(quad);
  if (k == 0u) retrace.entries[atomicAdd(retrace.dispatchX, 1u)] = slot;
}
#else
// Lists a pixel for the retrace pass.
void sslrListForRetrace(ivec2 px) {
  uint slot = atomicAdd(retrace.count, 1u);
  retrace.entries[slot] = sslrPackCoord(px);
  if (slot % uint(SSLR_RETRACE_GROUP) == 0u) atomicAdd(retrace.dispatchX, 1u);
}
#endif
#endif

layout(binding = SSLR_IMAGE_REFLECTION, rgba16f) uniform writeonly image2D uReflection;
// The resolved image gets the reflection too: tiles without a pixel to blur are final here,
// and the blur passes then run only over the tiles listed for them.
layout(binding = SSLR_IMAGE_RESOLVED, rgba16f) uniform writeonly image2D uResolved;
// The hit record: a debug output, and what temporal reuse (SSLR_TEMPORAL_HITS) reprojects by.
#if defined(SSLR_DEBUG_OUTPUTS) || defined(SSLR_TEMPORAL_HITS)
layout(binding = SSLR_IMAGE_HIT, rgba32f) uniform writeonly image2D uHit;
#endif
#ifdef SSLR_DEBUG_OUTPUTS
layout(binding = SSLR_IMAGE_ITERATIONS, r32f) uniform writeonly image2D uIterations;
#endif
#ifdef SSLR_COLLECT_STATS
layout(std430, binding = SSLR_BINDING_STATS_SSBO) buffer SslrStats {
  uint tracedPixels;
  uint fetches;
  uint hierarchicalPixels;
} stats;
#endif

uint gFetches = 0u;  // depth (or position) texels read by this invocation (stats)
float sslrLoadDepth(ivec2 px) {
  gFetches += 1u;
  return texelFetch(uDepth, px, 0).r;
}
bool sslrLoadSurface(ivec2 px, out vec3 vsPos) {
  return sslrSurfaceFromDepth(frame.proj, frame.surface, px, sslrLoadDepth(px), vsPos);
}
vec4 sslrLoadNormal(ivec2 px) { return texelFetch(uNormal, px, 0); }

#ifdef SSLR_METHOD_POSITION_BUFFER
layout(binding = SSLR_UNIT_POSITION) uniform sampler2D uPosition;  // view-space position, w = 1 on geometry
bool sslrLoadPosition(ivec2 px, out vec4 vsPosition) {
  gFetches += 1u;
  vsPosition = texelFetch(uPosition, px, 0);
  return vsPosition.w > 0.0f;
}
#include "sslr_trace_position.h"
#elif defined(SSLR_METHOD_DDA)
#include "sslr_trace_dda.h"
#else
// The min-max depth pyramid (classify.comp writes levels 0 and 1, hiz.comp the rest): mip m holds
// level m.
layout(binding = SSLR_UNIT_PYRAMID) uniform sampler2D uHiZ;
vec2 sslrLoadPyramidTexel(int level, ivec2 cell) {
  gFetches += 1u;
  return texelFetch(uHiZ, cell, level).rg;
}
#include "sslr_trace_hiz.h"
#ifdef SSLR_METHOD_FFX
#include "sslr_trace_ffx.h"
#endif
#endif

// The configured tracer for one ray from pixel px.
SslrHit sslrTraceRay(ivec2 px, vec3 vsP, vec3 vsV, vec3 vsR) {
#ifdef SSLR_METHOD_POSITION_BUFFER
  return sslrTracePositionBuffer(frame.proj, frame.surface, frame.positionBuffer, vsP, vsV, vsR);
#elif defined(SSLR_METHOD_DDA)
  return sslrTraceDda(frame.proj, frame.surface, frame.dda, px, vsP, vsR);
#elif defined(SSLR_METHOD_FFX)
  return sslrTraceFfx(frame.proj, frame.surface, frame.trace, px, vsP, vsR);
#else
  return sslrTraceDepthOnly(frame.proj, frame.surface, frame.trace, px, vsP, vsR);
#endif
}

// What shading pixel px needs, when it is to be traced: a reflective surface (mask, material,
// a normal that decodes) facing the camera. The position comes from depth, or from the stored
// positions for the tutorial's method.
struct SslrPixel {
  vec4 texel;     // the normal texel
  vec4 material;  // the texel of the material channels (sslrMaterialAt)
  vec3 vsP, vsN, vsV, vsR;
  float cosVN;    // dot(-V, N)
};
bool sslrPixelToTrace(ivec2 px, out SslrPixel q) {
  q.texel = sslrLoadNormal(px);
  float depth = sslrLoadDepth(px);
#ifdef SSLR_METHOD_POSITION_BUFFER
  vec4 stored;
  bool geometry = sslrLoadPosition(px, stored);
  q.vsP = stored.xyz;
#else
  bool geometry = sslrSurfaceFromDepth(frame.proj, frame.surface, px, depth, q.vsP);
#endif
  q.material = sslrMaterialAt(px, q.texel);
  if (!geometry || !sslrShouldTracePixel(px, depth, q.texel, q.material)) return false;
  sslrDecodeNormal(frame.surface, q.texel, q.vsN);
  q.vsV = sslrViewDirection(frame.proj, q.vsP);
  q.cosVN = dot(-q.vsV, q.vsN);
  if (!(q.cosVN > 0.0f)) return false;  // a normal facing away from the camera has nothing to reflect
  q.vsR = reflect(q.vsV, q.vsN);
  return true;
}

#ifdef SSLR_HALF_QUADS
void sslrTraceQuad(ivec2 quad) {
  // The traced pixel rotates through the quad frame by frame (the first of the four, in that
  // order, that needs tracing), so that a temporal filter would see every pixel's own ray. The
  // pixel is chosen first and traced once after the loop: with the tracer inside the loop, a SIMD
  // batch whose lanes chose different candidates ran the whole tracer once per candidate.
  int start = frame.trace.frameIndex & 3;
  int index = -1;
  ivec2 px;  // the chosen pixel once index >= 0
  SslrPixel q;
  for (int k = 0; k < 4 && index < 0; ++k) {
    int candidate = (start + k) & 3;
    px = quad * 2 + sslrQuadOffset(candidate);
    if (sslrInside(px) && sslrPixelToTrace(px, q)) index = candidate;
  }
  vec4 quadHit = vec4(0.0f);
  vec4 quadSurface = vec4(0.5f);
  if (index >= 0) {
#if defined(SSLR_DEFER_TRAVERSAL) && !defined(SSLR_HALF_QUAD_RETRACE)
    bool needsTraversal;
    SslrHit hit = sslrTraceFirstStage(frame.proj, frame.surface, frame.trace, px, q.vsP, q.vsR, needsTraversal);
    if (needsTraversal) {  // the quad retrace pass traces it (and finds the same pixel of the quad)
      sslrListForRetrace(quad);
#ifdef SSLR_COLLECT_STATS
      atomicAdd(stats.fetches, gFetches);
#endif
      return;
    }
#else
    SslrHit hit = sslrTraceRay(px, q.vsP, q.vsV, q.vsR);
#ifdef SSLR_COUNT_TRAVERSAL
    // Inline under TraversalPass::Auto: count the quads the traversal ran for (its feedback).
    if (hit.hierarchical != 0) atomicAdd(retrace.count, 1u);
#endif
#endif
    float confidence = hit.status == SSLR_STATUS_HIT ? hit.confidence : 0.0f;
    vec3 vsHitNormal = vec3(0.0f, 0.0f, 1.0f);
    if (confidence > 0.0f)
      sslrDecodeNormal(frame.surface, sslrLoadNormal(sslrPixelFromUv(hit.uvHit, sslrSizePx())), vsHitNormal);
    // What the ray says to the quad's other pixels (sslr_shared.h, "Half resolution").
    int kind = SSLR_QUAD_HIT;
    if (confidence == 0.0f)
      kind = hit.status == SSLR_STATUS_MISS && hit.hierarchical == 0 ? SSLR_QUAD_OWN_RAYS : SSLR_QUAD_MISS;
    quadHit = vec4(q.vsP + q.vsR * hit.L, sslrPackQuadCode(confidence, index, kind));
    quadSurface = vec4(sslrOctEncode(q.vsN), sslrOctEncode(vsHitNormal));
#ifdef SSLR_COLLECT_STATS
    atomicAdd(stats.tracedPixels, 1u);
    if (hit.hierarchical != 0) atomicAdd(stats.hierarchicalPixels, 1u);
#endif
  }
  imageStore(uQuadHitOut, quad, quadHit);
  imageStore(uQuadSurfaceOut, quad, quadSurface);
#ifdef SSLR_COLLECT_STATS
  atomicAdd(stats.fetches, gFetches);
#endif
}

void main() {
#ifdef SSLR_HALF_QUAD_RETRACE
  uint slot = retrace.entries[gl_WorkGroupID.x];
  if (gl_LocalInvocationIndex >= tiles.tileCoords[sslrQuadRetraceCountIndex(slot)]) return;
  sslrTraceQuad(sslrUnpackCoord(retrace.entries[sslrQuadRetraceRegion(slot) + gl_LocalInvocationIndex]));
#else
  sslrTraceQuad(sslrTileOrigin(gl_WorkGroupID.x) / 2 + sslrTileQuad(gl_LocalInvocationIndex));
#endif
}
#else

#ifdef SSLR_HALF_RES
// Whether the ray of a quad (of a tile traced this frame: the others hold older frames' records) hit.
bool sslrQuadRayHit(ivec2 quad) {
  ivec2 px = quad * 2;
  if (!sslrInside(px)) return false;
  if (tiles.tileCoords[sslrTileListedStamp(uvec2(px) / uint(SSLR_TILE_SIZE))] != uint(frame.trace.frameIndex))
    return false;
  gFetches += 1u;
  return sslrUnpackQuadCode(texelFetch(uQuadHit, quad, 0).w).confidence > 0.0f;
}

// The quad's ray answers for this pixel when the pixel lies on the traced pixel's surface: its hit
// is re-planed for this pixel's ray (sslrReusedLength) and checked against the depth where it
// lands. A quad's ray that found nothing (left the screen, met the sky, or the traversal gave up)
// is a miss here too unless a neighbouring quad's ray hit. False: trace this pixel's own ray.
bool sslrReuseQuadHit(ivec2 px, vec3 vsP, vec3 vsN, vec3 vsR, out SslrHit hit) {
  hit = sslrNoHit(SSLR_STATUS_MISS);
  ivec2 quad = px / 2;
  vec4 a = texelFetch(uQuadHit, quad, 0);
  vec4 b = texelFetch(uQuadSurface, quad, 0);
  gFetches += 2u;
  SslrQuadCode code = sslrUnpackQuadCode(a.w);
  float confidence = code.confidence;
  ivec2 traced = quad * 2 + sslrQuadOffset(code.index);
  if (traced != px) {  // (the traced pixel's answer is its own ray's)
    vec3 vsTraced;
    if (!sslrLoadSurface(traced, vsTraced)) return false;
    if (!sslrSameSurface(frame.proj, frame.surface, vsP, vsN, vsTraced, sslrOctDecode(b.xy))) return false;
    if (code.kind == SSLR_QUAD_OWN_RAYS) return false;
    if (code.kind == SSLR_QUAD_MISS) {
      // Beside a quad whose ray hit, the miss may be a band along an edge (rays passing behind a
      // box, leaving the screen just past its border): the quads across this pixel's two edges
      // of its quad.
      ivec2 side = ivec2((px.x & 1) != 0 ? 1 : -1, (px.y & 1) != 0 ? 1 : -1);
      if (sslrQuadRayHit(quad + ivec2(side.x, 0)) || sslrQuadRayHit(quad + ivec2(0, side.y))) return false;
    }
  }
  if (!(confidence > 0.0f)) return true;  // a miss for this pixel too
  vec3 vsHitNormal = sslrOctDecode(b.zw);
  float L = traced == px ? length(a.xyz - vsP) : sslrReusedLength(vsP, vsR, a.xyz, vsHitNormal);
  if (!(L > 0.0f)) return false;
  vec3 vsQ = vsP + vsR * L;
  if (sslrClipW(frame.proj, vsQ) <= 0.0f) return false;
  if (traced != px) {
    // The re-planed point must lie on what its pixel shows (else the reflected surface ended
    // between the two rays: a silhouette).
    vec3 ndcQ = sslrNdcFromView(frame.proj, vsQ);
    ivec2 landed = sslrPixelFromUv(sslrUvFromNdc(vec2(ndcQ.x, ndcQ.y)), sslrSizePx());
    vec3 vsSurface;
    if (!sslrLoadSurface(landed, vsSurface)) return false;
    float dist = frame.proj.orthographic != 0 ? abs(vsSurface.z) : sslrViewDistance(frame.proj, vsSurface);
    float tolerance = sslrHitTolerance(frame.proj, frame.surface, frame.trace, dist,
                                       sslrSlopeTan(frame.proj, vsSurface, vsHitNormal));
    if (length(vsQ - vsSurface) > tolerance) return false;
  }
  hit = sslrFinishHit(frame.proj, hit, vsP, vsR, L, confidence);
  return true;
}
#endif

// Traces (or reuses) and shades one pixel: reflection, resolved, debug images, stats, blur list.
void sslrShadePixel(ivec2 px) {
  SslrHit hit = sslrNoHit(SSLR_STATUS_NOT_TRACED);
  vec4 reflection = vec4(0.0f);
  float coverage = 0.0f;
  bool ranTracer = false;  // stats: half resolution answers most pixels from their quad's ray

  SslrPixel q;
  if (sslrPixelToTrace(px, q)) {
#if defined(SSLR_HALF_RES) || defined(SSLR_DEFER_TRAVERSAL)
#ifdef SSLR_HALF_RES
    bool answered = sslrReuseQuadHit(px, q.vsP, q.vsN, q.vsR, hit);
#else
    bool needsTraversal;
    hit = sslrTraceFirstStage(frame.proj, frame.surface, frame.trace, px, q.vsP, q.vsR, needsTraversal);
    bool answered = !needsTraversal;
    ranTracer = answered;
#endif
    if (!answered) {
      // Its own ray, in the retrace pass, which also writes this pixel's outputs.
      sslrListForRetrace(px);
#ifdef SSLR_COLLECT_STATS
      atomicAdd(stats.fetches, gFetches);
#endif
      return;
    }
#else
    hit = sslrTraceRay(px, q.vsP, q.vsV, q.vsR);
    ranTracer = true;
#ifdef SSLR_COUNT_TRAVERSAL
    // Inline under TraversalPass::Auto: count the pixels the traversal ran for (its feedback).
    if (hit.hierarchical != 0) atomicAdd(retrace.count, 1u);
#endif
#endif
    if (hit.status == SSLR_STATUS_HIT) {
      SslrWeights w = sslrReflectionWeights(frame.proj, frame.surface, frame.trace, hit, q.vsP, q.vsV, q.vsR,
                                            q.cosVN, sslrReflectance(frame.surface, q.material),
                                            sslrRoughness(frame.surface, q.material));
      vec3 color = textureLod(uColor, hit.uvHit, 0.0f).rgb;
      // Poisoned colour must not spread through the blur: NaN/Inf become 0, and the value is
      // kept inside RGBA16F's range.
      if (any(isnan(color)) || any(isinf(color))) color = vec3(0.0f);
      color = clamp(color, vec3(0.0f), vec3(60000.0f));
      reflection = vec4(color * w.reflection, w.blurAlpha);
      coverage = w.coverage;
    }
  }
  imageStore(uReflection, px, reflection);
  // Resolved before the blur: the same rgb with the coverage in alpha (the blur reads it from here).
  imageStore(uResolved, px, vec4(reflection.rgb, coverage));
#if defined(SSLR_DEBUG_OUTPUTS) || defined(SSLR_TEMPORAL_HITS)
  imageStore(uHit, px, vec4(hit.uvHit, hit.confidence, hit.L));
#endif
#ifdef SSLR_DEBUG_OUTPUTS
  imageStore(uIterations, px, vec4(float(hit.iterations)));
#endif
#ifdef SSLR_COLLECT_STATS
  if (ranTracer) atomicAdd(stats.tracedPixels, 1u);
  atomicAdd(stats.fetches, gFetches);
  if (hit.hierarchical != 0) atomicAdd(stats.hierarchicalPixels, 1u);
#endif
  // The first pixel of a tile that needs blurring lists the tile (no group barrier: on CPU
  // rasterizers barriers split the shader and cost more than this atomic).
  if (reflection.a * frame.trace.blurMaxRadiusPx >= 0.5f) sslrListTileForBlur(px);
}

void main() {
#ifdef SSLR_HALF_RETRACE
  uint i = gl_GlobalInvocationID.x;
  if (i >= retrace.count) return;
  ivec2 px = sslrUnpackCoord(retrace.entries[i]);
#else
  ivec2 px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;
#endif
  sslrShadePixel(px);
}
#endif  // SSLR_HALF_QUADS
