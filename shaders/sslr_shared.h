// sslr_shared.h - the one source of truth shared by C++ and GLSL (the umbrella of shared/*.h).
//
// It holds the uniform block layout (std140) and the pure math of the effect: depth <-> view
// reconstruction, projection, normal packing, Fresnel and fade terms, blur footprint. C++ includes
// it with GLM standing in for GLSL's types, so CPU tests run the very formulas the GPU runs.
//
// Naming: a prefix says the space. vs = view space (right-handed, camera looks down -z),
// ndc = normalized device coordinates, uv = [0,1]^2 texture coordinates with the origin at the
// lower left (GL), px = pixel coordinates (pixel i covers [i, i+1), its centre is i + 0.5).
// Matrices are named destination-from-source: clipFromView maps view space to clip space.
//
// Only the subset common to C++20 and GLSL 4.50 may be used below: no constructors with
// braces, no references except through SSLR_INOUT/SSLR_OUT, float literals with an f suffix.
//
// One file a concept, each including what it uses (shared/language.h first):
//   constants.h        enumerations, bindings and limits (#defines)
//   frame.h            the uniform block (std140) and the buffers' layouts
//   projection.h       depth <-> view position, window and clip space
//   normals.h          decoding the host's normal packing
//   pyramid.h          the min-max depth pyramid
//   weights.h          Fresnel, fades, coverage, blur radius
//   thickness.h        the pyramid's solids: curved, and the measured back-face depth
//   blur.h             the blur's tap weight
//   ggx.h              the GGX lobe
//   half_resolution.h  the quad record
//   temporal.h         history keys and reprojection
// The last five are C++'s here; a GLSL pass that uses one includes it itself, so that no other
// program (the trace above all) parses it.
#ifndef SSLR_SHARED_H
#define SSLR_SHARED_H

#include "shared/constants.h"
#include "shared/frame.h"
#include "shared/projection.h"
#include "shared/normals.h"
#include "shared/pyramid.h"
#include "shared/weights.h"
#ifdef __cplusplus
#include "shared/thickness.h"
#include "shared/blur.h"
#include "shared/ggx.h"
#include "shared/half_resolution.h"
#include "shared/temporal.h"
#endif

#endif  // SSLR_SHARED_H
