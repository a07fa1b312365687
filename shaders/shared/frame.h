// shared/frame.h - The uniform block (std140) and the buffers' layouts shared with the passes.
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_FRAME_H
#define SSLR_SHARED_FRAME_H

#include "language.h"
#include "constants.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- Uniform block structs (std140: every member 4 bytes, every struct a multiple of 16) ----

// A projection reduced to the six numbers that a perspective or orthographic matrix without skew
// can hold (GL column-major notation P[col][row]):
//   perspective:  xScale = P[0][0], yScale = P[1][1], xOffset = P[2][0], yOffset = P[2][1],
//                 zScale = P[2][2], zOffset = P[3][2]   (P[2][3] = -1, P[3][3] = 0)
//   orthographic: xScale = P[0][0], yScale = P[1][1], xOffset = P[3][0], yOffset = P[3][1],
//                 zScale = P[2][2], zOffset = P[3][2]   (P[2][3] = 0, P[3][3] = 1)
// Off-centre and jittered frusta live in the offsets. The C++ side extracts these in double from
// the host's matrix and rejects any matrix that is not of this form.
struct SslrProjection {
  float xScale;
  float yScale;
  float xOffset;
  float yOffset;
  float zScale;
  float zOffset;
  int orthographic;  // 0 = perspective, 1 = orthographic
  int ndcZeroToOne;  // 1: window depth = ndc z (glClipControl ZERO_TO_ONE); 0: = ndc z * 0.5 + 0.5
  // Perspective only: the window depth of the point at infinity, d_inf = hi + lo, split in double
  // on the CPU (hi = 0 or 1). Reconstruction divides by (depth - hi) - lo instead of
  // ndcZ + zScale: for a standard (non-reversed) depth buffer, depth - 1 is exact and the
  // cancellation near the far plane does not lose the bits float rounding of zScale costs.
  float infDepthHi;
  float infDepthLo;
  float pad0;
  float pad1;
};

struct SslrSurface {
  int normalEncoding;        // SSLR_NORMALS_*
  int roughnessChannel;      // channel of the normal texture holding roughness; -1 = constant
  int reflectanceChannel;    // channel holding reflectance (F0); -1 = constant
  int reversedZ;             // 1: near = 1, background = 0; 0: near = 0, background = 1
  float constantRoughness;   // used when roughnessChannel = -1
  float constantReflectance; // used when reflectanceChannel = -1
  float width;               // the frame's size in pixels (FrameInputs::viewport's, else the context's)
  float height;
  // Normals stored in world space (SurfaceLayout::space): the columns of the matrix that turns
  // them into view space (inverse-transpose of viewFromWorld's 3x3); w of the first is 1 then,
  // 0 for view-space normals (the columns are then unused).
  vec4 normalFromStored0;
  vec4 normalFromStored1;
  vec4 normalFromStored2;
  int separateMaterial;      // 1: roughness/reflectance channels are of the material texture
  int hasMask;               // 1: rays start only where the mask texture's first channel > 0.5
  int hasBackDepth;          // 1: FrameInputs::backDepthTexture measures what a pixel shows is deep
  int metalnessChannel;      // channel of the material texel holding metalness; -1: grey F0
  float normalScale SSLR_DEFAULT(2.0f);  // a stored normal channel unpacks to value * normalScale +
  float normalBias SSLR_DEFAULT(-1.0f);  // normalBias in [-1, 1] (2, -1: unsigned formats; 1, 0: signed)
  int originX;               // the frame's pixel (0, 0) is texel (originX, originY) of the host's
  int originY;               // textures and of the outputs (FrameInputs::viewport)
  int textureWidth;          // the size of those textures (the context's)
  int textureHeight;
  int viewportInside;        // 1: the frame is a part of the textures (their edge is not its edge)
  int surfacePad0;
};

struct SslrTraceParams {
  // Which pixels get a ray (Settings::selection).
  float roughnessCutoff;  // pixels rougher than this are not traced
  float minReflectance;   // pixels with reflectance at or below this are not traced
  // Adaptive L (Settings::adaptiveL).
  float initialLengthPixels;  // the first L moves the probe this many pixels (initialLengthScreen x height)
  float convergenceEps;       // stop once |L_new - L| <= eps * L
  int maxIterations;          // iterations at most, one depth fetch each
  // The traversal (Settings::traversal) and what the frame's inputs make of it.
  int hizMode;                // SSLR_HIZ_*: adaptive L alone, the traversal first, or the traversal alone
  int maxSteps;               // cells visited at most, one fetch each
  int hizLevels;              // pyramid levels above the depth buffer (sslrHiZLevelCount)
  float objectDepthRelative;  // the assumed thickness: this fraction of the view depth
  int curvedSolids;           // 1: deeper behind convex curved surfaces (no back-face depth given)
  int thinObjectHits;         // 1: thin objects' hits (traversal first; not lobe rays with a history)
  float hiddenGuess;          // the confidence of a guess (0 = none)
  // Weights (Settings::fades, fresnel, output).
  float errorK;         // the article's error term: 1 - saturate(L / distance * errorK)
  float maxDistance;    // reflections longer than this (view units) get no weight
  float screenEdge;     // fade width at the screen border, fraction of the screen [0, 0.5]
  float cameraStart;    // rays with dot(R, toCamera) above this start to fade ...
  float cameraEnd;      // ... and are gone here
  int fresnel;          // SSLR_FRESNEL_*
  int outputRadiance;   // 1: Settings::output is Radiance (no Fresnel term in the reflection)
  // The blur (Settings::blur).
  float maxRadiusPx;  // the radius (pixels) that alpha = 1 stands for
  float coneScale;    // cone tan(half angle) = roughness^2 * coneScale
  float depthSigma;   // neighbour weight exp(-|dz| / (depthSigma * z))
  float normalPower;  // neighbour weight max(0, dot(n0, n1))^normalPower
  // Rough surfaces and bright hits (Settings::glossy, radianceClamp).
  float stochasticFrom;  // GlossyMode::Stochastic: pixels this rough or more draw their ray (> 1: none)
  float maxLuminance;    // a hit colour's luminance at most this (colour-texture units; 0 = no clamp)
  // Method::FidelityFxSssr (Settings::ffx; sslr_trace_ffx.h).
  float depthBufferThickness;
  int maxTraversalIntersections;
  int frameIndex;  // increments per dispatch (never 0): per-tile "listed" stamps
  int tracePad0;  // std140: the block a multiple of 16 bytes
  int tracePad1;
  int tracePad2;
  int tracePad3;
};

// The position-buffer comparison method ("3D Game Shaders For Beginners", SSR chapter).
struct SslrPositionParams {
  float maxDistance;  // ray length in view units (tutorial: 8)
  float resolution;   // fraction of pixels visited by the coarse march, 0..1 (tutorial: 0.3)
  float hitTolerance; // view units: a ray point this close behind the stored position hits (tutorial: 0.5)
  int steps;          // binary refinement steps (tutorial: 5)
};

// The screen-space DDA comparison method (McGuire & Mara 2014).
struct SslrDdaParams {
  float stride;       // pixels per step (>= 1)
  float objectDepth;  // depth assumed behind every visible surface, view units (the paper's zThickness)
  float maxDistance;  // ray length, view units
  int maxSteps;       // steps at most (each one depth fetch), refinement not included
  int jitter;         // 1: checkerboard offset of half a stride (stride > 1)
  int refine;         // 1: re-march the stride of a hit one pixel at a time
  int pad0;
  int pad1;
};

// Temporal reuse (Settings::temporal): the previous frame's output, reprojected.
struct SslrTemporalParams {
  mat4 previousClipFromView;  // this frame's view space -> the previous frame's clip space
  float historyWeight;        // share of the (clamped) history in the output, [0, 1)
  float keyTolerance;         // history valid where its key is within this relative difference
  int history;                // 1: the history textures hold the previous frame (else ignore them)
  int hasMotion;              // 1: FrameInputs::motionTexture gives where each pixel was (uv offset)
  vec4 previousEye;           // the previous camera's position in this frame's view space; w = 1
                              // when known (perspective), 0 otherwise (no virtual-point reprojection)
};

#ifdef __cplusplus
#define SSLR_FRAME_BLOCK_BEGIN struct SslrFrame {
#define SSLR_FRAME_BLOCK_END };
#elif SSLR_VIEWS > 1
// Several views (ContextDesc::views): one SslrFrame a view, `frame` the current view's.
#define SSLR_FRAME_BLOCK_BEGIN struct SslrFrame {
#define SSLR_FRAME_BLOCK_END };                                                                  \
  layout(std140, binding = SSLR_BINDING_FRAME_UBO) uniform SslrFrameBlock { SslrFrame sslrFrames[SSLR_VIEWS]; };
#else
#define SSLR_FRAME_BLOCK_BEGIN layout(std140, binding = SSLR_BINDING_FRAME_UBO) uniform SslrFrameBlock {
#define SSLR_FRAME_BLOCK_END } frame;
#endif

SSLR_FRAME_BLOCK_BEGIN
  SslrProjection proj;
  SslrSurface surface;
  SslrTraceParams trace;
  SslrPositionParams positionBuffer;
  SslrDdaParams dda;
  SslrTemporalParams temporal;
SSLR_FRAME_BLOCK_END

#ifndef __cplusplus
// ---- Views (ContextDesc::views) ----------------------------------------------------------------
// With several views every texture and image of a pass is a 2D array, one layer a view, and each
// invocation serves one view, sslrView: a full-screen pass's gl_WorkGroupID.z, a listed tile's,
// pixel's or quad's view from its list entry (sslrEnterCoord, common/tiles.glsl). SSLR_AT and
// SSLR_UV_AT turn a texel or uv of the frame into that view's (of types SSLR_COORD, SSLR_UV);
// with one view they are the texel or uv itself and the textures plain 2D ones, so the
// single-view shaders are unchanged.
#if SSLR_VIEWS > 1
int sslrView = 0;
#define frame sslrFrames[sslrView]
#define SSLR_SET_VIEW(v) sslrView = int(v)
#define SSLR_SAMPLER sampler2DArray
#define SSLR_IMAGE image2DArray
#define SSLR_COORD ivec3
#define SSLR_UV vec3
#define SSLR_AT(p) ivec3(p, sslrView)
#define SSLR_UV_AT(uv) vec3(uv, float(sslrView))
#else
#define sslrView 0
#define SSLR_SET_VIEW(v)
#define SSLR_SAMPLER sampler2D
#define SSLR_IMAGE image2D
#define SSLR_COORD ivec2
#define SSLR_UV vec2
#define SSLR_AT(p) (p)
#define SSLR_UV_AT(uv) (uv)
#endif
#endif

// The tile buffer's header (common/tiles.glsl's SSBO, std430: tightly packed uints), shared by the
// passes and the C++ code that writes its per-frame part and dispatches through its commands.
#define SSLR_TILE_HEADER_FIELDS                                                                     \
  /* DispatchIndirectCommand of the trace: x = listed tiles (classification increments it). */     \
  uint dispatchX;                                                                                 \
  uint dispatchY;                                                                                 \
  uint dispatchZ;                                                                                 \
  /* DrawArraysIndirectCommand of the composite: 6 vertices per listed tile, instanced. */         \
  uint drawCount;                                                                                 \
  uint drawInstances;                                                                             \
  uint drawFirst;                                                                                 \
  uint drawBaseInstance;                                                                          \
  uint reserved0;                                                                                 \
  /* DispatchIndirectCommand of the blur: x = tiles with a pixel to blur (the trace lists them). */ \
  uint blurDispatchX;                                                                             \
  uint blurDispatchY;                                                                             \
  uint blurDispatchZ;                                                                             \
  uint reserved1;                                                                                 \
  /* DispatchIndirectCommand per pyramid level: zero groups unless classification listed a tile; */ \
  /* then the pyramid-args pass copies each level's real group counts in from hizGroups. */         \
  uint hizDispatch[3 * SSLR_HIZ_MAX_LEVELS];                                                      \
  uint hizGroups[3 * SSLR_HIZ_MAX_LEVELS];                                                        \
  /* DispatchIndirectCommand of half resolution's quad pass under DeviceProfile::Gpu: x = groups */ \
  /* of 4 listed tiles (classification increments it at every fourth tile it lists). */           \
  uint quadDispatchX;                                                                             \
  uint quadDispatchY;                                                                             \
  uint quadDispatchZ;                                                                             \
  uint reserved3;                                                                                 \
  /* DispatchIndirectCommand of the clean-up pass: the previous frame's trace dispatch, copied */   \
  /* here before this frame's header is written (the CPU never writes it). */                      \
  uint cleanupDispatchX;                                                                          \
  uint cleanupDispatchY;                                                                          \
  uint cleanupDispatchZ;                                                                          \
  uint reserved2;

#ifdef __cplusplus
struct SslrTileHeader {
  SSLR_TILE_HEADER_FIELDS
};
static_assert(offsetof(SslrTileHeader, drawCount) == 12, "std430 mirror");
static_assert(offsetof(SslrTileHeader, blurDispatchX) == 32, "std430 mirror");
static_assert(offsetof(SslrTileHeader, hizDispatch) == 48, "std430 mirror");
static_assert(offsetof(SslrTileHeader, hizGroups) == 48 + 12 * SSLR_HIZ_MAX_LEVELS, "std430 mirror");
static_assert(offsetof(SslrTileHeader, quadDispatchX) == 48 + 24 * SSLR_HIZ_MAX_LEVELS, "std430 mirror");
static_assert(offsetof(SslrTileHeader, cleanupDispatchX) == 64 + 24 * SSLR_HIZ_MAX_LEVELS, "std430 mirror");
static_assert(sizeof(SslrTileHeader) == offsetof(SslrTileHeader, cleanupDispatchX) + 16, "std430 mirror");
#endif

#ifdef __cplusplus
// The reduced form of a projection matrix (C++ only; the library validates the matrix first,
// see src/sslr/src/projection.cpp).
inline SslrProjection sslrProjectionFromMatrix(const glm::dmat4& clipFromView, bool ndcZeroToOne) {
  const bool ortho = clipFromView[3][3] == 1.0 && clipFromView[2][3] == 0.0;
  SslrProjection p{};
  p.xScale = static_cast<float>(clipFromView[0][0]);
  p.yScale = static_cast<float>(clipFromView[1][1]);
  p.xOffset = static_cast<float>(ortho ? clipFromView[3][0] : clipFromView[2][0]);
  p.yOffset = static_cast<float>(ortho ? clipFromView[3][1] : clipFromView[2][1]);
  p.zScale = static_cast<float>(clipFromView[2][2]);
  p.zOffset = static_cast<float>(clipFromView[3][2]);
  p.orthographic = ortho ? 1 : 0;
  p.ndcZeroToOne = ndcZeroToOne ? 1 : 0;
  if (!ortho) {
    // ndcZ = -zScale at infinite distance; window depth of that point, split hi + lo.
    const double ndcInf = -clipFromView[2][2];
    const double depthInf = ndcZeroToOne ? ndcInf : ndcInf * 0.5 + 0.5;
    const double hi = depthInf > 0.5 ? 1.0 : 0.0;
    p.infDepthHi = static_cast<float>(hi);
    p.infDepthLo = static_cast<float>(depthInf - hi);
  }
  return p;
}
static_assert(sizeof(SslrProjection) == 48, "std140 mirror");
static_assert(sizeof(SslrSurface) == 128, "std140 mirror");
static_assert(sizeof(SslrTraceParams) == 128, "std140 mirror");
static_assert(offsetof(SslrFrame, surface) == 48, "std140 mirror");
static_assert(offsetof(SslrFrame, trace) == 176, "std140 mirror");
static_assert(sizeof(SslrPositionParams) == 16, "std140 mirror");
static_assert(offsetof(SslrFrame, positionBuffer) == 304, "std140 mirror");
static_assert(sizeof(SslrDdaParams) == 32, "std140 mirror");
static_assert(offsetof(SslrFrame, dda) == 320, "std140 mirror");
static_assert(sizeof(SslrTemporalParams) == 96, "std140 mirror");
static_assert(offsetof(SslrFrame, temporal) == 352, "std140 mirror");
static_assert(sizeof(SslrFrame) == 448, "std140 mirror");
#endif

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_FRAME_H
