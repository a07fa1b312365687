// A GPU frame time predicted from a frame's ray work, on any machine.
#pragma once

#include <optional>

#include "sslr/sslr.hpp"

namespace sslr::host {

// What decides which fit applies: the tracer and the frame's shape.
struct FrameShape {
  Method method = Method::AdaptiveL;
  bool traversal = true;         // AdaptiveL: Settings::traversal.maxSteps > 0 (else adaptive L alone)
  DeviceProfile device = DeviceProfile::Gpu;  // the profile the frame ran (Context::device())
  bool halfResolution = false;
  bool traversalDeferred = false;  // FrameStats::traversalDeferred
  bool oneBodyTraversal = false;   // ContextDesc::oneBodyTraversal (not in the fitted run)
  bool occupancyExit = false;      // ContextDesc::occupancyExit (neither)
};

// The shape of a frame that ran with `settings` on a context of profile `device` (Context::device())
// created with the pass shapes `shapes` (ContextDesc's oneBodyTraversal, occupancyExit).
FrameShape frameShapeOf(const Settings& settings, DeviceProfile device, const ContextDesc& shapes, const FrameStats& stats);

// The frame's time on an NVIDIA H100 (ms, GL_TIME_ELAPSED), predicted per tracer as
// a + b x longest chain + c x SIMT work (RayWork::simt32): the least-squares fit to that GPU's
// times of 15 scenes x 49 configurations at 960x540 (commit 869d7fc; docs/results/gpu-h100.md,
// "The cost model"). Fitted without a scene, it predicted that scene to a median 11% (largest
// 125%: a longest chain of cheap steps). Only for frames shaped as the fitted ones were: the Gpu
// profile, full resolution, the traversal inline in two phases; none otherwise.
std::optional<double> predictedH100FrameMs(const FrameShape& shape, const RayWork& work);

}  // namespace sslr::host
