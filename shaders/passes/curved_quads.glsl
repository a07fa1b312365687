// Curved solids (sslr_shared.h, "Curved solids"): the list of 2x2 quads whose normals turn, which
// classification (or the levels-0-and-1 pass) fills and the curved pass works through.
layout(std430, binding = SSLR_BINDING_CURVED_SSBO) buffer SslrCurvedQuads {
  uint dispatchX;  // DispatchIndirectCommand of the curved pass: the pyramid-arguments pass sets x
  uint dispatchY;
  uint dispatchZ;
  uint groups;     // groups of 64 listed quads (classification counts them)
  uint count;      // listed quads
  uint pad0, pad1, pad2;
  uint quads[];    // sslrPackCoord(cell) (its view in bits 14-15)
} curved;
