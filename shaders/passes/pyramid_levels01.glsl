// Levels 0 and 1 of the min-max depth pyramid (sslr_shared.h, "Min-max depth pyramid"), written
// from the depths of one 2x2 quad: level 1's cell holds the quad's (min, max), level 0 its pixels'
// texels. Used by classification (which reads every depth anyway), the levels-0-and-1 pass and
// the curved pass.
#include "common/quads.glsl"
#include "shared/thickness.h"
#if defined(SSLR_CURVED_SOLIDS) && SSLR_CURVED_SOLIDS
#include "passes/curved_quads.glsl"
#endif

layout(binding = SSLR_IMAGE_PYRAMID_LEVEL1, rg32f) uniform writeonly SSLR_IMAGE uLevel1;  // the pyramid's level 1 (mip 1)
layout(binding = SSLR_IMAGE_PYRAMID_LEVEL0, rg32f) uniform writeonly SSLR_IMAGE uLevel0;  // its level 0 (mip 0)

// The level-0 texels of level-1 cell `cell`'s pixels. Where the quad straddles the screen's edge,
// `depths` and `extra` repeat a pixel of the quad for the one past the edge, which lands in the
// level's padding (never read: the traversal stays on the screen); stores without a condition.
void sslrWriteLevel0(ivec2 cell, vec4 depths, vec4 extra) {
  ivec2 px = cell * 2;
  imageStore(uLevel0, SSLR_AT(px), vec4(sslrHiZLevel0Texel(frame.surface, depths.x, extra.x), 0.0f, 0.0f));
  imageStore(uLevel0, SSLR_AT(px + ivec2(1, 0)), vec4(sslrHiZLevel0Texel(frame.surface, depths.y, extra.y), 0.0f, 0.0f));
  imageStore(uLevel0, SSLR_AT(px + ivec2(0, 1)), vec4(sslrHiZLevel0Texel(frame.surface, depths.z, extra.z), 0.0f, 0.0f));
  imageStore(uLevel0, SSLR_AT(px + 1), vec4(sslrHiZLevel0Texel(frame.surface, depths.w, extra.w), 0.0f, 0.0f));
}

#if defined(SSLR_CURVED_SOLIDS) && SSLR_CURVED_SOLIDS
// Whether the quad's normals turn (sslrQuadNormalsTurn), from its normal channels gathered: two
// (octahedral) or three (xyz); the material channels do not take part.
bool sslrQuadNormalsTurnAt(ivec2 cell) {
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
#endif

// Level 1's cell `cell` from its quad's depths (SSLR_GATHER_QUAD), and its pixels' level-0 texels.
// A quad whose normals turn is listed for the curved pass. `countsOwnDispatch`: this pass runs
// only in a frame that traces, so it sizes the curved pass's dispatch itself (else the
// pyramid-arguments pass turns the counted groups on).
void sslrWriteLevels01(ivec2 cell, vec4 depths, bool countsOwnDispatch) {
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
  if (all(lessThan(cell, imageSize(uLevel1).xy))) {
    imageStore(uLevel1, SSLR_AT(cell), vec4(level1, 0.0f, 0.0f));
    // A quad of background alone gets no level-0 texels: the traversal skips its level-1 cell
    // (nothing there can stop a ray) and never reads them.
    if (!outside && sslrHiZCellHoldsGeometry(frame.surface, level1)) sslrWriteLevel0(cell, depths, extra);
#if defined(SSLR_CURVED_SOLIDS) && SSLR_CURVED_SOLIDS
    // Curved surfaces reach deeper than the slab: the curved pass overwrites the cell with the
    // solids' backs and the pixels' level-0 texels with their extra depths.
    if (!outside && sslrQuadNormalsTurnAt(cell)) {
      uint slot = atomicAdd(curved.count, 1u);
      if ((slot & 63u) == 0u) {
        if (countsOwnDispatch) atomicAdd(curved.dispatchX, 1u);
        else atomicAdd(curved.groups, 1u);
      }
      curved.quads[slot] = sslrPackCoord(cell);
    }
#endif
  }
}
