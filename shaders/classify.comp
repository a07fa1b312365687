// Pass 1 (classification; passes.cpp runClassify): tile classification, one invocation per 2x2 quad: the first quad of an 8x8 tile found
// to need tracing appends the tile to the tile list (a per-tile stamp says "listed this frame");
// all later passes run over listed tiles only. No shared memory and no barrier: on CPU
// rasterizers a barrier splits the shader (an empty frame took 1.12x as long with the group flag
// and barriers, in an interleaved A/B). With SSLR_CLASSIFY_LEVEL1 (the traversal is on) each quad
// also writes its pixels' texels of level 0 and its (min, max) depth, level 1 of the depth
// pyramid, from the reads classification makes anyway (for level 1, a separate pass read every
// depth a second time; sky-heavy 960x540 on llvmpipe: the default 1.67-1.91x -> 1.28-1.49x the
// tutorial's time, an empty frame 0.73 -> 0.85x the baseline pass in one A/B; level 0's four
// stores per quad cost 0.6-0.9 ms and save the traversal up to two fetches per step; quads of
// sky alone get none, docs/algorithm.md "Level 0 in the pyramid").
//
// With SSLR_CLEANUP the same file is the clean-up pass, run after classification over the
// previous frame's traced tiles: those not listed again are zeroed. The outputs are never cleared
// whole: the trace writes every pixel of a listed tile, so after a frame only its listed tiles
// can be non-zero, and an empty frame after an empty frame only reads the G-buffer.
//
// With SSLR_PYRAMID_ARGS it is a one-group pass that turns the pyramid's dispatches on when a
// tile was listed. That copy is not in the classification itself: llvmpipe runs every
// instruction of a shader under lane masks, taken branch or not, and the 24-word copy there made
// classification 2.5x slower (measured).
//
// With SSLR_LEVEL1_PASS it writes levels 0 and 1 alone, in a frame after one that listed no tile
// (whose classification then skips them); with SSLR_CURVED_PASS it computes the level-1 cells of
// the quads classification listed for their turning normals and their pixels' extra depths in
// level 0 (curved solids, sslr_shared.h).
#include "common/gbuffer.glsl"
#include "common/tiles.glsl"

#if defined(SSLR_CURVED_SOLIDS) && SSLR_CURVED_SOLIDS
// Curved solids (sslr_shared.h): classification lists the quads whose normals turn; the curved
// pass (SSLR_CURVED_PASS) computes their cells. Their math in classification itself cost every
// quad of the screen (llvmpipe runs it under lane masks): sky-heavy's classification 4.0 -> 5.9 ms.
layout(std430, binding = SSLR_BINDING_CURVED_SSBO) buffer SslrCurvedQuads {
  uint dispatchX;  // DispatchIndirectCommand of the curved pass: the pyramid-args pass sets x
  uint dispatchY;
  uint dispatchZ;
  uint groups;     // groups of 64 listed quads (classification counts them)
  uint count;      // listed quads
  uint pad0, pad1, pad2;
  uint quads[];    // cell x | cell y << 16
} curved;
#endif

#if defined(SSLR_CURVED_PASS)
// A 2x2 quad of the G-buffer (level 1's cell `cell`): its pixels clamped to the screen
// (sslrQuadPixel), their depths and packed normal texels, for the curved pass's math.
// Straight-line code (a loop with per-pixel branches ran 2x slower on llvmpipe).
struct SslrQuad {
  ivec2 p0, p1, p2, p3;
  vec4 depths;
  vec4 n0, n1, n2, n3;
};
SslrQuad sslrLoadQuad(ivec2 cell) {
  ivec2 last = ivec2(frame.surface.width, frame.surface.height) - 1;
  SslrQuad q;
  q.p0 = sslrQuadPixel(cell, 0, last);
  q.p1 = sslrQuadPixel(cell, 1, last);
  q.p2 = sslrQuadPixel(cell, 2, last);
  q.p3 = sslrQuadPixel(cell, 3, last);
  q.depths = vec4(texelFetch(uDepth, q.p0, 0).r, texelFetch(uDepth, q.p1, 0).r, texelFetch(uDepth, q.p2, 0).r,
                  texelFetch(uDepth, q.p3, 0).r);
  q.n0 = texelFetch(uNormal, q.p0, 0);
  q.n1 = texelFetch(uNormal, q.p1, 0);
  q.n2 = texelFetch(uNormal, q.p2, 0);
  q.n3 = texelFetch(uNormal, q.p3, 0);
  return q;
}
#endif

#if defined(SSLR_CURVED_PASS)
layout(local_size_x = 64) in;
#elif defined(SSLR_CLEANUP) || defined(SSLR_PYRAMID_ARGS) || defined(SSLR_LEVEL1_PASS)
layout(local_size_x = SSLR_TILE_SIZE, local_size_y = SSLR_TILE_SIZE) in;
#else
layout(local_size_x = SSLR_TILE_QUADS) in;  // a tile's quads (sslrTileQuad)
#endif

#ifdef SSLR_CLEANUP
#ifdef SSLR_CLEANUP_HISTORY
// Temporal reuse, after this frame's history is stored: the tiles traced last frame and not now
// lose their history keys, so next frame finds history only where this frame stored it.
layout(binding = SSLR_IMAGE_HISTORY_KEY, r32f) uniform writeonly image2D uHistoryKey;
#else
layout(binding = SSLR_IMAGE_REFLECTION, rgba16f) uniform writeonly image2D uReflection;
layout(binding = SSLR_IMAGE_RESOLVED, rgba16f) uniform writeonly image2D uResolved;
#endif

void main() {
  uint entry = tiles.tileCoords[4u * sslrTileCapacity() + gl_WorkGroupID.x];
  uvec2 tile = uvec2(sslrUnpackCoord(entry));
  if (tiles.tileCoords[sslrTileListedStamp(tile)] == uint(frame.trace.frameIndex)) return;  // traced again
  ivec2 px = ivec2(tile) * SSLR_TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  if (!sslrInside(px)) return;
#ifdef SSLR_CLEANUP_HISTORY
  imageStore(uHistoryKey, px, vec4(0.0f));
#else
  imageStore(uReflection, px, vec4(0.0f));
  imageStore(uResolved, px, vec4(0.0f));
#endif
}
#elif defined(SSLR_PYRAMID_ARGS)
void main() {
  // A frame that traces needs the pyramid: its dispatches get their real group counts.
  if (gl_LocalInvocationIndex == 0u && tiles.dispatchX != 0u) {
    for (int i = 0; i < 3 * SSLR_HIZ_MAX_LEVELS; ++i) tiles.hizDispatch[i] = tiles.hizGroups[i];
#if defined(SSLR_CURVED_SOLIDS) && SSLR_CURVED_SOLIDS
    curved.dispatchX = curved.groups;  // and the curved quads' cells
#endif
  }
}
#else
#if defined(SSLR_CLASSIFY_LEVEL1) || defined(SSLR_LEVEL1_PASS) || defined(SSLR_CURVED_PASS)
layout(binding = SSLR_IMAGE_PYRAMID_LEVEL1, rg32f) uniform writeonly image2D uLevel1;  // the pyramid's level 1 (mip 1)
layout(binding = SSLR_IMAGE_PYRAMID_LEVEL0, rg32f) uniform writeonly image2D uLevel0;  // its level 0 (mip 0)

// The level-0 texels of level-1 cell `cell`'s pixels. Where the quad straddles the screen's edge,
// `depths` and `extra` repeat a pixel of the quad for the one past the edge, which lands in the
// level's padding (never read: the traversal stays on the screen); stores without a condition.
void writeLevel0(ivec2 cell, vec4 depths, vec4 extra) {
  ivec2 px = cell * 2;
  imageStore(uLevel0, px, vec4(sslrHiZLevel0Texel(frame.surface, depths.x, extra.x), 0.0f, 0.0f));
  imageStore(uLevel0, px + ivec2(1, 0), vec4(sslrHiZLevel0Texel(frame.surface, depths.y, extra.y), 0.0f, 0.0f));
  imageStore(uLevel0, px + ivec2(0, 1), vec4(sslrHiZLevel0Texel(frame.surface, depths.z, extra.z), 0.0f, 0.0f));
  imageStore(uLevel0, px + 1, vec4(sslrHiZLevel0Texel(frame.surface, depths.w, extra.w), 0.0f, 0.0f));
}
#endif

#if defined(SSLR_CURVED_PASS)
void main() {
  // The listed quads' level-1 cells with their solids (over the plain cells classification wrote),
  // and their pixels' extra depths in level 0 (classification wrote none).
  if (gl_GlobalInvocationID.x >= curved.count) return;
  uint entry = curved.quads[gl_GlobalInvocationID.x];
  ivec2 cell = sslrUnpackCoord(entry);
  SslrQuad q = sslrLoadQuad(cell);
  vec4 extra;
  vec2 level1 = sslrHiZLevel1Cell(frame.proj, frame.surface, frame.trace, q.p0, q.p1, q.p2, q.p3, q.depths, q.n0, q.n1,
                                  q.n2, q.n3, extra);
  imageStore(uLevel1, cell, vec4(level1, 0.0f, 0.0f));
  writeLevel0(cell, q.depths, extra);
}
#else
#if defined(SSLR_CLASSIFY_LEVEL1) || defined(SSLR_LEVEL1_PASS)

// Whether the quad's normals turn (sslrQuadNormalsTurn), from its normal channels gathered: two
// (octahedral) or three (xyz); the material channels do not take part.
bool quadNormalsTurn(ivec2 cell) {
  vec4 x = SSLR_GATHER_QUAD(uNormal, cell, 0);
  vec4 y = SSLR_GATHER_QUAD(uNormal, cell, 1);
#if SSLR_NORMAL_ENCODING == SSLR_NORMALS_OCTAHEDRAL
  vec4 z = vec4(0.0f);
#else
  vec4 z = SSLR_GATHER_QUAD(uNormal, cell, 2);
#endif
  return sslrQuadNormalsTurn(vec4(x.x, y.x, z.x, 0.0f), vec4(x.y, y.y, z.y, 0.0f), vec4(x.z, y.z, z.z, 0.0f),
                             vec4(x.w, y.w, z.w, 0.0f));
}

// Level 1's cell `cell` from its quad's depths (SSLR_GATHER_QUAD), and its pixels' level-0 texels.
void writeLevels01(ivec2 cell, vec4 depths) {
  // The gather's clamp repeats a pixel of the same quad when the quad straddles the screen's edge
  // (neutral for the min-max, harmless for the flag); a quad wholly outside is empty.
#if defined(SSLR_BACK_DEPTH) && SSLR_BACK_DEPTH
  // Measured thickness (sslr_shared.h): the solids' backs in level 1, their extra depths in level 0.
  vec4 extra;
  vec2 level1 = sslrHiZLevel1Measured(frame.proj, frame.surface, frame.trace, depths,
                                      SSLR_GATHER_QUAD(uBackDepth, cell, 0), extra);
#else
  vec2 level1 = sslrHiZLevel1Plain(frame.surface, depths);
  vec4 extra = vec4(0.0f);
#endif
  bool outside = any(greaterThan(cell * 2, ivec2(frame.surface.width, frame.surface.height) - 1));
  if (outside) level1 = sslrHiZEmpty();
  if (all(lessThan(cell, imageSize(uLevel1)))) {
    imageStore(uLevel1, cell, vec4(level1, 0.0f, 0.0f));
    // A quad of background alone gets no level-0 texels: the traversal skips its level-1 cell
    // (nothing there can stop a ray) and never reads them. On sparse frames most quads are sky.
    if (!outside && sslrHiZCellHoldsGeometry(frame.surface, level1)) writeLevel0(cell, depths, extra);
#if defined(SSLR_CURVED_SOLIDS) && SSLR_CURVED_SOLIDS
    // Curved surfaces reach deeper than the slab (sslr_shared.h, "Curved solids"): a quad whose
    // normals turn is listed for the curved pass, which overwrites its cell with the solids' backs
    // and its pixels' level-0 texels with their extra depths.
    if (!outside && quadNormalsTurn(cell)) {
      uint slot = atomicAdd(curved.count, 1u);
#ifdef SSLR_LEVEL1_PASS
      if ((slot & 63u) == 0u) atomicAdd(curved.dispatchX, 1u);  // this pass runs only when a tile is listed
#else
      if ((slot & 63u) == 0u) atomicAdd(curved.groups, 1u);  // the pyramid-args pass turns them on
#endif
      curved.quads[slot] = sslrPackCoord(cell);
    }
#endif
  }
}
#endif

#ifndef SSLR_LEVEL1_PASS
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
#endif

// One invocation per 2x2 quad (one group per 8x8 tile; SSLR_LEVEL1_PASS: per 8x8 cells of
// level 1).
void main() {
#ifdef SSLR_LEVEL1_PASS
  ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
#else
  ivec2 cell = ivec2(gl_WorkGroupID.xy) * (SSLR_TILE_SIZE / 2) + sslrTileQuad(gl_LocalInvocationIndex);
#endif
  vec4 depths = SSLR_GATHER_QUAD(uDepth, cell, 0);
#ifdef SSLR_LEVEL1_PASS
  // Levels 0 and 1 alone, in a frame whose classification skipped them (the frame before listed
  // no tile): dispatched through the pyramid's arguments, so only when this frame lists a tile.
  writeLevels01(cell, depths);
#else
  bool trace = quadHasCandidate(cell, depths);
#ifdef SSLR_CLASSIFY_LEVEL1
  writeLevels01(cell, depths);
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
#endif
}
#endif  // SSLR_CURVED_PASS
#endif
