// Pass 3, half resolution's shading (passes/trace.cpp runTrace; Settings::halfResolution): one
// invocation per pixel of a listed tile reuses its quad's ray (3_trace_quads.comp) where the pixel
// lies on the traced pixel's surface, and lists the others for the retrace (3_trace.comp). No
// tracer runs here: a CPU rasterizer would run its code under lane masks for every pixel.
#include "passes/trace_common.glsl"
#include "passes/retrace_list.glsl"
#include "passes/shade_pixel.glsl"
#include "shared/half_resolution.h"

layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;

layout(binding = SSLR_UNIT_QUAD_HIT) uniform SSLR_SAMPLER uQuadHit;          // xyz: view-space hit point; w: sslrPackQuadCode
layout(binding = SSLR_UNIT_QUAD_SURFACE) uniform SSLR_SAMPLER uQuadSurface;  // xy: traced pixel's octahedral normal; zw: hit surface's

// Whether the ray of a quad (of a tile traced this frame: the others hold older frames' records) hit
// (a guess is not a hit: SSLR_QUAD_MISS).
bool sslrQuadRayHit(ivec2 quad) {
  ivec2 px = quad * 2;
  if (!sslrInside(px)) return false;
  if (tiles.tileCoords[sslrTileListedStamp(uvec2(px) / uint(SSLR_TILE_SIZE))] != uint(frame.trace.frameIndex))
    return false;
  gFetches += 1u;
  SslrQuadCode code = sslrUnpackQuadCode(texelFetch(uQuadHit, SSLR_AT(quad), 0).w);
  return code.kind == SSLR_QUAD_HIT && code.confidence > 0.0f;
}

// The quad's ray answers for this pixel when the pixel lies on the traced pixel's surface: its hit
// is re-planed for this pixel's ray (sslrReusedLength) and checked against the depth where it
// lands. A quad's ray that found nothing (left the screen, met the sky, or the traversal gave up)
// is a miss here too unless a neighbouring quad's ray hit. False: trace this pixel's own ray.
bool sslrReuseQuadHit(ivec2 px, vec3 vsP, vec3 vsN, vec3 vsR, out SslrHit hit) {
  hit = sslrNoHit(SSLR_STATUS_MISS);
  ivec2 quad = px / 2;
  vec4 a = texelFetch(uQuadHit, SSLR_AT(quad), 0);
  vec4 b = texelFetch(uQuadSurface, SSLR_AT(quad), 0);
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
    float dist = sslrOrthographic(frame.proj) ? abs(vsSurface.z) : sslrViewDistance(frame.proj, vsSurface);
    float tolerance = sslrHitTolerance(frame.proj, frame.surface, dist,
                                       sslrSlopeTan(frame.proj, vsSurface, vsHitNormal));
    if (length(vsQ - vsSurface) > tolerance) return false;
  }
  hit = sslrFinishHit(frame.proj, hit, vsP, vsR, L, confidence);
  return true;
}

bool sslrPixelHit(ivec2 px, SslrPixel q, out SslrHit hit, out bool ranTracer) {
  ranTracer = false;
  if (sslrReuseQuadHit(px, q.vsP, q.vsN, q.vsR, hit)) return true;
  sslrListPixelForRetrace(px);  // its own ray, in the retrace pass
  return false;
}

void main() {
  ivec2 px = sslrTileOrigin(gl_WorkGroupID.x) + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;
  sslrShadePixel(px);  // traces nothing itself (its pixels without an answer go to the retrace pass)
}
