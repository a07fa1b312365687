// Half resolution's quad ray (sslr_shared.h, "Half resolution"): one ray per 2x2 quad, from the
// first pixel of the quad, in a rotating order, that needs one; its hit, confidence and both
// surfaces' normals go to the quad images that the shading pass reuses.
#include "shared/half_resolution.h"
layout(binding = SSLR_IMAGE_QUAD_HIT, rgba32f) uniform writeonly SSLR_IMAGE uQuadHitOut;          // see uQuadHit
layout(binding = SSLR_IMAGE_QUAD_SURFACE, rgba16f) uniform writeonly SSLR_IMAGE uQuadSurfaceOut;  // see uQuadSurface

// `slot`: the quad's tile's slot in the tile list. Returns the dependent steps of the tracer run
// here (0 where none ran: FrameStats' ray work).
uint sslrTraceQuad(uint slot, ivec2 quad) {
  // The traced pixel rotates through the quad frame by frame, so that a temporal filter sees every
  // pixel's own ray. The pixel is chosen first and traced once after the loop: with the tracer
  // inside the loop, a SIMD batch whose lanes chose different candidates ran it once per candidate.
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
  uint steps = 0u;
  if (index >= 0) {
#ifdef SSLR_DEFER_TRAVERSAL
    bool needsTraversal;
    SslrHit hit = sslrTraceFirstStage(frame.proj, frame.surface, sslrRayParams(q), px, q.vsP, q.vsR, needsTraversal);
    if (needsTraversal) {  // the quad retrace pass traces it (and finds the same pixel of the quad)
      sslrListQuadForRetrace(slot, quad);
#ifdef SSLR_COLLECT_STATS
      atomicAdd(stats.fetches, gFetches);
#endif
      return uint(hit.iterations);
    }
#else
    SslrHit hit = sslrTraceRay(sslrRayParams(q), px, q.vsP, q.vsV, q.vsR);
#ifdef SSLR_COUNT_TRAVERSAL
    // Inline under TraversalPass::Auto: count the quads the traversal ran for (its feedback).
    if (uRetrace == 0 && sslrRanSecondStage(frame.trace, hit)) atomicAdd(retrace.count, 1u);
#endif
#endif
    steps = uint(hit.iterations);
    float confidence = hit.status == SSLR_STATUS_HIT ? hit.confidence : 0.0f;
    vec3 vsHitNormal = vec3(0.0f, 0.0f, 1.0f);
    if (confidence > 0.0f)
      sslrDecodeNormal(frame.surface, sslrLoadNormal(sslrPixelFromUv(hit.uvHit, sslrSizePx())), vsHitNormal);
    // What the ray says to the quad's other pixels (sslr_shared.h, "Half resolution").
    int kind = SSLR_QUAD_HIT;
    if (confidence == 0.0f)
      kind = hit.status == SSLR_STATUS_MISS && hit.hierarchical == 0 ? SSLR_QUAD_OWN_RAYS : SSLR_QUAD_MISS;
    else if (hit.guessed != 0)  // adaptive L alone's guess: each pixel's own ray may converge
      kind = hit.hierarchical == 0 ? SSLR_QUAD_OWN_RAYS : SSLR_QUAD_MISS;
    quadHit = vec4(q.vsP + q.vsR * hit.L, sslrPackQuadCode(confidence, index, kind));
    quadSurface = vec4(sslrOctEncode(q.vsN), sslrOctEncode(vsHitNormal));
#ifdef SSLR_COLLECT_STATS
    atomicAdd(stats.tracedPixels, 1u);
    if (hit.hierarchical != 0) atomicAdd(stats.hierarchicalPixels, 1u);
#endif
  }
  imageStore(uQuadHitOut, SSLR_AT(quad), quadHit);
  imageStore(uQuadSurfaceOut, SSLR_AT(quad), quadSurface);
#ifdef SSLR_COLLECT_STATS
  atomicAdd(stats.fetches, gFetches);
#endif
  return steps;
}
