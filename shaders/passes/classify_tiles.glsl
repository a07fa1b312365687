// Classification's shared part (1_classify.comp, 1_classify_wide.comp): whether a quad holds a
// pixel that may need a ray, and the tile list's append.
#ifndef SSLR_PASSES_CLASSIFY_TILES_GLSL
#define SSLR_PASSES_CLASSIFY_TILES_GLSL
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#include "common/quads.glsl"
#ifdef SSLR_CLASSIFY_LEVEL1  // the pyramid is on: levels 0 and 1 from the depths read here
#include "passes/pyramid_levels01.glsl"
#endif

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

// Appends `tile` to the tile list once per frame; true (and its slot) for the quad that did.
bool listTile(uvec2 tile, out uint slot) {
  slot = 0u;
  uint stamp = sslrTileListedStamp(tile);
  uint frameIndex = uint(frame.trace.frameIndex);
  // The plain read spares the atomic to all but the first few quads of a listed tile.
  if (tiles.tileCoords[stamp] == frameIndex || atomicExchange(tiles.tileCoords[stamp], frameIndex) == frameIndex)
    return false;
  slot = atomicAdd(tiles.dispatchX, 1u);
  atomicAdd(tiles.drawInstances, 1u);
  tiles.tileCoords[slot] = sslrPackCoord(ivec2(tile));
  tiles.tileCoords[sslrQuadRetraceCountIndex(slot)] = 0u;
  return true;
}

// The depths of the quad at `cell` and whether it needs tracing; with SSLR_CLASSIFY_LEVEL1 it also
// writes the pyramid's levels 0 and 1 from them (wide: the group holds 2x2 tiles).
bool classifyQuad(ivec2 cell, bool wide) {
  vec4 depths = SSLR_GATHER_QUAD(uDepth, cell, 0);
  // (A quad wholly past the frame's edge holds no pixel of it.)
  bool trace = all(lessThan(cell * 2, ivec2(frame.surface.width, frame.surface.height))) && quadHasCandidate(cell, depths);
#ifdef SSLR_CLASSIFY_LEVEL1
  // (Gpu: the pass counts the curved pass's groups itself; the curved pass exits at once in a
  // frame that lists no tile.)
  sslrWriteLevels01(cell, depths, wide);
#endif
  return trace;
}

#endif  // SSLR_PASSES_CLASSIFY_TILES_GLSL
