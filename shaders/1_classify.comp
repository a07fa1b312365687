// Pass 1, classification (passes.cpp runClassify): one invocation per 2x2 quad. The first quad of
// a tile found to need tracing appends the tile to the tile list (a per-tile stamp says "listed
// this frame"); every later pass runs over listed tiles only.
// With SSLR_CLASSIFY_LEVEL1 (the pyramid is on) each quad also writes the pyramid's levels 0 and 1
// from the depths it reads anyway (passes/pyramid_levels01.glsl).
//
// Two shapes (DeviceProfile), the same outputs:
// - Software: a group per tile (16 invocations along x: llvmpipe fills its SIMD lanes along x), no
//   shared memory and no barrier (on CPU rasterizers a barrier splits the shader). The clean-up
//   (1_clear_untraced.comp) and the pyramid's arguments (2_pyramid_arguments.comp) are passes of
//   their own.
// - Gpu (SSLR_CLASSIFY_WIDE): a group per 2x2 tiles (64 invocations: no half-empty warp). After a
//   barrier each tile knows whether it was listed, and a tile traced last frame and not now clears
//   its pixels of the outputs here; the first tile listed sets the pyramid's dispatches
//   (SSLR_CLASSIFY_ARGS). One dispatch and one barrier where Software has three of each.
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"
#ifdef SSLR_CLASSIFY_LEVEL1
#include "passes/pyramid_levels01.glsl"
#endif

#ifdef SSLR_CLASSIFY_WIDE
#define SSLR_CLASSIFY_TILES 4  // 2x2 tiles a group
layout(binding = SSLR_IMAGE_CLASSIFY_REFLECTION, rgba16f) uniform writeonly image2D uReflection;
layout(binding = SSLR_IMAGE_CLASSIFY_RESOLVED, rgba16f) uniform writeonly image2D uResolved;
shared uint sTileListed[SSLR_CLASSIFY_TILES];
#else
#define SSLR_CLASSIFY_TILES 1
#endif

layout(local_size_x = SSLR_CLASSIFY_TILES * SSLR_TILE_QUADS) in;  // the tiles' quads (sslrTileQuad)

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

// Appends `tile` to the tile list once per frame.
void listTile(uvec2 tile) {
  uint stamp = sslrTileListedStamp(tile);
  uint frameIndex = uint(frame.trace.frameIndex);
  // The plain read spares the atomic to all but the first few quads of a listed tile.
  if (tiles.tileCoords[stamp] == frameIndex || atomicExchange(tiles.tileCoords[stamp], frameIndex) == frameIndex)
    return;
  uint slot = atomicAdd(tiles.dispatchX, 1u);
  atomicAdd(tiles.drawInstances, 1u);
  tiles.tileCoords[slot] = sslrPackCoord(ivec2(tile));
  tiles.tileCoords[sslrQuadRetraceCountIndex(slot)] = 0u;
#ifdef SSLR_CLASSIFY_WIDE
  if ((slot & 3u) == 0u) atomicAdd(tiles.quadDispatchX, 1u);  // half resolution's quad pass: 4 tiles a group
#endif
#ifdef SSLR_CLASSIFY_ARGS
  // The frame traces: the pyramid's dispatches get their group counts (else they stay at zero).
  if (slot == 0u)
    for (int i = 0; i < 3 * SSLR_HIZ_MAX_LEVELS; ++i) tiles.hizDispatch[i] = tiles.hizGroups[i];
#endif
}

#ifdef SSLR_CLASSIFY_WIDE
// The clean-up of 1_clear_untraced.comp for this quad's pixels: zeros where the tile was traced in
// the previous frame (its stamp holds that frame's index: not overwritten, as this frame did not
// list it) and is not listed in this one.
void clearIfUntraced(uvec2 tile, ivec2 cell, bool listed) {
  uint frameIndex = uint(frame.trace.frameIndex);
  uint previous = frameIndex == 1u ? 0x7fffffffu : frameIndex - 1u;  // dispatch() wraps the index to 1
  if (listed || tiles.tileCoords[sslrTileListedStamp(tile)] != previous) return;
  for (int i = 0; i < 4; ++i) {
    ivec2 px = cell * 2 + ivec2(i & 1, i >> 1);
    if (!sslrInside(px)) continue;
    imageStore(uReflection, sslrTexel(px), vec4(0.0f));
    imageStore(uResolved, sslrTexel(px), vec4(0.0f));
  }
}
#endif

void main() {
  uint tileInGroup = gl_LocalInvocationIndex / uint(SSLR_TILE_QUADS);
  uvec2 tile = gl_WorkGroupID.xy * (SSLR_CLASSIFY_TILES == 4 ? 2u : 1u) + uvec2(tileInGroup & 1u, tileInGroup >> 1);
  ivec2 cell = ivec2(tile) * (SSLR_TILE_SIZE / 2) + sslrTileQuad(gl_LocalInvocationIndex % uint(SSLR_TILE_QUADS));
#ifdef SSLR_CLASSIFY_WIDE
  // The grid's last row and column of groups may hold tiles past the screen: they do nothing but
  // take part in the barriers.
  bool onGrid = tile.x < sslrTilesX() && tile.y < sslrTilesY();
  if (gl_LocalInvocationIndex % uint(SSLR_TILE_QUADS) == 0u) sTileListed[tileInGroup] = 0u;
  barrier();
#else
  const bool onGrid = true;  // a group per tile of the grid
#endif
  bool trace = false;
  if (onGrid) {
    vec4 depths = SSLR_GATHER_QUAD(uDepth, cell, 0);
    // (A quad wholly past the frame's edge holds no pixel of it.)
    trace = all(lessThan(cell * 2, ivec2(frame.surface.width, frame.surface.height))) && quadHasCandidate(cell, depths);
#ifdef SSLR_CLASSIFY_LEVEL1
    // (Gpu: the pass counts the curved pass's groups itself; the curved pass exits at once in a
    // frame that lists no tile.)
    sslrWriteLevels01(cell, depths, SSLR_CLASSIFY_TILES == 4);
#endif
    if (trace) listTile(tile);
  }
#ifdef SSLR_CLASSIFY_WIDE
  if (trace) atomicOr(sTileListed[tileInGroup], 1u);
  memoryBarrierShared();
  barrier();
  if (onGrid) clearIfUntraced(tile, cell, sTileListed[tileInGroup] != 0u);
#endif
}
