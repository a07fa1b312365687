// sslr_trace_hiz.h - the hierarchical traversal over the min-max depth pyramid, and the per-pixel
// choice between it and the adaptive-L tracer. Shared by the GPU pass and the CPU tests.
//
// Besides the loaders of sslr_trace.h, the includer defines (for this file and sslr_hit_model.h)
//   vec2 sslrLoadPyramidTexel(int level, ivec2 cell);  // the pyramid (sslr_shared.h): level 0
//                                                      // sslrHiZLevel0Texel, level >= 1 (min, max)
//
// The traversal (in the spirit of Uludag's Hi-Z tracing, GPU Pro 5, and FidelityFX SSSR) runs in
// window space: x, y in pixels and the raw window depth. Both kinds of projection map the view-
// space ray to a straight line there with the depth affine along it (perspective: depth is affine
// in 1/w, as are x and y), so a cell of the pyramid is crossed by one segment whose nearest and
// farthest depth sit at its ends. The depth is multiplied by keySign (-1 for reversed Z) so that a
// larger key is always farther from the camera; the sign flip is exact, reversed-Z keeps its bits.
//
// Per step, at the current level, the cell under the ray is
//   - skipped when the segment lies in front of the nearest depth of the cell, or behind its
//     farthest depth by more than any hit tolerance and the objects' assumed thickness (the ray
//     passes behind what the cell shows: depth buffers have no thickness, this is the thickness
//     test); after a skip the level rises when the ray enters a new parent cell;
//   - else descended into, after moving to where the ray reaches the cell's nearest depth;
//   - at level 0 (a pixel), handed to the hit model (sslr_hit_model.h: sslrJudgePixel), which says
//     whether the ray hit there, goes on, ended inside what the pixel shows (then sslrJudgeInside
//     answers after the walk) or passes behind it.

#ifndef SSLR_TRACE_HIZ_H
#define SSLR_TRACE_HIZ_H

#include "sslr_hit_model.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// The traversal's state between its steps: the ray in window space (x, y in pixels, z the depth
// key; t counts pixels along the major axis) and where the walk stands.
struct SslrWalk {
  vec3 o, d;
  vec3 invD;          // 1 / d: huge but finite on an axis x, y the ray does not move along; z: 0
                      // unless the ray moves away from the camera
  vec2 boundaryStep;  // 1 on an axis the ray moves up, 0 down: the cell boundary it leaves by
  float tEnd;         // the ray is off the screen or out of the depth range [0, 1] from here on
  vec2 sizePx;
  float keySign;      // -1 with reversed depth: keySign x depth grows away from the camera
  float tRay;         // where the ray is
  int level, topLevel;
  int i;              // steps taken
  // Where the ray entered the first pixel of the pixels it has been behind since it was last in
  // front of (or deeper than the slab behind) what the screen shows: the outline it may have
  // crossed onto an object's side (sslrEntryHit, tried once, if the ray ends in the slab).
  float tRun;
  bool inSlab;        // the walk ended inside what pixel slabPx shows, with the verdict `slab`
  ivec2 slabPx;
  SslrVerdict slab;
  // Where the ray's current passage behind what the screen shows (its last pixel or cell) began:
  // tRay there (< 0: the ray is in front now). The hidden guess (sslrWalkGuess, after the walk)
  // shows the colour at the ray's point there, or at the pixel's centre wHiddenPx where a pixel
  // test began the passage (tHiddenPx == tHidden): the walk's loop carries tHidden alone.
  float tHidden;
  float tHiddenPx;
  vec2 wHiddenPx;
  // The pixel sslrWalkToPixel reached: its cell, where the ray leaves it, the ray's nearest and
  // farthest depth keys in it, the cell's nearest key and the pixel's extra depth (level 0's .y).
  vec2 cell;
  float tExit, segNear, segFar, keyNear, extra;
};

// The level after the walk left cell w.cell of level w.level (w.tRay just past its boundary):
// one coarser when the ray entered a new parent cell, else the same (the parent, containing the
// cell, could not have been skipped whole). Cell indices are integer shifts of the pixel,
// floor(x / 2^k) = floor(x) >> k: no division. A position off the screen truncates to the wrong
// cell, but the next step ends the walk there whatever the level.
SSLR_FN int sslrHiZNextLevel(SslrWalk w) {
  if (w.level >= w.topLevel) return w.topLevel;
  ivec2 parentNext = ivec2(vec2(w.o.x, w.o.y) + vec2(w.d.x, w.d.y) * w.tRay) >> (w.level + 1);
  ivec2 parentNow = ivec2(w.cell) >> 1;
  return (parentNext.x != parentNow.x || parentNext.y != parentNow.y) ? w.level + 1 : w.level;
}

// How a step ended: at a pixel to test, with the walk over (out of steps, or inside a slab), or
// with the hit record answered (a hit, off the screen, hidden).
#define SSLR_WALK_PIXEL 0
#define SSLR_WALK_ENDED 1
#define SSLR_WALK_ANSWERED 2
#define SSLR_WALK_ON 3  // sslrWalkStep: a cell skipped or descended into, the walk goes on

// The ray from vsP along vsR in window space, just out of its own pixel. False for a ray along the
// view direction: it stays in its own pixel, and nothing on screen can answer it.
SSLR_FN bool sslrWalkBegin(SslrProjection p, SslrSurface s, SslrTraceParams t, vec3 vsP, vec3 vsR,
                           SSLR_OUT(SslrWalk) w) {
  w.sizePx = vec2(s.width, s.height);
  w.keySign = sslrReversedZ(s) ? -1.0f : 1.0f;
  w.invD = vec3(0.0f);
  w.boundaryStep = vec2(0.0f);
  w.tEnd = 0.0f;
  w.tRay = 0.0f;
  w.level = 0;
  w.topLevel = t.hizLevels;
  w.i = 0;
  w.tRun = -1.0f;
  w.inSlab = false;
  w.slabPx = ivec2(0);
  w.slab = sslrNoVerdict();
  w.tHidden = -1.0f;
  w.tHiddenPx = -1.0f;
  w.wHiddenPx = vec2(0.0f);
  w.cell = vec2(0.0f);
  w.tExit = 0.0f;
  w.segNear = 0.0f;
  w.segFar = 0.0f;
  w.keyNear = 0.0f;
  w.extra = 0.0f;
  w.o = sslrWindowFromView(p, w.sizePx, w.keySign, vsP);
  w.d = sslrWindowDirection(p, s, w.keySign, vsP, vsR, w.o);
  float majorPx = max(abs(w.d.x), abs(w.d.y));
  if (!(majorPx > 1e-3f)) return false;
  w.d /= majorPx;
  // An axis the ray barely moves along is one it does not move along: its boundary is then never
  // the one the ray leaves by (a tiny negative d with the up boundary's huge 1 / d would be).
  if (!(abs(w.d.x) > 1e-12f)) w.d.x = 0.0f;
  if (!(abs(w.d.y) > 1e-12f)) w.d.y = 0.0f;
  w.invD = vec3(w.d.x != 0.0f ? 1.0f / w.d.x : 1e12f, w.d.y != 0.0f ? 1.0f / w.d.y : 1e12f,
                w.d.z > 0.0f ? 1.0f / w.d.z : 0.0f);
  w.boundaryStep = vec2(w.d.x >= 0.0f ? 1.0f : 0.0f, w.d.y >= 0.0f ? 1.0f : 0.0f);
  // The screen edge the ray heads for, and the end of the key range [0, 1] x keySign it heads
  // for; a nudge short of them, so that no rounding of o + d t reaches past the last pixel.
  vec2 tEdge = (w.boundaryStep * w.sizePx - vec2(w.o.x, w.o.y)) * vec2(w.invD.x, w.invD.y);
  float keyEnd = w.d.z > 0.0f ? max(w.keySign, 0.0f) : min(w.keySign, 0.0f);
  float tDepth = w.d.z != 0.0f ? (keyEnd - w.o.z) / w.d.z : 1e30f;
  w.tEnd = min(min(tEdge.x, tEdge.y), tDepth) - SSLR_HIZ_NUDGE;
  // Leave the reflecting pixel first.
  w.cell = floor(vec2(w.o.x, w.o.y));
  vec2 tBound0 = ((w.cell + w.boundaryStep) - vec2(w.o.x, w.o.y)) * vec2(w.invD.x, w.invD.y);
  w.tExit = min(tBound0.x, tBound0.y);
  w.tRay = w.tExit + SSLR_HIZ_NUDGE;
  // Level 0 is read only inside a 2x2 quad whose level-1 cell holds geometry (classification
  // writes no level-0 texels under a cell of background alone): the walk enters a new quad at
  // level 1, here and after each pixel it tested, as after a skip.
  w.level = sslrHiZNextLevel(w);
  return true;
}

// The ray is behind what the screen shows: a hidden passage begins here (true) unless one goes on.
SSLR_FN bool sslrWalkGoesHidden(SSLR_INOUT(SslrWalk) w) {
  if (w.tHidden >= 0.0f) return false;
  w.tHidden = w.tRay;
  return true;
}

// Where the hidden guess (Settings::traversal.hiddenGuess) reads its colour, as the hit record
// holds it: the uv where the current hidden passage began and the ray's length there (LGuess 0:
// the ray ended in front, or no guess).
SSLR_FN SslrHit sslrWalkGuess(SslrProjection p, SslrTraceParams t, SslrWalk w, vec3 vsP, vec3 vsR, SslrHit hit) {
  if (!(t.hiddenGuess > 0.0f) || w.tHidden < 0.0f) return hit;
  vec2 wPoint = w.tHidden == w.tHiddenPx ? w.wHiddenPx : vec2(w.o.x, w.o.y) + vec2(w.d.x, w.d.y) * w.tHidden;
  hit.uvGuess = wPoint / w.sizePx;
  hit.LGuess = sslrRayLengthAt(p, w.sizePx, w.keySign, w.o, w.d, w.tHidden, vsP, vsR);
  return hit;
}

// One step of the walk over pyramid cells: a cell skipped or descended into (SSLR_WALK_ON), or a
// pixel the ray does not pass in front of or far behind (SSLR_WALK_PIXEL: w.cell and the segment
// fields are that pixel's).
SSLR_FN int sslrWalkStep(SslrProjection p, SslrSurface s, SslrTraceParams t, SSLR_INOUT(SslrWalk) w,
                         SSLR_INOUT(SslrHit) hit) {
  // Off the screen, or behind the near plane or beyond the far one (NaN too).
  if (!(w.tRay < w.tEnd)) {
    hit.status = SSLR_STATUS_OFF_SCREEN;
    return SSLR_WALK_ANSWERED;
  }
  vec3 pos = w.o + w.d * w.tRay;
  float cellSize = float(1 << w.level);
  w.cell = vec2(ivec2(pos.x, pos.y) >> w.level);  // pos >= 0: the integer part is its floor
  vec2 texel = sslrLoadPyramidTexel(w.level, ivec2(w.cell));
  vec2 minMax = sslrHiZMinMax(w.level, texel);
  w.keyNear = min(w.keySign * minMax.x, w.keySign * minMax.y);
  float keyFar = max(w.keySign * minMax.x, w.keySign * minMax.y);
  vec2 tBound = ((w.cell + w.boundaryStep) * cellSize - vec2(w.o.x, w.o.y)) * vec2(w.invD.x, w.invD.y);
  w.tExit = min(tBound.x, tBound.y);
  float keyExit = w.o.z + w.d.z * w.tExit;
  w.segNear = min(pos.z, keyExit);
  w.segFar = max(pos.z, keyExit);
#ifdef SSLR_HIZ_DEBUG_HOOK
  SSLR_HIZ_DEBUG_HOOK(w.i, w.level, w.cell, w.tRay, w.tExit, pos, keyExit, w.keyNear, keyFar);
#endif
  // In front of everything the cell shows, or a coarse cell of background alone (its nearest key
  // is the clear value's: nothing in it can stop a ray, and classification writes no level-0
  // texels under such a level-1 cell): skip it. A background pixel that a ray at the far plane
  // reaches goes to the hit model, which leaves a hidden passage going on (the guess pays there).
  bool skip = w.segFar < w.keyNear || (w.level > 0 && w.keyNear >= sslrHiZBackgroundKey(s));
  // A pixel on a curved surface reaches deeper than the slab (coarse cells' far keys hold it).
  // With a back-face depth, the pixel's measured extra depth over the slab (either sign).
  w.extra = w.level == 0 && (sslrCurvedSolids(t) || sslrBackDepth(s)) ? texel.y : 0.0f;
  bool behindSkip = !skip && sslrPassesBehindCell(p, s, t, w.keySign, w.segNear, keyFar, w.extra);
  if (behindSkip) {
    sslrWalkGoesHidden(w);
  } else if (skip) {
    w.tHidden = -1.0f;  // in front again (or over background)
  }
  if (skip || behindSkip) {
    // Look coarser only on entering a new parent cell: the parent of this one was (or will
    // be) looked at already, and going up into it again costs a step just to come back down.
    w.tRun = -1.0f;
    w.tRay = w.tExit + SSLR_HIZ_NUDGE;
    w.level = sslrHiZNextLevel(w);
    return SSLR_WALK_ON;
  }
  if (w.level > 0) {
    // Move to where the ray reaches the cell's nearest depth (nothing in the cell is nearer),
    // then look finer.
    if (w.d.z > 0.0f && pos.z < w.keyNear) w.tRay = max(w.tRay, (w.keyNear - w.o.z) * w.invD.z);
    --w.level;
    return SSLR_WALK_ON;
  }
  return SSLR_WALK_PIXEL;
}

// The walk until the ray reaches a pixel to test (SSLR_WALK_PIXEL), runs out of steps or is
// answered.
SSLR_FN int sslrWalkToPixel(SslrProjection p, SslrSurface s, SslrTraceParams t, SSLR_INOUT(SslrWalk) w,
                            SSLR_INOUT(SslrHit) hit) {
  for (; w.i < t.maxSteps; ++w.i) {
    int step = sslrWalkStep(p, s, t, w, hit);
    if (step != SSLR_WALK_ON) return step;
  }
  return SSLR_WALK_ENDED;
}

// The test of the pixel the walk reached (level 0): the hit model's verdict (sslrJudgePixel)
// applied to the walk: a hit (SSLR_WALK_ANSWERED), the ray inside what the pixel shows
// (SSLR_WALK_ENDED, w.inSlab), or on past it (SSLR_WALK_PIXEL: walk on).
SSLR_FN int sslrTestPixel(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP, vec3 vsR,
                          SSLR_INOUT(SslrWalk) w, SSLR_INOUT(SslrHit) hit) {
  SslrCrossing c;
  c.px = ivec2(w.cell);
  c.depth = w.keySign * w.keyNear;  // level 0: (depth, depth)
  c.segNear = w.segNear;
  c.segFar = w.segFar;
  c.keySign = w.keySign;
  c.extra = w.extra;
  c.hidden = w.tHidden >= 0.0f;
  SslrVerdict v = sslrJudgePixel(p, s, t, pxOrigin, vsP, vsR, c);
  if (v.kind == SSLR_VERDICT_HIT) {
    if (!(v.L > t.maxDistance)) hit = sslrFinishHit(p, hit, vsP, vsR, v.L, v.valid);
    return SSLR_WALK_ANSWERED;
  }
  // The run of pixels the ray is behind (not deeper than their solids) goes on from where it began.
  if (v.kind == SSLR_VERDICT_NEAR || v.kind == SSLR_VERDICT_INSIDE) {
    if (w.tRun < 0.0f) w.tRun = w.tRay;
  } else {
    w.tRun = -1.0f;
  }
  if (v.kind == SSLR_VERDICT_INSIDE) {
    w.inSlab = true;
    w.slab = v;
    w.slabPx = c.px;
    return SSLR_WALK_ENDED;
  }
  if (v.kind == SSLR_VERDICT_IN_FRONT) w.tHidden = -1.0f;
  // Passed behind the pixel: a hidden passage begins at its centre, unless one goes on.
  if (v.kind == SSLR_VERDICT_BEHIND && sslrWalkGoesHidden(w)) {
    w.tHiddenPx = w.tRay;
    w.wHiddenPx = vec2(c.px) + 0.5f;
  }
  w.tRay = w.tExit + SSLR_HIZ_NUDGE;
  w.level = sslrHiZNextLevel(w);
  return SSLR_WALK_PIXEL;
}

#ifdef SSLR_HIZ_OCCUPANCY_EXIT
// ContextDesc::occupancyExit (GLSL only, GL_ARB_shader_ballot): the lanes of this invocation's
// subgroup that are here.
uint sslrLanesHere() {
  uvec2 lanes = unpackUint2x32(ballotARB(true));
  return uint(bitCount(lanes.x) + bitCount(lanes.y));
}
#endif

SSLR_FN SslrHit sslrTraceHierarchical(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin,
                                      vec3 vsP, vec3 vsR) {
  SslrHit hit = sslrNoHit(SSLR_STATUS_MISS);
  hit.hierarchical = 1;
  SslrWalk w;
  if (!sslrWalkBegin(p, s, t, vsP, vsR, w)) return hit;
  // Two phases per pixel the ray reaches: the walk (skip, descend) over cells until the ray
  // reaches a pixel it does not pass in front of or far behind, then that pixel's test. In SIMD
  // lanes that run in step (CPU rasterizers run every instruction of a loop body under lane
  // masks) the test then runs once for the lanes' pixels together instead of in every step.
  // SSLR_HIZ_ONE_BODY (ContextDesc::oneBodyTraversal) runs the same steps in one loop body
  // instead: a lane tests its pixel as soon as it reaches one, without waiting for the others.
  // SSLR_HIZ_OCCUPANCY_EXIT stops the walk of the lanes of a subgroup still walking once they are
  // at most an eighth of those that began it (FidelityFX SSSR's 4 of a full 32-lane wave; a GPU
  // group costs its slowest lane): as at the step cap, adaptive L resumes there.
  bool answered = false;
  bool stoppedShort = false;
#ifdef SSLR_HIZ_OCCUPANCY_EXIT
  uint lanesStarted = sslrLanesHere();
#endif
  while (w.i < t.maxSteps) {
#ifdef SSLR_HIZ_OCCUPANCY_EXIT
    uint lanes = sslrLanesHere();
    if (8u * lanes <= lanesStarted) {
      stoppedShort = true;
      break;
    }
#endif
#ifdef SSLR_HIZ_ONE_BODY
    int walked = sslrWalkStep(p, s, t, w, hit);
    if (walked == SSLR_WALK_ON) {
      ++w.i;
      continue;
    }
#else
    int walked = sslrWalkToPixel(p, s, t, w, hit);
#endif
    answered = walked == SSLR_WALK_ANSWERED;
    if (walked != SSLR_WALK_PIXEL) break;
    ++w.i;  // the test is the step that reached the pixel
    int tested = sslrTestPixel(p, s, t, pxOrigin, vsP, vsR, w, hit);
    answered = tested == SSLR_WALK_ANSWERED;
    if (tested != SSLR_WALK_PIXEL) break;
  }
  hit.iterations = w.i;  // a step that found the ray off the screen counts none
  hit = sslrWalkGuess(p, t, w, vsP, vsR, hit);
  if (answered) return hit;
  // Out of steps (or stopped short) in front of what the screen shows: adaptive L may resume there
  // (sslrProbeAfterWalk), the segment before it walked.
  if ((w.i >= t.maxSteps || stoppedShort) && !w.inSlab && w.tHidden < 0.0f)
    hit.LResume = sslrRayLengthAt(p, w.sizePx, w.keySign, w.o, w.d, w.tRay, vsP, vsR);
  if (!w.inSlab) return hit;
  // Ended inside what a pixel shows: the hit model answers from where the ray went in. A deferred
  // first stage leaves that to the second stage, which walks the ray again: few rays end inside,
  // and a SIMD CPU runs a program's every branch for every group of lanes, taken or not.
  hit.endedInside = 1;
#ifdef SSLR_DEFER_TRAVERSAL
  return hit;
#else
  SslrInside entered;
  entered.wEntry = w.o + w.d * w.tRun;
  entered.d = w.d;
  entered.LEntry = sslrRayLengthAt(p, w.sizePx, w.keySign, w.o, w.d, w.tRun, vsP, vsR);
  entered.px = w.slabPx;
  entered.verdict = w.slab;
  return sslrJudgeInside(p, s, t, vsP, vsR, hit, entered);
#endif
}

// The depth-only tracer of a pixel (t.hizMode): adaptive L alone (SSLR_HIZ_OFF), the traversal
// alone (SSLR_HIZ_ONLY), or both (SSLR_HIZ_TRAVERSAL_FIRST, the default): the traversal on every
// ray, adaptive L only where the traversal has no confident hit. The traversal walks every cell,
// so its hit is the first crossing; adaptive L converges on *a* crossing, not always the first
// (its probes can step over a thin occluder onto the surface behind), so it only answers rays the
// traversal left without one (docs/results/ray-work.md).
//
// Two stages, so that a pass can run the first alone and leave the second (with traversal first:
// adaptive L; traversal alone: the traversal) to a pass of its own (ContextDesc::traversalPass):
// sslrTraceFirstStage answers the pixel or says it needs the second.

// Rays that come back towards the camera, or run within ~17 degrees of the image plane, are where
// adaptive L jumps over what stands between (its probes see the front of the occluders, not the
// ray): the traversal's answer is final for them.
SSLR_FN bool sslrTraversalOnly(SslrProjection p, vec3 vsP, vec3 vsR) {
  return dot(vsR, -sslrViewDirection(p, vsP)) > -0.3f;
}

SSLR_FN bool sslrConfidentHit(SslrHit h) { return h.status == SSLR_STATUS_HIT && h.confidence >= 0.5f; }

// SSLR_HIZ_TRAVERSAL_FIRST: the traversal's hit where it has a confident one; where it stopped on
// the screen without one (inside an assumed slab, which adaptive L's probes carry past; at its
// step cap; a crossing it refused), adaptive L's, if confident and not beyond where the traversal
// found the ray hidden. The traversal's hit is the first crossing it walked to; adaptive L only
// fills a missing one. The two stages below: the traversal (`walked`), then adaptive L where
// sslrWalkedNeedsProbes says so.

// A ray the traversal walked off the screen (or out of the depth range) crossed nothing it could
// take: adaptive L there finds little and spends its whole iteration budget (design-notes.md,
// "Traversal first"). A ray that ran out of steps in front of what the screen shows gets adaptive
// L from there, whatever its direction: the segment before is walked, so its probes cannot jump
// over what stands there (the step cap's answer; results/ray-work.md).
SSLR_FN bool sslrWalkedNeedsProbes(SslrProjection p, vec3 vsP, vec3 vsR, SslrHit walked) {
  if (sslrConfidentHit(walked)) return false;
  return walked.LResume > 0.0f || (walked.status != SSLR_STATUS_OFF_SCREEN && !sslrTraversalOnly(p, vsP, vsR));
}

// The answer for a ray the traversal left (`walked`): adaptive L's (from walked.LResume, where the
// traversal ran out of steps), or the traversal's. hierarchical = 2 says both ran (the share
// TraversalPass::Auto follows).
SSLR_FN SslrHit sslrProbeAfterWalk(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                   vec3 vsR, SslrHit walked) {
  SslrHit probed = sslrTraceAdaptiveLFrom(p, s, t, pxOrigin, vsP, vsR, walked.LResume);
  bool useProbed = sslrConfidentHit(probed) ||
                   (probed.status == SSLR_STATUS_HIT && !(walked.status == SSLR_STATUS_HIT &&
                                                          walked.confidence >= probed.confidence));
  // Known hidden from walked.L on (a measured solid): a hit beyond that (by 3%: the same surface
  // found twice differs by less) lies behind what hid the ray.
  if (walked.status == SSLR_STATUS_HIDDEN && walked.L < 0.97f * probed.L) useProbed = false;
  SslrHit answer = useProbed ? probed : walked;
  // Where it found nothing beyond an assumed slab, the slab's colour as a guess (sslrSlabGuess).
  if (answer.status != SSLR_STATUS_HIT) answer.LSlab = walked.LSlab;
  answer.endedInside = walked.endedInside;
  answer.iterations = walked.iterations + probed.iterations;
  answer.hierarchical = 2;
  return answer;
}

// Whether the second stage ran for this answer, or would have in a pass of its own (the pixels a
// deferred pass lists: those it probes and those whose walk ended inside what a pixel shows).
SSLR_FN bool sslrRanSecondStage(SslrTraceParams t, SslrHit h) {
  return sslrHiZMode(t) == SSLR_HIZ_TRAVERSAL_FIRST ? h.hierarchical == 2 || h.endedInside != 0
                                                    : h.hierarchical != 0;
}

// The first stage's answer (traversal first: the traversal's; adaptive L alone: adaptive L's);
// needsTraversal: the pixel's answer is sslrTraceSecondStage's instead (a deferred first stage's:
// the whole tracer's, run again by the retrace).
SSLR_FN SslrHit sslrTraceFirstStage(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                    vec3 vsR, SSLR_OUT(bool) needsTraversal) {
  needsTraversal = sslrHiZMode(t) != SSLR_HIZ_OFF;
#if SSLR_HIZ_MODE_MAY_BE(SSLR_HIZ_TRAVERSAL_FIRST)
  if (sslrHiZMode(t) == SSLR_HIZ_TRAVERSAL_FIRST) {  // the traversal first; the second stage probes
    SslrHit walked = sslrTraceHierarchical(p, s, t, pxOrigin, vsP, vsR);
#ifdef SSLR_DEFER_TRAVERSAL
    if (walked.endedInside != 0) return walked;  // not answered here (sslrTraceHierarchical)
#endif
    needsTraversal = sslrWalkedNeedsProbes(p, vsP, vsR, walked);
    return needsTraversal ? walked : sslrGuess(p, t, vsP, vsR, walked);
  }
#endif
  if (needsTraversal) return sslrNoHit(SSLR_STATUS_MISS);
#if SSLR_HIZ_MODE_MAY_BE(SSLR_HIZ_OFF)
  // Adaptive L alone: its guess shows where its probes went behind (LGuess), if in front of the camera.
  SslrHit alone = sslrTraceAdaptiveL(p, s, t, pxOrigin, vsP, vsR);
  vec3 vsGuess = vsP + vsR * alone.LGuess;
  if (alone.LGuess > 0.0f && sslrClipW(p, vsGuess) > 0.0f) {
    vec3 ndcGuess = sslrNdcFromView(p, vsGuess);
    alone.uvGuess = sslrUvFromNdc(vec2(ndcGuess.x, ndcGuess.y));
  } else {
    alone.LGuess = 0.0f;
  }
  return sslrHiddenGuess(t, alone);
#else
  return sslrNoHit(SSLR_STATUS_MISS);  // (not reached: the mode is compiled in)
#endif
}

// The second stage (traversal first: adaptive L after the walk; the traversal alone: the walk),
// given the first stage's answer `first` for a pixel that needs it.
SSLR_FN SslrHit sslrTraceSecondStage(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                     vec3 vsR, SslrHit first) {
#if SSLR_HIZ_MODE_MAY_BE(SSLR_HIZ_TRAVERSAL_FIRST)
  if (sslrHiZMode(t) == SSLR_HIZ_TRAVERSAL_FIRST)
    return sslrGuess(p, t, vsP, vsR, sslrProbeAfterWalk(p, s, t, pxOrigin, vsP, vsR, first));
#endif
#if SSLR_HIZ_MODE_MAY_BE(SSLR_HIZ_ONLY)
  return sslrHiddenGuess(t, sslrTraceHierarchical(p, s, t, pxOrigin, vsP, vsR));
#else
  return first;  // (not reached: the mode is compiled in)
#endif
}

SSLR_FN SslrHit sslrTraceDepthOnly(SslrProjection p, SslrSurface s, SslrTraceParams t, ivec2 pxOrigin, vec3 vsP,
                                   vec3 vsR) {
  bool needsTraversal;
  SslrHit first = sslrTraceFirstStage(p, s, t, pxOrigin, vsP, vsR, needsTraversal);
  return needsTraversal ? sslrTraceSecondStage(p, s, t, pxOrigin, vsP, vsR, first) : first;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_TRACE_HIZ_H
