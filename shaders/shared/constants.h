// shared/constants.h - Enumerations and limits: plain #defines, so that both languages and #if can use them.
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_CONSTANTS_H
#define SSLR_SHARED_CONSTANTS_H

#include "language.h"

#ifdef __cplusplus
namespace sslr::shared {
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
#define SSLR_STATUS_HIDDEN 5      // the traversal ran into a solid the back-face depth measured:
                                  // what the ray meets is hidden (L: where that was known)

#define SSLR_HIZ_OFF 0              // adaptive L alone (the article's method, made robust)
#define SSLR_HIZ_TRAVERSAL_FIRST 1  // the traversal on every ray; adaptive L where it has no hit
                                    // (Settings::traversal.maxSteps > 0, the default)
#define SSLR_HIZ_ONLY 2             // the hierarchical traversal alone (Method::HierarchicalDepth)

// The hit tolerance (sslrHitTolerance): a ray point Q counts as on the surface P' a pixel shows
// within this fraction of the view distance (depth precision) plus this many pixel footprints,
// stretched by the surface's slope as seen (1 + tan).
#define SSLR_HIT_TOLERANCE_RELATIVE 0.002f
#define SSLR_HIT_TOLERANCE_PIXELS 1.5f

// Thin objects (sslrMetThinObject, traversal first): a ray met the hidden side of what a pixel shows when that
// object is at most SSLR_THIN_MAX_WIDTH_PX and SSLR_THIN_MAX_WIDTH_SCREEN x the screen height
// across, and the ray went in less deep than SSLR_THIN_DEPTH_PER_WIDTH times its width and
// SSLR_THIN_MAX_DEPTH_FOOTPRINTS pixel footprints (sslrMetThinObject; docs/algorithm.md, "Thin objects").
#define SSLR_THIN_MAX_WIDTH_PX 16
#define SSLR_THIN_MAX_WIDTH_SCREEN (1.0f / 30.0f)
#define SSLR_THIN_DEPTH_PER_WIDTH 1.0f
#define SSLR_THIN_MAX_DEPTH_FOOTPRINTS 6.0f

// SslrTraceParams::stochasticFrom when no pixel draws its ray from its lobe: above every roughness.
#define SSLR_NO_STOCHASTIC_RAYS 2.0f

// Most levels of the min-max depth pyramid above the depth buffer (level l: 2^l-pixel cells).
#define SSLR_HIZ_MAX_LEVELS 8

// Views a context traces in the same dispatches at most (ContextDesc::views): a list entry keeps
// its view in the two bits above a 14-bit coordinate (common/tiles.glsl).
#define SSLR_MAX_VIEWS 4
#ifndef __cplusplus
#ifndef SSLR_VIEWS
#define SSLR_VIEWS 1  // the program's views (Context::Impl::buildPrograms defines it when > 1)
#endif
#endif

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
#define SSLR_UNIT_BLUR_INPUT 3        // blur: the pass's input (resolved, then the scratch image)
#define SSLR_UNIT_BLUR_REFLECTION 4   // ... the reflection (its alpha: the radius)
#define SSLR_UNIT_BLUR_UNBLURRED 5    // ... vertical pass: resolved before it
#define SSLR_UNIT_TEMPORAL_CURRENT 3  // temporal reuse: this frame's resolved (store: the blend)
#define SSLR_UNIT_HISTORY 4           // ... the previous frame's output
#define SSLR_UNIT_HISTORY_KEY 5       // ... its keys
#define SSLR_UNIT_COMPOSITE_RESOLVED 4  // composite: the resolved output
#define SSLR_UNIT_COMPOSITE_FALLBACK 5  // ... the host's fallback specular
// The composite's uniform location of the view it draws (ContextDesc::views > 1: CompositeOptions::view).
#define SSLR_COMPOSITE_VIEW_LOCATION 0
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
#define SSLR_RETRACE_GROUP (SSLR_TILE_SIZE * SSLR_TILE_SIZE)  // pixels per group of the retrace (3_trace.comp's group)
#define SSLR_RETRACE_ROLE_LOCATION 0  // uRetrace of 3_trace.comp and 3_trace_quads.comp (passes/retrace_list.glsl)

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

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_CONSTANTS_H
