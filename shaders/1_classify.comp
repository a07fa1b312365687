// Pass 1, classification (passes.cpp runClassify): one invocation per 2x2 quad, one group per 8x8
// tile. The first quad of a tile found to need tracing appends the tile to the tile list (a
// per-tile stamp says "listed this frame"); every later pass runs over listed tiles only. No
// shared memory and no barrier (on CPU rasterizers a barrier splits the shader).
// With SSLR_CLASSIFY_LEVEL1 (the pyramid is on) each quad also writes the pyramid's levels 0 and 1
// from the depths it reads anyway (passes/pyramid_levels01.glsl).
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#ifdef SSLR_CLASSIFY_LEVEL1
#include "passes/pyramid_levels01.glsl"
#endif

layout(local_size_x = SSLR_TILE_QUADS) in;  // a tile's quads (sslrTileQuad)

// Whether a pixel of the quad may need a ray (sslrTraceCandidate, inside the host's mask): the
// channels it needs, gathered. The normal's decode is left to the trace (sslrShouldTrace), which
// writes every pixel of a listed tile: a tile listed for a pixel whose normal does not decode
// traces nothing and outputs zeros, as unlisted.
bool quadHasCandidate(ivec2 cell, vec4 depths) {
  vec4 reflectance = sslrQuadReflectance(cell);
  vec4 roughness = sslrQuadRoughness(cell);
#ifdef SSLR_HAS_MASK
  bvec4 inMask = greaterThan(SSLR_GATHER_QUAD(uMask, cell, 0), vec4(0.5f));
#else
  bvec4 inMask = bvec4(true);
#endif
  SslrSurface s = frame.surface;
  SslrTraceParams t = frame.trace;
  return (inMask.x && sslrTraceCandidate(s, t, depths.x, reflectance.x, roughness.x)) ||
         (inMask.y && sslrTraceCandidate(s, t, depths.y, reflectance.y, roughness.y)) ||
         (inMask.z && sslrTraceCandidate(s, t, depths.z, reflectance.z, roughness.z)) ||
         (inMask.w && sslrTraceCandidate(s, t, depths.w, reflectance.w, roughness.w));
}

void main() {
  ivec2 cell = ivec2(gl_WorkGroupID.xy) * (SSLR_TILE_SIZE / 2) + sslrTileQuad(gl_LocalInvocationIndex);
  vec4 depths = SSLR_GATHER_QUAD(uDepth, cell, 0);
  bool trace = quadHasCandidate(cell, depths);
#ifdef SSLR_CLASSIFY_LEVEL1
  sslrWriteLevels01(cell, depths, false);
#endif
  if (!trace) return;
  uint stamp = sslrTileListedStamp(gl_WorkGroupID.xy);
  uint frameIndex = uint(frame.trace.frameIndex);
  // The plain read spares the atomic to all but the first few quads of a listed tile.
  if (tiles.tileCoords[stamp] == frameIndex || atomicExchange(tiles.tileCoords[stamp], frameIndex) == frameIndex)
    return;
  uint slot = atomicAdd(tiles.dispatchX, 1u);
  atomicAdd(tiles.drawInstances, 1u);
  tiles.tileCoords[slot] = sslrPackCoord(ivec2(gl_WorkGroupID.xy));
  tiles.tileCoords[sslrQuadRetraceCountIndex(slot)] = 0u;
}
