#include "sslr_host/cost_model.hpp"

namespace sslr::host {

namespace {

struct Fit {
  double a, perChainStep, perSimt32Step;  // ms, ms a step of the longest chain, ms a 32-lane group step
};

// docs/results/gpu-h100.md, "The cost model" (coefficients rounded as printed there).
constexpr Fit kTraversal{0.09236, 0.00095, 0.06102e-5};        // fitted to the default, hiz and 0.5's orders
constexpr Fit kAdaptiveLAlone{0.04008, 0.00053, 0.03469e-5};
constexpr Fit kFfx{-0.00051, 0.00073, 0.02354e-5};
constexpr Fit kDda{0.05908, 0.00017, 0.00724e-5};
constexpr Fit kPositionBuffer{0.0483, 0.00017, 0.0051e-5};

const Fit& fitFor(const FrameShape& shape) {
  switch (shape.method) {
    case Method::AdaptiveL: return shape.traversal ? kTraversal : kAdaptiveLAlone;
    case Method::HierarchicalDepth: return kTraversal;
    case Method::FidelityFxSssr: return kFfx;
    case Method::ScreenSpaceDDA: return kDda;
    case Method::PositionBuffer: return kPositionBuffer;
  }
  return kTraversal;
}

}  // namespace

FrameShape frameShapeOf(const Settings& settings, DeviceProfile device, const ContextDesc& shapes, const FrameStats& stats) {
  return {settings.method,         settings.traversal.maxSteps > 0, device,
          settings.halfResolution, stats.traversalDeferred,         shapes.oneBodyTraversal,
          shapes.occupancyExit};
}

std::optional<double> predictedH100FrameMs(const FrameShape& shape, const RayWork& work) {
  if (shape.device != DeviceProfile::Gpu || shape.halfResolution || shape.traversalDeferred || shape.oneBodyTraversal ||
      shape.occupancyExit)
    return std::nullopt;
  const Fit& fit = fitFor(shape);
  return fit.a + fit.perChainStep * double(work.longestChain) + fit.perSimt32Step * double(work.simt32);
}

}  // namespace sslr::host
