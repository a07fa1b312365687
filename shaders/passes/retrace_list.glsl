// The retrace list: the rays a trace pass hands to a later pass. Pixels: those the half-resolution
// shading pass could not answer from their quad's ray, or (deferred traversal) whose first stage
// needs the traversal; the retrace pass traces them. Quads: the half-resolution quad rays that
// need the traversal, grouped by tile so that a group's rays start side by side; the quad retrace
// pass traces them.
layout(std430, binding = SSLR_BINDING_RETRACE_SSBO) buffer SslrRetrace {
  // DispatchIndirectCommand: the retrace pass's ceil(count / SSLR_RETRACE_GROUP) groups, or the
  // quad retrace pass's one group per tile with a quad listed.
  uint dispatchX;
  uint dispatchY;
  uint dispatchZ;
  uint count;  // pixels listed; inline under TraversalPass::Auto: pixels (or quads) the traversal
               // ran for; in the quad passes under Auto: quads listed
  // Pixels: sslrPackCoord(px) in the order listed. Quads: [0, cap) the slots of the tiles with a quad
  // listed, then per slot a region of its listed quads, sslrPackCoord(quad), as many as
  // sslrQuadRetraceCountIndex says.
  uint entries[];
} retrace;

// The retrace is the whole tracer's program in its retrace role (SSLR_RETRACE_ROLE): uRetrace = 1
// traces the listed pixels (quads) instead of the listed tiles', so that Auto's inline trace and
// its deferred retrace are one program to compile.
#ifdef SSLR_RETRACE_ROLE
layout(location = SSLR_RETRACE_ROLE_LOCATION) uniform int uRetrace;
#else
const int uRetrace = 0;
#endif

// Lists a pixel for the retrace pass.
void sslrListPixelForRetrace(ivec2 px) {
  uint slot = atomicAdd(retrace.count, 1u);
  retrace.entries[slot] = sslrPackCoord(px);
  if (slot % uint(SSLR_RETRACE_GROUP) == 0u) atomicAdd(retrace.dispatchX, 1u);
}

// Where tile slot `slot`'s listed quads start in entries.
uint sslrQuadRetraceRegion(uint slot) { return sslrTileCapacity() + slot * uint(SSLR_TILE_QUADS); }

// Lists a quad of the tile in list slot `slot` for the quad retrace pass, which runs one group per
// tile with a quad listed.
void sslrListQuadForRetrace(uint slot, ivec2 quad) {
#ifdef SSLR_COUNT_TRAVERSAL
  atomicAdd(retrace.count, 1u);  // TraversalPass::Auto's feedback: quads that needed the traversal
#endif
  uint k = atomicAdd(tiles.tileCoords[sslrQuadRetraceCountIndex(slot)], 1u);
  retrace.entries[sslrQuadRetraceRegion(slot) + k] = sslrPackCoord(quad);
  if (k == 0u) retrace.entries[atomicAdd(retrace.dispatchX, 1u)] = slot;
}
