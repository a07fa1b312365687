// sslr_shared.h - the one source of truth shared by C++ and GLSL.
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
#ifndef SSLR_SHARED_H
#define SSLR_SHARED_H

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <cstddef>
#include <cstdint>
namespace sslr::shared {
using glm::ivec2;
using glm::ivec4;
using glm::bvec4;
using glm::uvec2;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::mat4;
using uint = std::uint32_t;
using glm::abs;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp2;
using glm::log2;
using glm::floor;
using glm::isinf;
using glm::isnan;
using glm::length;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::inversesqrt;
using glm::reflect;
using glm::sign;
using glm::sin;
using glm::smoothstep;
using glm::sqrt;
#define SSLR_FN inline
#define SSLR_INOUT(T) T&
#define SSLR_OUT(T) T&
#define SSLR_DEFAULT(v) = v  // a member's default in C++ (a GLSL block member has none)
#else
#define SSLR_FN
#define SSLR_INOUT(T) inout T
#define SSLR_OUT(T) out T
#define SSLR_DEFAULT(v)
#endif

// ---- Enumerations (plain #defines so both languages and #if can use them) -------------------
#define SSLR_NORMALS_OCTAHEDRAL 0  // RG (unorm) = octahedral encoding of the view-space normal
#define SSLR_NORMALS_XYZ_UNORM 1   // RGB (unorm) = n * 0.5 + 0.5, the article's packing

#define SSLR_FRESNEL_CLASSIC 0  // the article: 2.8 (1 - cos)^2, with its error term 1 - sat(L k)
#define SSLR_FRESNEL_SCHLICK 1  // F0 + (1 - F0) (1 - cos)^5 with F0 = material reflectance

#define SSLR_STATUS_NOT_TRACED 0  // background, not reflective, too rough, back-facing normal
#define SSLR_STATUS_HIT 1         // converged and validated (confidence may still be faded)
#define SSLR_STATUS_OFF_SCREEN 2  // the probe left the screen or crossed the near plane
#define SSLR_STATUS_MISS 3        // did not converge, or the hit failed validation
#define SSLR_STATUS_SKY 4         // the ray ran into the background (nothing on screen to hit)
#define SSLR_STATUS_HIDDEN 5      // the traversal ran into a solid the back-face depth measured, or
                                  // past Settings::traversal.hiddenPassageLimitPx behind the depth buffer: what
                                  // the ray meets is hidden (L: where that was known)

#define SSLR_HIZ_OFF 0       // adaptive L alone (the article's method, made robust)
#define SSLR_HIZ_FALLBACK 1  // adaptive L first; the hierarchical traversal where it finds no hit
#define SSLR_HIZ_ONLY 2      // the hierarchical traversal alone (Method::HierarchicalDepth)
#define SSLR_HIZ_VERIFY 3    // as FALLBACK, and the traversal also checks every adaptive-L hit for an
                             // earlier crossing (Settings::traversal.verify)
#define SSLR_HIZ_TRAVERSAL_FIRST 4  // the traversal on every ray; adaptive L where it has no hit
                                    // (Settings::traversal.order, the default)

// Most levels of the min-max depth pyramid above the depth buffer (level l: 2^l-pixel cells).
#define SSLR_HIZ_MAX_LEVELS 8

#define SSLR_TILE_SIZE 8  // compute work-group edge and classification tile edge, in pixels
#define SSLR_TILE_QUADS ((SSLR_TILE_SIZE / 2) * (SSLR_TILE_SIZE / 2))  // 2x2 quads per tile

// Texture / image / buffer binding points used by the passes (they are restored afterwards).
#define SSLR_BINDING_FRAME_UBO 0
#define SSLR_BINDING_TILE_SSBO 0
#define SSLR_BINDING_STATS_SSBO 1
#define SSLR_BINDING_RETRACE_SSBO 2  // half resolution: pixels that trace their own ray
#define SSLR_BINDING_CURVED_SSBO 2   // curved solids: the quads whose normals turn (1_classify.comp, 2_pyramid_*.comp)

// Texture units, named once for GLSL, C++ and the GL state contract (gl_state.hpp). The G-buffer's
// units keep their meaning in every pass; units 3-5 are the inputs of the pass that runs.
#define SSLR_UNIT_DEPTH 0
#define SSLR_UNIT_NORMAL 1
#define SSLR_UNIT_COLOR 2
#define SSLR_UNIT_QUAD_HIT 3          // trace at half resolution: the quads' hits
#define SSLR_UNIT_QUAD_SURFACE 4      // ... and surfaces
#define SSLR_UNIT_BLUR_INPUT 3        // blur: the pass's input (resolved, then blurTemp)
#define SSLR_UNIT_BLUR_REFLECTION 4   // ... the reflection (its alpha: the radius)
#define SSLR_UNIT_BLUR_UNBLURRED 5    // ... vertical pass: resolved before it
#define SSLR_UNIT_TEMPORAL_CURRENT 3  // temporal reuse: this frame's resolved (store: the blend)
#define SSLR_UNIT_HISTORY 4           // ... the previous frame's output
#define SSLR_UNIT_HISTORY_KEY 5       // ... its keys
#define SSLR_UNIT_COMPOSITE_RESOLVED 4  // composite: the resolved output
#define SSLR_UNIT_COMPOSITE_FALLBACK 5  // ... the host's fallback specular
#define SSLR_UNIT_POSITION 5          // Method::PositionBuffer: the host's position texture
#define SSLR_UNIT_PYRAMID 6           // the depth pyramid (the trace passes, 2_pyramid_*.comp)
#define SSLR_UNIT_MOTION 6            // temporal reuse: the host's motion vectors (after the trace)
#define SSLR_UNIT_MATERIAL 7
#define SSLR_UNIT_MASK 8
#define SSLR_UNIT_HIT_RECORD 9        // temporal reuse: this frame's hits
#define SSLR_UNIT_BACK_DEPTH 10
#define SSLR_UNIT_BASE_COLOR 11       // coloured F0: the host's base colour (metalness workflow)
#define SSLR_UNIT_COUNT 12
// Image units, likewise per pass.
#define SSLR_IMAGE_REFLECTION 0       // trace, clean-up
#define SSLR_IMAGE_HIT 1              // trace (debug outputs, temporal reuse)
#define SSLR_IMAGE_ITERATIONS 2       // trace (debug outputs)
#define SSLR_IMAGE_RESOLVED 3         // trace, clean-up
#define SSLR_IMAGE_HIT_DISTANCE 4     // trace (Settings::hitDistance)
#define SSLR_IMAGE_QUAD_HIT 1         // half resolution's quad pass
#define SSLR_IMAGE_QUAD_SURFACE 2
#define SSLR_IMAGE_PYRAMID_LEVEL1 0   // classification, level-1 and curved passes
#define SSLR_IMAGE_PYRAMID_LEVEL0 1
#define SSLR_IMAGE_CLASSIFY_REFLECTION 2  // classification (DeviceProfile::Gpu): last frame's untraced tiles
#define SSLR_IMAGE_CLASSIFY_RESOLVED 3
#define SSLR_IMAGE_PYRAMID_BLOCK 0    // 2_pyramid_levels2to7.comp: levels 2..7 on units 0..5; 2_pyramid_top_level.comp: 0
#define SSLR_IMAGE_BLUR_OUTPUT 0
#define SSLR_IMAGE_TEMPORAL_OUTPUT 0  // temporal reuse: the blend (store: resolved)
#define SSLR_IMAGE_HISTORY 1          // ... store: the history
#define SSLR_IMAGE_HISTORY_CONFIDENCE 1  // ... blend: history's share (Settings::temporal.outputConfidence)
#define SSLR_IMAGE_HISTORY_KEY 2      // ... store (and its clean-up): the keys
#define SSLR_IMAGE_COUNT 6
#define SSLR_RETRACE_GROUP 64        // invocations per group of the retrace pass

// The stats buffer (Settings::debug.collectStats): counters of the trace passes (0-2), the tile
// counts the host copies in (4, 5), then the ray work of each trace dispatch (passes/ray_work.glsl,
// FrameStats::RayWork): SSLR_RAY_WORK_FIELDS counters per dispatch.
#define SSLR_STATS_LISTED_TILES 4
#define SSLR_STATS_BLUR_TILES 5
#define SSLR_STATS_RAY_WORK 8          // index of the first ray-work counter
#define SSLR_RAY_WORK_TRACE 0          // dispatches: the full-resolution trace
#define SSLR_RAY_WORK_RETRACE 1        // ... the retrace of listed pixels (deferred traversal, half resolution)
#define SSLR_RAY_WORK_QUADS 2          // ... half resolution's quad rays
#define SSLR_RAY_WORK_QUAD_RETRACE 3   // ... and their deferred traversal
#define SSLR_RAY_WORK_DISPATCHES 4
#define SSLR_RAY_WORK_LANE_STEPS 0     // fields: the lanes' dependent steps, summed
#define SSLR_RAY_WORK_SIMT32 1         // ... each 32-lane group's largest, summed
#define SSLR_RAY_WORK_SIMT64 2         // ... each 64-lane group's largest, summed
#define SSLR_RAY_WORK_CHAIN 3          // ... the largest of any lane
#define SSLR_RAY_WORK_GROUPS 4         // ... groups with a lane that traced
#define SSLR_RAY_WORK_FIELDS 5
#define SSLR_STATS_COUNT (SSLR_STATS_RAY_WORK + SSLR_RAY_WORK_DISPATCHES * SSLR_RAY_WORK_FIELDS)

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
  float initialLengthPixels;  // first L moves the probe this many pixels (Settings: fraction x height)
  float convergenceEps;       // stop once |L_new - L| <= eps * L
  float errorK;               // the article's "LDelmiter": error = 1 - saturate(L / distance * k)
  float maxDistance;          // reflections longer than this (view units) get zero confidence
  float hitToleranceRelative; // hit tolerance: this fraction of the hit's view distance ...
  float hitTolerancePixels;   // ... plus this many pixel footprints (scaled by surface slope)
  float edgeFade;             // fade width at the screen border, fraction of the screen [0,0.5]
  float cameraFadeStart;      // rays with dot(R, toCamera) above start fade out ...
  float cameraFadeEnd;        // ... and are gone at end
  float roughnessCutoff;      // pixels rougher than this are not traced
  float minReflectance;       // pixels with reflectance at or below this are not traced
  float blurMaxRadiusPx;      // blur radius (pixels) that alpha = 1 stands for
  float blurConeScale;        // cone tan(half angle) = roughness^2 * blur.coneScale
  float blurDepthSigma;       // bilateral: weight exp(-|dz| / (sigma * z))
  float blurNormalPower;      // bilateral: weight max(0, dot(n0, n1))^power
  int maxIterations;          // adaptive-L iteration cap
  int fresnelMode;            // SSLR_FRESNEL_*
  int hizMode;                // SSLR_HIZ_* : hierarchical traversal off, as fallback (+ verify), or alone
  int frameIndex;             // increments per dispatch (never 0): per-tile "listed" stamps
  int hizMaxSteps;            // hierarchical traversal: cell visits (each one fetch) at most
  int hizLevels;              // pyramid levels above the depth buffer (sslrHiZLevelCount)
  float objectDepthRelative;  // hierarchical: a ray less than this fraction of the view depth
                              // behind a surface is inside the object (stops); farther: behind it
  int outlineThinning;        // 1: that depth shrinks near the object's outline (sslrSlabNearOutline)
  int curvedSolids;           // 1: ... and grows behind convex curved surfaces (sslrCurvedExtraDepth)
  float hiddenPassageLimitPx; // hierarchical: pixels a ray may travel behind the depth buffer
  float ffxDepthBufferThickness;  // Method::FidelityFxSssr (sslr_trace_ffx.h)
  int ffxMaxIntersections;
  int outputRadiance;         // 1: Settings::output is Radiance (no Fresnel term in the reflection)
  float stochasticFrom;       // GlossyMode::Stochastic: pixels this rough or more draw their ray (> 1: none)
  float maxHitLuminance;      // Settings::radianceClamp: a hit colour's luminance at most this
                              // (colour-texture units; 0 = no clamp)
  int tracePad1;
  int tracePad2;
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

// ---- Pure math ----------------------------------------------------------------------------

SSLR_FN float sslrSaturate(float x) { return clamp(x, 0.0f, 1.0f); }

// Window depth -> ndc z, and back.
SSLR_FN float sslrNdcZFromDepth(SslrProjection p, float depth) {
  return p.ndcZeroToOne != 0 ? depth : depth * 2.0f - 1.0f;
}
SSLR_FN float sslrDepthFromNdcZ(SslrProjection p, float ndcZ) {
  return p.ndcZeroToOne != 0 ? ndcZ : ndcZ * 0.5f + 0.5f;
}

// A depth sample that holds geometry: finite, inside [0,1] and not the clear value. NaN fails
// every comparison and so counts as background (poisoned input never reaches the tracer).
SSLR_FN bool sslrIsGeometryDepth(SslrSurface s, float depth) {
  bool inRange = depth >= 0.0f && depth <= 1.0f;
  return inRange && (s.reversedZ != 0 ? depth > 0.0f : depth < 1.0f);
}

SSLR_FN vec2 sslrNdcFromUv(vec2 uv) { return uv * 2.0f - 1.0f; }
SSLR_FN vec2 sslrUvFromNdc(vec2 ndc) { return ndc * 0.5f + 0.5f; }
// Whether uv lies on the screen (borders included); false for NaN.
SSLR_FN bool sslrInsideUv(vec2 uv) { return uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f; }
SSLR_FN vec2 sslrUvFromPixel(ivec2 px, vec2 sizePx) { return (vec2(px) + 0.5f) / sizePx; }
SSLR_FN ivec2 sslrPixelFromUv(vec2 uv, vec2 sizePx) {
  return clamp(ivec2(floor(uv * sizePx)), ivec2(0), ivec2(sizePx) - 1);
}

// View-space position from ndc, exact for both projection kinds (see SslrProjection).
// Perspective: dist = zOffset / (ndcZ + zScale) is the view distance along -z; x and y follow.
SSLR_FN vec3 sslrViewFromNdc(SslrProjection p, vec2 ndcXY, float ndcZ) {
  if (p.orthographic != 0) {
    return vec3((ndcXY.x - p.xOffset) / p.xScale, (ndcXY.y - p.yOffset) / p.yScale,
                (ndcZ - p.zOffset) / p.zScale);
  }
  float depth = sslrDepthFromNdcZ(p, ndcZ);
  float ndcScale = p.ndcZeroToOne != 0 ? 1.0f : 2.0f;
  // ndcZ + zScale = ndcScale * (depth - d_inf), see SslrProjection::infDepthHi.
  float dist = p.zOffset / (ndcScale * ((depth - p.infDepthHi) - p.infDepthLo));
  return vec3(dist * (ndcXY.x + p.xOffset) / p.xScale, dist * (ndcXY.y + p.yOffset) / p.yScale,
              -dist);
}

SSLR_FN vec3 sslrViewFromUvDepth(SslrProjection p, vec2 uv, float depth) {
  return sslrViewFromNdc(p, sslrNdcFromUv(uv), sslrNdcZFromDepth(p, depth));
}

// The surface a depth texel shows, as the tracer's sslrLoadSurface wants it: false for the
// background (clear value, NaN, out of range), else the view position at the pixel centre.
SSLR_FN bool sslrSurfaceFromDepth(SslrProjection p, SslrSurface s, ivec2 px, float depth,
                                  SSLR_OUT(vec3) vsPos) {
  if (!sslrIsGeometryDepth(s, depth)) {
    vsPos = vec3(0.0f);
    return false;
  }
  vsPos = sslrViewFromUvDepth(p, sslrUvFromPixel(px, vec2(s.width, s.height)), depth);
  return true;
}

// Clip w of a view-space point: the view distance (perspective) or 1 (orthographic).
SSLR_FN float sslrClipW(SslrProjection p, vec3 vsPos) {
  return p.orthographic != 0 ? 1.0f : -vsPos.z;
}

// View space -> ndc (x, y, z). The caller must have checked sslrClipW > 0.
SSLR_FN vec3 sslrNdcFromView(SslrProjection p, vec3 vsPos) {
  if (p.orthographic != 0) {
    return vec3(p.xScale * vsPos.x + p.xOffset, p.yScale * vsPos.y + p.yOffset,
                p.zScale * vsPos.z + p.zOffset);
  }
  float w = -vsPos.z;
  return vec3((p.xScale * vsPos.x + p.xOffset * vsPos.z) / w,
              (p.yScale * vsPos.y + p.yOffset * vsPos.z) / w,
              (p.zScale * vsPos.z + p.zOffset) / w);
}

// Unit direction from the camera towards a view-space point (orthographic: constant -z).
SSLR_FN vec3 sslrViewDirection(SslrProjection p, vec3 vsPos) {
  return p.orthographic != 0 ? vec3(0.0f, 0.0f, -1.0f) : normalize(vsPos);
}

// Distance used for pixel footprints and relative tolerances.
SSLR_FN float sslrViewDistance(SslrProjection p, vec3 vsPos) {
  return p.orthographic != 0 ? 1.0f : max(-vsPos.z, 0.0f);
}

// Size (view units) of one pixel at a given view distance.
SSLR_FN float sslrPixelFootprint(SslrProjection p, float heightPx, float dist) {
  return 2.0f * dist / (abs(p.yScale) * heightPx);
}

// ---- Normals ------------------------------------------------------------------------------
// Whether stored normal channels hold 0..1 (the default unpack, value * 2 - 1): the decode keeps
// that exact formula then; other scale/bias pairs (signed formats: 1, 0) go through the general one.
SSLR_FN bool sslrUnsignedNormalUnpack(SslrSurface s) { return s.normalScale == 2.0f && s.normalBias == -1.0f; }

// Octahedral mapping (Meyer et al. 2010 / Cigolle et al. 2014) into [0,1]^2.
SSLR_FN vec2 sslrOctWrap(vec2 v) {
  return (1.0f - abs(vec2(v.y, v.x))) * vec2(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f);
}
SSLR_FN vec2 sslrOctEncode(vec3 n) {
  n /= (abs(n.x) + abs(n.y) + abs(n.z));
  vec2 e = n.z >= 0.0f ? vec2(n.x, n.y) : sslrOctWrap(vec2(n.x, n.y));
  return e * 0.5f + 0.5f;
}
SSLR_FN vec3 sslrOctDecode(vec2 e01) {
  vec2 f = e01 * 2.0f - 1.0f;
  vec3 n = vec3(f.x, f.y, 1.0f - abs(f.x) - abs(f.y));
  float t = max(-n.z, 0.0f);
  n.x += n.x >= 0.0f ? -t : t;
  n.y += n.y >= 0.0f ? -t : t;
  return normalize(n);
}

// Decodes the host's texel normal. Returns false for a normal that cannot be trusted (zero,
// NaN/Inf, or far from unit length for the xyz packing): such pixels are not traced.
//
// sslr's compute passes get the encoding and the world-space flag as #defines (the dispatch's
// inputDefines, equal to these uniforms): a CPU rasterizer runs both sides of a uniform branch
// under lane masks.
SSLR_FN bool sslrDecodeNormal(SslrSurface s, vec4 texel, SSLR_OUT(vec3) vsNormal) {
#ifdef SSLR_NORMAL_ENCODING
  const bool octahedral = SSLR_NORMAL_ENCODING == SSLR_NORMALS_OCTAHEDRAL;
  const bool worldNormals = SSLR_WORLD_NORMALS != 0;
  const bool unsignedUnpack = SSLR_NORMAL_UNSIGNED != 0;
#else
  bool octahedral = s.normalEncoding == SSLR_NORMALS_OCTAHEDRAL;
  bool worldNormals = s.normalFromStored0.w != 0.0f;
  bool unsignedUnpack = sslrUnsignedNormalUnpack(s);
#endif
  vec3 n;
  if (octahedral) {
    // The octahedral coordinates in [0, 1]: stored so by unsigned formats, else unpacked first.
    vec2 e = vec2(texel.x, texel.y);
    if (!unsignedUnpack) e = (e * s.normalScale + s.normalBias) * 0.5f + 0.5f;
    e = clamp(e, vec2(0.0f), vec2(1.0f));
    n = sslrOctDecode(e);
  } else {
    n = unsignedUnpack ? vec3(texel.x, texel.y, texel.z) * 2.0f - 1.0f
                       : vec3(texel.x, texel.y, texel.z) * s.normalScale + s.normalBias;
    float len2 = dot(n, n);
    // 8-bit packing of a unit vector keeps |n| within ~1.5%; zero or garbage fails this.
    if (!(len2 > 0.8f && len2 < 1.2f)) {
      vsNormal = vec3(0.0f, 0.0f, 1.0f);
      return false;
    }
    n = normalize(n);
  }
  if (worldNormals) {  // world-space normals: into view space
    n = normalize(vec3(s.normalFromStored0.x, s.normalFromStored0.y, s.normalFromStored0.z) * n.x +
                  vec3(s.normalFromStored1.x, s.normalFromStored1.y, s.normalFromStored1.z) * n.y +
                  vec3(s.normalFromStored2.x, s.normalFromStored2.y, s.normalFromStored2.z) * n.z);
  }
  bool finite = !(isnan(n.x) || isnan(n.y) || isnan(n.z) || isinf(n.x) || isinf(n.y) || isinf(n.z));
  vsNormal = finite ? n : vec3(0.0f, 0.0f, 1.0f);
  return finite;
}

SSLR_FN float sslrChannel(vec4 v, int channel) {
  return channel == 0 ? v.x : (channel == 1 ? v.y : (channel == 2 ? v.z : v.w));
}
SSLR_FN float sslrRoughness(SslrSurface s, vec4 texel) {
  return s.roughnessChannel < 0 ? s.constantRoughness : sslrChannel(texel, s.roughnessChannel);
}
SSLR_FN float sslrReflectance(SslrSurface s, vec4 texel) {
  return s.reflectanceChannel < 0 ? s.constantReflectance : sslrChannel(texel, s.reflectanceChannel);
}

// Coloured F0 (metalness workflow, SurfaceLayout::metalnessChannel): the reflectance for
// dielectrics, the base colour for metals, mixed by metalness. Metalness and base colour are
// clamped to [0, 1] (NaN reads as 0), so a poisoned input cannot leave the Fresnel range.
SSLR_FN float sslrUnitOrZero(float x) { return x > 0.0f ? min(x, 1.0f) : 0.0f; }  // [0, 1], NaN -> 0
SSLR_FN vec3 sslrF0FromMetalness(float reflectance, vec3 baseColor, float metalness) {
  float m = sslrUnitOrZero(metalness);
  vec3 base = vec3(sslrUnitOrZero(baseColor.x), sslrUnitOrZero(baseColor.y), sslrUnitOrZero(baseColor.z));
  return vec3(reflectance) * (1.0f - m) + base * m;
}

// Whether a pixel's material is worth a ray: reflective enough and smooth enough. Written so that
// NaN material values fail.
SSLR_FN bool sslrMaterialTraced(SslrTraceParams t, float reflectance, float roughness) {
  return reflectance > t.minReflectance && roughness <= t.roughnessCutoff;
}

// A pixel that may need a ray: geometry (not background) of a traced material. Classification
// lists tiles by this test (1_classify.comp), which needs no normal; the passes after it ask
// sslrShouldTrace of each pixel.
SSLR_FN bool sslrTraceCandidate(SslrSurface s, SslrTraceParams t, float depth, float reflectance,
                                float roughness) {
  return sslrIsGeometryDepth(s, depth) && sslrMaterialTraced(t, reflectance, roughness);
}

// The per-pixel test shared by tracing, the blur's neighbour test and temporal reuse: a candidate
// (above) whose normal decodes. `material` is the texel holding the material channels: the normal
// texel itself unless the host gave a separate material texture (SslrSurface::separateMaterial).
SSLR_FN bool sslrShouldTrace(SslrSurface s, SslrTraceParams t, float depth, vec4 packedNormal, vec4 material) {
  // A branch of its own, not one && chain: shader compilers evaluate such a chain whole, and the
  // normal decode is most of the test's cost.
  if (!sslrTraceCandidate(s, t, depth, sslrReflectance(s, material), sslrRoughness(s, material))) return false;
  vec3 n;
  return sslrDecodeNormal(s, packedNormal, n);
}

// ---- Min-max depth pyramid (hierarchical traversal) -----------------------------------------
// Level l >= 1 holds, per 2^l x 2^l cell, the (min, max) of the raw window depth of its pixels
// (with curved solids, the far end reaches the backs of their solids: "Curved solids" below).
// Level l has ceil(size / 2^l) cells per axis, so cell c of level l covers exactly pixels
// [c 2^l, (c + 1) 2^l) of the screen. Level 0 is the pyramid's too (mip 0 of the same texture):
// per pixel, its depth as sslrHiZTexel reads it and its curved solid's extra depth
// (sslrHiZLevel0Texel; a quad of background alone gets none, and the walk never reads level 0
// there). The traversal's walk thus reads every level, and a pixel's extra depth, in
// one fetch per step: with level 0 in the depth buffer and the extra depths in a texture of
// their own, SIMD lanes at different levels fetched from all three (llvmpipe runs every branch's
// fetch under lane masks; docs/design-notes.md).

// Levels worth building: the top level's cells are about an eighth of the larger screen side
// (coarser cells would cover most of the screen and skip nothing).
SSLR_FN int sslrHiZLevelCount(int width, int height) {
  int side = max(max(width, height), 1);
  int levels = 0;
  while (levels < SSLR_HIZ_MAX_LEVELS && (side >> (levels + 1)) >= 8) ++levels;
  return max(levels, 1);
}

// The pyramid's (min, max) for a cell without pixels (outside the screen): neutral in both.
SSLR_FN vec2 sslrHiZEmpty() { return vec2(2.0f, -1.0f); }

// One depth texel as the pyramid stores it: background, NaN and out-of-range depth all become the
// clear value (the farthest depth), so nothing that is not geometry can stop a ray.
SSLR_FN vec2 sslrHiZTexel(SslrSurface s, float depth) {
  float d = sslrIsGeometryDepth(s, depth) ? depth : (s.reversedZ != 0 ? 0.0f : 1.0f);
  return vec2(d, d);
}

SSLR_FN vec2 sslrHiZReduce(vec2 a, vec2 b) { return vec2(min(a.x, b.x), max(a.y, b.y)); }

// Level 0's texel of a pixel: (its depth as sslrHiZTexel reads it, its curved extra depth, 0 on
// flat surfaces and without curved solids).
SSLR_FN vec2 sslrHiZLevel0Texel(SslrSurface s, float depth, float extra) {
  return vec2(sslrHiZTexel(s, depth).x, extra);
}
// The (min, max) of a cell from its pyramid texel: a level-0 texel holds one depth.
SSLR_FN vec2 sslrHiZMinMax(int level, vec2 texel) { return level == 0 ? vec2(texel.x, texel.x) : texel; }
// Whether a cell of level >= 1 holds any geometry: its nearest depth is not background. Where it
// does not, classification writes no level-0 texels under it and the traversal skips it whole.
SSLR_FN bool sslrHiZCellHoldsGeometry(SslrSurface s, vec2 minMax) {
  return sslrIsGeometryDepth(s, s.reversedZ != 0 ? max(minMax.x, minMax.y) : min(minMax.x, minMax.y));
}

// View distance (or orthographic -z) of a window depth: the tolerance and "how far behind" tests
// of the traversal work in view units, like the adaptive-L tracer's.
SSLR_FN float sslrViewDepthFromDepth(SslrProjection p, float depth) {
  return -sslrViewFromNdc(p, vec2(0.0f), sslrNdcZFromDepth(p, depth)).z;
}

// Window depth of a view depth (-z): sslrViewDepthFromDepth's inverse.
SSLR_FN float sslrDepthFromViewDepth(SslrProjection p, float dist) {
  if (p.orthographic != 0) return sslrDepthFromNdcZ(p, p.zOffset - p.zScale * dist);
  float ndcScale = p.ndcZeroToOne != 0 ? 1.0f : 2.0f;
  return (p.zOffset / (ndcScale * dist) + p.infDepthLo) + p.infDepthHi;
}

// ---- Curved solids (hierarchical traversal) ---------------------------------------------------
// A depth buffer has no thickness; the traversal assumes what a pixel shows to be objectDepthRelative x
// its distance deep. A convex curved surface tells more: it is taken to be the surface of a solid
// as curved as it looks, a sphere of its own radius of curvature r, which extends 2 r cos(a)
// behind the pixel along the view ray (a: the view ray's angle to the normal). A mirror sphere of
// radius 1 seen from 8 units is 2 deep at its centre, the default slab 0.6: rays that run into its
// hidden side would be let through to the wall behind.
// Flat faces (a box) keep the slab. Settings::curvedSolids (default on); the GPU passes get it
// compiled in (SSLR_CURVED_SOLIDS). Classification only lists the quads whose normals turn and a
// pass of its own computes their cells, so that the math costs the listed quads alone.
SSLR_FN bool sslrCurvedSolids(SslrTraceParams t) {
#ifdef SSLR_CURVED_SOLIDS
  return SSLR_CURVED_SOLIDS != 0;
#else
  return t.curvedSolids != 0;
#endif
}

// The radius of curvature between two neighbouring pixels, or 0 where they do not look like one
// convex curved surface. On a sphere P_a - P_b = r (N_a - N_b) exactly; the two differences must
// point the same way (convex, within ~18 deg) and the normals turn by more than their encoding's
// noise (8-bit xyz: ~0.5 deg per component) and less than an edge's ~20 deg; a step of more than
// 8 footprints (footprintA: pixel A's) is a depth jump (a silhouette), not a surface. Squared
// forms: every listed quad runs this four times, and on a CPU rasterizer each square root and
// division shows.
SSLR_FN float sslrConvexRadius(SslrSurface s, vec3 vsA, vec3 vsNa, vec3 vsB, vec3 vsNb, float footprintA) {
#ifdef SSLR_NORMAL_ENCODING
  const bool octahedral = SSLR_NORMAL_ENCODING == SSLR_NORMALS_OCTAHEDRAL;
#else
  bool octahedral = s.normalEncoding == SSLR_NORMALS_OCTAHEDRAL;
#endif
  float minTurn2 = octahedral ? 3e-5f : 1.2e-3f;  // (0.3 deg)^2, (2 deg)^2 in radians^2
  vec3 dN = vsNa - vsNb;
  float dn2 = dot(dN, dN);
  vec3 dP = vsA - vsB;
  float along = dot(dP, dN);
  float dp2 = dot(dP, dP);
  bool curved = dn2 > minTurn2 && dn2 < 0.12f && along > 0.0f && along * along > 0.9025f * dp2 * dn2 &&
                dp2 <= 64.0f * footprintA * footprintA;
  return curved ? along / dn2 : 0.0f;
}

// How much deeper than the slab (objectDepthRelative x view depth) a pixel's solid extends, in view
// depth: max(0, min(2 r cos a, 4 x slab) |v.z| - slab), v the unit view direction. The cap keeps a
// gently curved wall from becoming a solid hill. r: the largest radius the pixel shares with a
// neighbour (sslrConvexRadius).
SSLR_FN float sslrCurvedExtraDepth(SslrProjection p, SslrTraceParams t, vec3 vsPos, vec3 vsNormal, float r) {
  vec3 v = p.orthographic != 0 ? vec3(0.0f, 0.0f, -1.0f) : vsPos * inversesqrt(dot(vsPos, vsPos));
  float slab = t.objectDepthRelative * -vsPos.z;
  float chord = min(2.0f * r * abs(dot(vsNormal, v)), 4.0f * slab) * abs(v.z);
  return max(chord - slab, 0.0f);
}

// Two estimates of one radius that agree within a factor of 2 (0 where either is missing): both
// rows (or both columns) of a quad on a sphere or a cylinder see the same curvature; noise does
// not: per-pixel turns like a normal map's pass one pair's test on some flat pixels, and would
// make those faces deep.
SSLR_FN float sslrAgreedRadius(float a, float b) {
  return a > 0.0f && b > 0.0f && a < 2.0f * b && b < 2.0f * a ? min(a, b) : 0.0f;
}

// The extra depth of each pixel of a 2x2 quad (x, y, z, w: pixels (0,0), (1,0), (0,1), (1,1)),
// from the quad's radius: its two rows' estimates where they agree, or its two columns'
// (sslrAgreedRadius), the larger. ok: the pixel holds geometry with a trusted normal. The curved
// pass computes it once for the pyramid's level 1 and for the traversal's pixels
// (level 0's texels), so a cell's farthest key bounds what its pixels' solids reach.
SSLR_FN vec4 sslrQuadCurvedExtraDepth(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 vs0, vec3 vs1,
                                      vec3 vs2, vec3 vs3, vec3 n0, vec3 n1, vec3 n2, vec3 n3, bvec4 ok) {
  // One footprint per quad, its farthest pixel's (a pixel without geometry has vs = 0).
  float farthest = max(max(-vs0.z, -vs1.z), max(-vs2.z, -vs3.z));
  float footprint = sslrPixelFootprint(p, s.height, p.orthographic != 0 ? 1.0f : max(farthest, 0.0f));
  float r01 = ok.x && ok.y ? sslrConvexRadius(s, vs0, n0, vs1, n1, footprint) : 0.0f;
  float r23 = ok.z && ok.w ? sslrConvexRadius(s, vs2, n2, vs3, n3, footprint) : 0.0f;
  float r02 = ok.x && ok.z ? sslrConvexRadius(s, vs0, n0, vs2, n2, footprint) : 0.0f;
  float r13 = ok.y && ok.w ? sslrConvexRadius(s, vs1, n1, vs3, n3, footprint) : 0.0f;
  float r = max(sslrAgreedRadius(r01, r23), sslrAgreedRadius(r02, r13));
  return vec4(ok.x ? sslrCurvedExtraDepth(p, t, vs0, n0, r) : 0.0f, ok.y ? sslrCurvedExtraDepth(p, t, vs1, n1, r) : 0.0f,
              ok.z ? sslrCurvedExtraDepth(p, t, vs2, n2, r) : 0.0f, ok.w ? sslrCurvedExtraDepth(p, t, vs3, n3, r) : 0.0f);
}

// ---- Measured thickness: back-face depth (FrameInputs::backDepthTexture) ----------------------
// With a back-face depth (the host's depth pass with front faces culled: per pixel, the nearest
// back face), what a pixel shows is as deep as measured, not objectDepthRelative x its distance: a
// leg thinner than the slab lets rays pass just behind it, a box seen across its diagonal stops
// rays deeper than the slab. The measurement enters where the curved solids' estimate does (it
// replaces it): as the pixel's extra depth over the slab, in level 0 of the pyramid and in the
// far key of level 1 where positive. Negative extra depths thin the slab (down to nothing: the
// traversal then lets a ray just behind a very thin object pass). Compiled in (SSLR_BACK_DEPTH)
// on the GPU.
SSLR_FN bool sslrBackDepth(SslrSurface s) {
#ifdef SSLR_BACK_DEPTH
  return SSLR_BACK_DEPTH != 0;
#else
  return s.hasBackDepth != 0;
#endif
}

// A pixel's measured extra depth over the slab (view units), or 0 where nothing is measured: no
// back face behind it (a floor, an open mesh, the background), or the back face not behind the
// shown surface (a one-sided face seen from behind is its own back face). front: the view depth
// of `depth` (sslrViewDepthFromDepth).
SSLR_FN float sslrMeasuredExtraDepth(SslrProjection p, SslrSurface s, SslrTraceParams t, float depth, float front,
                                     float backDepth) {
  if (!sslrIsGeometryDepth(s, depth) || !sslrIsGeometryDepth(s, backDepth)) return 0.0f;
  float thickness = sslrViewDepthFromDepth(p, backDepth) - front;
  if (!(thickness > 1e-4f * front)) return 0.0f;
  float extra = thickness - t.objectDepthRelative * front;
  return extra != 0.0f ? extra : 1e-7f * front;  // 0 means "not measured"
}

// A pixel's texel of level 1 when its solid reaches extra deeper than the slab: (min, max) of its
// depth and of the depth of the solid's back (clamped to the depth range). viewDepth: the
// pixel's view depth (-z).
SSLR_FN vec2 sslrHiZSolidTexel(SslrProjection p, SslrSurface s, float depth, float viewDepth, float extra) {
  vec2 texel = sslrHiZTexel(s, depth);
  if (!(extra > 0.0f) || !sslrIsGeometryDepth(s, depth)) return texel;
  float back = clamp(sslrDepthFromViewDepth(p, viewDepth + extra), 0.0f, 1.0f);
  return vec2(min(texel.x, back), max(texel.y, back));
}

// Level 1's cell of a quad whose pixels' solids reach `extra` deeper than the slab (curved or
// measured): the min-max of the four sslrHiZSolidTexel.
SSLR_FN vec2 sslrHiZQuadSolids(SslrProjection p, SslrSurface s, vec4 depths, vec4 viewDepths, vec4 extra) {
  return sslrHiZReduce(sslrHiZReduce(sslrHiZSolidTexel(p, s, depths.x, viewDepths.x, extra.x),
                                     sslrHiZSolidTexel(p, s, depths.y, viewDepths.y, extra.y)),
                       sslrHiZReduce(sslrHiZSolidTexel(p, s, depths.z, viewDepths.z, extra.z),
                                     sslrHiZSolidTexel(p, s, depths.w, viewDepths.w, extra.w)));
}

// Pixel k (0: (0,0), 1: (1,0), 2: (0,1), 3: (1,1)) of level-1 cell `cell`'s 2x2 quad, clamped to
// the screen (`last`: the last pixel): a quad straddling the edge repeats one of its own pixels,
// neutral for the min-max and flat for the curvature.
SSLR_FN ivec2 sslrQuadPixel(ivec2 cell, int k, ivec2 last) {
  return min(cell * 2 + ivec2(k & 1, k >> 1), last);
}

// Level 1 with measured thickness: the (min, max) of the quad's depths and, where a solid reaches
// deeper than the slab, of its back (sslrHiZSolidTexel); `extra` receives the pixels' measured
// extra depths (sslrMeasuredExtraDepth) for level 0.
SSLR_FN vec2 sslrHiZLevel1Measured(SslrProjection p, SslrSurface s, SslrTraceParams t, vec4 depths, vec4 backDepths,
                                   SSLR_OUT(vec4) extra) {
  vec4 front = vec4(sslrViewDepthFromDepth(p, depths.x), sslrViewDepthFromDepth(p, depths.y),
                    sslrViewDepthFromDepth(p, depths.z), sslrViewDepthFromDepth(p, depths.w));
  extra = vec4(sslrMeasuredExtraDepth(p, s, t, depths.x, front.x, backDepths.x),
               sslrMeasuredExtraDepth(p, s, t, depths.y, front.y, backDepths.y),
               sslrMeasuredExtraDepth(p, s, t, depths.z, front.z, backDepths.z),
               sslrMeasuredExtraDepth(p, s, t, depths.w, front.w, backDepths.w));
  return sslrHiZQuadSolids(p, s, depths, front, extra);
}

// Level 1 of the pyramid without solids: the (min, max) of a quad's four depths.
SSLR_FN vec2 sslrHiZLevel1Plain(SslrSurface s, vec4 depths) {
  return sslrHiZReduce(sslrHiZReduce(sslrHiZTexel(s, depths.x), sslrHiZTexel(s, depths.y)),
                       sslrHiZReduce(sslrHiZTexel(s, depths.z), sslrHiZTexel(s, depths.w)));
}

// Whether a quad's normals turn at all (packed texels compared): only such quads can hold a curved
// solid (sslrConvexRadius needs a turn), so classification lists them for the curved pass and
// gives the others the plain cell, which is what sslrHiZLevel1Cell computes for them.
SSLR_FN bool sslrQuadNormalsTurn(vec4 n0, vec4 n1, vec4 n2, vec4 n3) {
  return n0 != n1 || n0 != n2 || n0 != n3;
}

// Level 1 of the pyramid, one cell from its 2x2 quad (pixel coordinates clamped to the screen,
// their depth and packed normal texels): the curved pass on the GPU, the CPU tracer's pyramid and
// the tests all build it here. With curved solids, `extra` receives the quad's pixels' extra
// depths (sslrQuadCurvedExtraDepth), which the curved pass stores in level 0 for the traversal's
// pixels (the quad's math inside the traversal's loop cost every step on llvmpipe).
SSLR_FN vec2 sslrHiZLevel1Cell(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 p0, ivec2 p1, ivec2 p2,
                               ivec2 p3, vec4 depths, vec4 n0, vec4 n1, vec4 n2, vec4 n3, SSLR_OUT(vec4) extra) {
  extra = vec4(0.0f);
  if (!sslrCurvedSolids(t)) return sslrHiZLevel1Plain(s, depths);
  vec3 vs0, vs1, vs2, vs3, m0, m1, m2, m3;
  bool ok0 = sslrSurfaceFromDepth(p, s, p0, depths.x, vs0);
  ok0 = sslrDecodeNormal(s, n0, m0) && ok0;
  bool ok1 = sslrSurfaceFromDepth(p, s, p1, depths.y, vs1);
  ok1 = sslrDecodeNormal(s, n1, m1) && ok1;
  bool ok2 = sslrSurfaceFromDepth(p, s, p2, depths.z, vs2);
  ok2 = sslrDecodeNormal(s, n2, m2) && ok2;
  bool ok3 = sslrSurfaceFromDepth(p, s, p3, depths.w, vs3);
  ok3 = sslrDecodeNormal(s, n3, m3) && ok3;
  extra = sslrQuadCurvedExtraDepth(p, s, t, vs0, vs1, vs2, vs3, m0, m1, m2, m3, bvec4(ok0, ok1, ok2, ok3));
  return sslrHiZQuadSolids(p, s, depths, vec4(-vs0.z, -vs1.z, -vs2.z, -vs3.z), extra);
}

// ---- Weights ------------------------------------------------------------------------------
// cosVN = dot(-V, N) = cosine of the angle between the normal and the direction to the camera.
// The article writes 2.8 * pow(1 + dot(V, N), 2) with V pointing into the surface: the same.
SSLR_FN float sslrFresnelClassic(float cosVN) {
  float x = 1.0f - sslrSaturate(cosVN);
  return sslrSaturate(2.8f * x * x);
}
SSLR_FN float sslrFresnelSchlick(float f0, float cosVN) {
  float x = 1.0f - sslrSaturate(cosVN);
  float x2 = x * x;
  return f0 + (1.0f - f0) * x2 * x2 * x;
}
// The article's error term, long reflections fade out: 1 - saturate(L k). The article's L is in
// world units, so its k ties the look to the scene's unit (a scene modelled in centimetres loses
// its reflections). Here L is measured relative to the reflecting point's distance from the
// camera (orthographic: its depth), which is the same at every scale.
SSLR_FN float sslrErrorWeight(SslrProjection p, vec3 vsP, float L, float k) {
  float distance = p.orthographic != 0 ? abs(vsP.z) : length(vsP);
  return 1.0f - sslrSaturate(L / max(distance, 1e-30f) * k);
}

// 1 inside, falling linearly to 0 over `width` (fraction of the screen) at each border.
SSLR_FN float sslrEdgeFade(vec2 uv, float width) {
  if (width <= 0.0f) return sslrInsideUv(uv) ? 1.0f : 0.0f;
  vec2 d = min(uv, 1.0f - uv) / width;
  return sslrSaturate(min(d.x, d.y));
}

// Rays heading back towards the camera see the back of what the screen shows: fade them. The fade
// is presentation (it weights the colour), never part of the hit decision or its confidence.
SSLR_FN float sslrCameraFacingFade(vec3 vsR, vec3 vsV, float start, float end) {
  float towardsCamera = dot(vsR, -vsV);
  return 1.0f - smoothstep(start, max(end, start + 1e-4f), towardsCamera);
}

// Blur radius in pixels for a reflection of length L seen from a surface at view distance
// `dist`: a cone of tan(half angle) = roughness^2 * coneScale spreads to L * tan at the hit,
// which the camera sees at the mirror image's distance dist + L.
SSLR_FN float sslrBlurRadiusPx(SslrProjection p, float heightPx, float dist, float L,
                               float roughness, float coneScale) {
  float spread = L * roughness * roughness * coneScale;
  float imageDist = p.orthographic != 0 ? 1.0f : dist + L;
  return spread / sslrPixelFootprint(p, heightPx, imageDist);
}

// The blur pass's bilateral weight of a neighbour `offsetPx` pixels away along the blur's axis,
// for a centre pixel of blur radius `radiusPx` (>= 0.5) at view distance z0 with normal n0 and a
// neighbour at z1 with n1:
//   exp(-offset^2 / (2 sigma^2)) * exp(-|z1 - z0| / (blur.depthSigma z0)) * max(0, n0.n1)^blur.normalPower
// with sigma = max(radius / 2, 0.5): a Gaussian, a depth term relative to the centre's distance (so
// the same surface step counts the same near and far) and a normal term, so a reflection does not
// bleed across an edge or a crease. Evaluated as one exp2 of a sum of logarithms (one exp2 and one
// log2 per tap, not two exps and a pow); the per-centre factors are computed once per pixel.
struct SslrBlurCentre {
  float gaussianLog2;  // log2(e) * -1 / (2 sigma^2): times offset^2
  float depthLog2;     // log2(e) * -1 / (blur.depthSigma z0): times |z1 - z0|
  float z;             // view distance z0
  float normalPower;   // blur.normalPower
  vec3 normal;         // n0
};

SSLR_FN SslrBlurCentre sslrBlurCentre(SslrTraceParams t, float radiusPx, float z0, vec3 n0) {
  const float log2e = 1.44269504f;
  float sigma = max(radiusPx * 0.5f, 0.5f);
  SslrBlurCentre c;
  c.gaussianLog2 = -0.5f * log2e / (sigma * sigma);
  c.depthLog2 = -log2e / max(t.blurDepthSigma * z0, 1e-6f);
  c.z = z0;
  c.normalPower = t.blurNormalPower;
  c.normal = n0;
  return c;
}

// Settings::radianceClamp: `color` scaled down (hue kept) to a Rec. 709 luminance of at most
// `maxLuminance`; unchanged when that is 0 (off) or the colour is below it.
SSLR_FN vec3 sslrClampLuminance(vec3 color, float maxLuminance) {
  float luminance = dot(color, vec3(0.2126f, 0.7152f, 0.0722f));
  return maxLuminance > 0.0f && luminance > maxLuminance ? color * (maxLuminance / luminance) : color;
}

// One tap's weight in the blur's sum (not the "blur weight", the reflection's alpha that sets
// the radius): Gaussian in the offset, falling with the depth and normal differences.
SSLR_FN float sslrBlurTapWeight(SslrBlurCentre c, int offsetPx, float z1, vec3 n1) {
  float normalLog2 = 0.0f;  // blur.normalPower 0: no normal term
  if (c.normalPower > 0.0f) {
    float cosine = dot(c.normal, n1);
    if (!(cosine > 0.0f)) return 0.0f;  // max(0, n0.n1)^power = 0 (log2 would be undefined)
    normalLog2 = c.normalPower * log2(cosine);
  }
  return exp2(c.gaussianLog2 * float(offsetPx * offsetPx) + c.depthLog2 * abs(z1 - c.z) + normalLog2);
}

// ---- GGX lobe (the glossy reference, tools/truth) ----------------------------------------------
// alpha = roughness^2 (perceptual roughness, as the blur's cone). Directions in a tangent frame
// with the normal along +z.
// Smith's masking for GGX: G1(v) = 2 cos / (cos + sqrt(alpha^2 + (1 - alpha^2) cos^2)).
SSLR_FN float sslrSmithG1(float cosTheta, float alpha) {
  if (!(cosTheta > 0.0f)) return 0.0f;
  float a2 = alpha * alpha;
  return 2.0f * cosTheta / (cosTheta + sqrt(a2 + (1.0f - a2) * cosTheta * cosTheta));
}
// A microfacet normal drawn from GGX's distribution of normals visible from `ve` (unit, z > 0),
// by Heitz 2018 ("Sampling the GGX Distribution of Visible Normals", JCGT 7(4)), from two
// uniform numbers in [0, 1). Reflecting ve about it gives a light direction whose weight, for the
// lobe's mean radiance, is G1 of that direction (sslrSmithG1).
SSLR_FN vec3 sslrSampleGgxVndf(vec3 ve, float alpha, vec2 u) {
  vec3 vh = normalize(vec3(alpha * ve.x, alpha * ve.y, ve.z));  // the view in the hemisphere configuration
  float lensq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = 6.28318531f * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * p2;
  vec3 nh = t1 * p1 + t2 * p2 + vh * sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2));
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0f, nh.z)));  // back to the ellipsoid
}

// Point k of an n-point Hammersley set in [0, 1)^2 (stratified: (k + 0.5) / n, then k's bits
// reversed).
SSLR_FN vec2 sslrHammersley(int k, int n) {
  uint bits = uint(k);
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return vec2((float(k) + 0.5f) / float(n), float(bits) * 2.3283064365386963e-10f);
}

// A pixel's ray in GlossyMode::Stochastic: the reflection of the view (vsV, towards the surface)
// about a normal drawn from the lobe's visible normals around vsN; a direction below the surface
// (the lobe's masked part) falls back to the mirror ray.
SSLR_FN vec3 sslrGgxReflectionSample(vec3 vsV, vec3 vsN, float alpha, vec2 u) {
  vec3 t = normalize(abs(vsN.z) < 0.999f ? cross(vec3(0.0f, 0.0f, 1.0f), vsN) : cross(vec3(1.0f, 0.0f, 0.0f), vsN));
  vec3 b = cross(vsN, t);
  vec3 ve = vec3(dot(-vsV, t), dot(-vsV, b), dot(-vsV, vsN));
  vec3 l = reflect(-ve, sslrSampleGgxVndf(ve, alpha, u));
  if (!(l.z > 0.0f)) return reflect(vsV, vsN);
  return normalize(t * l.x + b * l.y + vsN * l.z);
}

// Integer hash (Wellons' lowbias32) and two uniform numbers in [0, 1) per pixel and frame.
SSLR_FN uint sslrHash(uint x) {
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}
SSLR_FN vec2 sslrPixelRandom(ivec2 px, int frameIndex) {
  uint h = sslrHash(uint(px.x) * 1973u + uint(px.y) * 9277u + uint(frameIndex) * 26699u);
  return vec2(float(h >> 8u), float(sslrHash(h ^ 0x9e3779b9u) >> 8u)) * (1.0f / 16777216.0f);
}

// ---- Half resolution (Settings::halfResolution) ----------------------------------------------
// One ray per 2x2 quad; the quad's other pixels reuse its hit when they lie on the traced pixel's
// surface, and trace their own ray otherwise.

// Pixel offsets within a quad, in the order the traced pixel rotates through (one per frame).
SSLR_FN ivec2 sslrQuadOffset(int index) {
  return index == 0 ? ivec2(0, 0) : (index == 1 ? ivec2(1, 1) : (index == 2 ? ivec2(1, 0) : ivec2(0, 1)));
}

// What a quad's ray says to the quad's other pixels (the quad record's w, one float):
// SSLR_QUAD_HIT       its hit, re-planed for each of them (a record no ray wrote is this, with no hit);
// SSLR_QUAD_OWN_RAYS  adaptive L did not converge and no traversal ran: each traces its own ray
//                     (adaptive L may converge for it);
// SSLR_QUAD_MISS      no hit (the ray left the screen, met the sky, or the traversal found nothing):
//                     a miss for them too, unless a neighbouring quad's ray hit. There the miss may
//                     be a band along an edge (rays passing behind a box, beyond a mirror's end,
//                     leaving the screen just past its border) that a pixel's own ray escapes.
#define SSLR_QUAD_HIT 0
#define SSLR_QUAD_OWN_RAYS 1
#define SSLR_QUAD_MISS 2
struct SslrQuadCode {
  float confidence;  // the quad ray's, in [0, 0.999]
  int index;         // the traced pixel (sslrQuadOffset)
  int kind;          // SSLR_QUAD_*
};
// w = confidence + 2 index + 8 kind: index and kind exact, the confidence to one float step of w
// (< 2e-6), clamped below 1 so that it cannot carry into the index.
SSLR_FN float sslrPackQuadCode(float confidence, int index, int kind) {
  return min(max(confidence, 0.0f), 0.999f) + 2.0f * float(index) + 8.0f * float(kind);
}
SSLR_FN SslrQuadCode sslrUnpackQuadCode(float w) {
  SslrQuadCode c;
  c.kind = clamp(int(floor(w * 0.125f)), 0, 2);
  float rest = w - 8.0f * float(c.kind);
  c.index = clamp(int(floor(rest * 0.5f)), 0, 3);
  c.confidence = rest - 2.0f * float(c.index);
  return c;
}

// Whether P (normal N) lies on the surface of the quad's traced pixel (Pc, Nc): on its tangent
// plane within depth precision and a quarter pixel, with normals within about 1.8 degrees. Exact
// for planes whatever their slope (a depth comparison is not: a floor seen at a grazing angle
// changes depth by many percent from one pixel to the next).
SSLR_FN bool sslrSameSurface(SslrProjection p, SslrSurface s, vec3 vsP, vec3 vsN, vec3 vsPc, vec3 vsNc) {
  float dist = p.orthographic != 0 ? abs(vsP.z) : sslrViewDistance(p, vsP);
  float tolerance = 0.002f * dist + 0.25f * sslrPixelFootprint(p, s.height, p.orthographic != 0 ? 1.0f : dist);
  return dot(vsN, vsNc) > 0.9995f && abs(dot(vsP - vsPc, vsNc)) <= tolerance;
}

// The length along P's ray R to the plane of the quad's hit (point H, normal Nh): a neighbouring
// pixel of a plane sees the same reflected surface, shifted. A plane seen edge-on by the ray
// keeps the quad's point; a plane behind the ray gives -1 (no reuse).
SSLR_FN float sslrReusedLength(vec3 vsP, vec3 vsR, vec3 vsH, vec3 vsNh) {
  float dn = dot(vsR, vsNh);
  if (!(dn < -0.05f)) return length(vsH - vsP);
  float L = dot(vsH - vsP, vsNh) / dn;
  return L > 0.0f ? L : -1.0f;
}

// ---- Temporal reuse ----------------------------------------------------------------------------
// The history key of a view-space point: what tells a surface from the one that hid it. Under a
// perspective projection the view depth (clip w), under an orthographic one NDC z (linear in
// depth there, and clip w is 1). Always > 0 for visible geometry (0 marks "no history").
SSLR_FN float sslrHistoryKeyFromClip(int orthographic, vec4 clip) {
  return orthographic != 0 ? 2.0f + clip.z / clip.w : clip.w;
}

// This frame's key of view-space point P (the same quantity as sslrHistoryKeyFromClip).
SSLR_FN float sslrHistoryKey(SslrProjection p, vec3 vsP) {
  return p.orthographic != 0 ? 2.0f + sslrNdcFromView(p, vsP).z : sslrClipW(p, vsP);
}

// Where view-space point P (this frame) was in the previous frame: its uv there and its key
// there. False when it was behind the previous camera or outside its screen.
SSLR_FN bool sslrReproject(SslrProjection p, mat4 previousClipFromView, vec3 vsP, SSLR_OUT(vec2) uvPrevious,
                           SSLR_OUT(float) keyPrevious) {
  vec4 clip = previousClipFromView * vec4(vsP, 1.0f);
  uvPrevious = vec2(-1.0f);
  keyPrevious = 0.0f;
  if (!(clip.w > 0.0f)) return false;
  uvPrevious = sslrUvFromNdc(vec2(clip.x, clip.y) / clip.w);
  keyPrevious = sslrHistoryKeyFromClip(p.orthographic, clip);
  return sslrInsideUv(uvPrevious);
}

// Where a mirror's reflection was in the previous frame. The reflection of hit Q seen at P
// (normal N, reflected length L) is the virtual point V = P + L * (P - eye) / |P - eye|, behind
// the mirror; the previous camera saw it through the mirror plane at X, where the segment from
// its eye to V crosses the plane. X is returned (view space, this frame); false when the previous
// eye is unknown or on the plane's far side.
SSLR_FN bool sslrVirtualPointOnMirror(vec4 previousEye, vec3 vsP, vec3 vsN, float L, SSLR_OUT(vec3) vsX) {
  vsX = vsP;
  if (previousEye.w == 0.0f || !(L > 0.0f)) return false;
  vec3 eye = vec3(previousEye.x, previousEye.y, previousEye.z);
  vec3 vsVirtual = vsP + normalize(vsP) * L;
  vec3 d = vsVirtual - eye;
  float denom = dot(d, vsN);
  float t = dot(vsP - eye, vsN) / denom;
  if (!(dot(eye - vsP, vsN) > 0.0f) || !(t > 0.0f && t < 1.0f)) return false;
  vsX = eye + d * t;
  return true;
}

// Whether a stored history key belongs to the same surface as the expected one.
SSLR_FN bool sslrHistoryKeyMatches(float stored, float expected, float tolerance) {
  return stored > 0.0f && abs(stored - expected) <= tolerance * expected;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_H
