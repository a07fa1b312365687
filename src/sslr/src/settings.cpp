// Settings: the presets and the validation dispatch() runs (also public: sslr::validate).
#include <cmath>
#include <sstream>

#include "sslr/sslr.hpp"

namespace sslr {

Settings Settings::preset(Preset preset) {
  Settings s;
  switch (preset) {
    case Preset::Low:
      s.maxIterations = 8;  // 6 lost half the long reflections at 960x540 (docs/results.md)
      s.convergenceEps = 0.01f;
      // Adaptive L alone: with 8 iterations it fails often enough that a fallback made the
      // cheapest preset the slowest (measured 1.55x high's time on mirror-room, llvmpipe).
      s.hierarchicalFallback = false;
      s.hierarchicalVerify = false;
      s.blurMaxRadiusPx = 4.0f;
      s.roughnessCutoff = 0.3f;
      break;
    case Preset::Medium:
      // High's tracer with a 96-step cap (same recall on every scene but mirror-walls, -0.5%),
      // a narrower blur and fewer rough pixels traced. Until the traversal ran in two phases
      // medium had the article's 10 iterations and 48 steps: on llvmpipe now slower than high on
      // the open scenes (more pixels fall back) and 0.10-0.14 recall lower on the hard ones.
      s.hierarchicalMaxSteps = 96;
      s.hierarchicalVerify = false;  // adaptive L's hits unchecked: cheaper, below the traversal alone
      s.blurMaxRadiusPx = 6.0f;
      s.roughnessCutoff = 0.4f;
      break;
    case Preset::High:
      break;  // the defaults: adaptive L, every hit verified and every miss retraced by the traversal
    case Preset::Ultra:
      s.maxIterations = 32;
      s.convergenceEps = 0.0005f;
      s.hierarchicalMaxSteps = 256;
      s.blurMaxRadiusPx = 12.0f;
      s.roughnessCutoff = 0.6f;
      break;
  }
  return s;
}

std::string validate(const Settings& s) {
  std::ostringstream why;
  auto finite = [](float v) { return std::isfinite(v); };
  if (s.maxIterations < 1 || s.maxIterations > 256)
    why << "maxIterations = " << s.maxIterations << " (must be 1..256); ";
  if (s.method == Method::AdaptiveL && s.hierarchicalVerify && !s.hierarchicalFallback)
    why << "hierarchicalVerify needs hierarchicalFallback (both run the hierarchical traversal); ";
  if (s.traversalPass != TraversalPass::Auto && s.traversalPass != TraversalPass::Inline &&
      s.traversalPass != TraversalPass::Deferred)
    why << "traversalPass = " << static_cast<int>(s.traversalPass) << " (not a TraversalPass); ";
  if (s.hierarchicalMaxSteps < 1 || s.hierarchicalMaxSteps > 1024)
    why << "hierarchicalMaxSteps = " << s.hierarchicalMaxSteps << " (must be 1..1024); ";
  if (std::isnan(s.hiddenPassageLimitPx) || s.hiddenPassageLimitPx < 0.0f)
    why << "hiddenPassageLimitPx = " << s.hiddenPassageLimitPx << " (must be >= 0; 1e30 = off); ";
  if (!finite(s.objectThickness) || s.objectThickness < 0.0f)
    why << "objectThickness = " << s.objectThickness << " (must be >= 0); ";
  if (!finite(s.convergenceEps) || s.convergenceEps < 0.0f)
    why << "convergenceEps = " << s.convergenceEps << " (must be >= 0); ";
  if (!finite(s.initialLengthScreen) || s.initialLengthScreen <= 0.0f || s.initialLengthScreen > 1.0f)
    why << "initialLengthScreen = " << s.initialLengthScreen << " (must be in (0, 1]); ";
  if (!finite(s.errorK) || s.errorK < 0.0f) why << "errorK = " << s.errorK << " (must be >= 0); ";
  if (!(s.maxDistance > 0.0f)) why << "maxDistance = " << s.maxDistance << " (must be > 0); ";
  if (!finite(s.thicknessRelative) || s.thicknessRelative < 0.0f)
    why << "thicknessRelative = " << s.thicknessRelative << " (must be >= 0); ";
  if (!finite(s.thicknessPixels) || s.thicknessPixels < 0.0f)
    why << "thicknessPixels = " << s.thicknessPixels << " (must be >= 0); ";
  if (s.thicknessRelative == 0.0f && s.thicknessPixels == 0.0f)
    why << "thicknessRelative and thicknessPixels are both 0 (no hit could validate); ";
  if (!finite(s.edgeFade) || s.edgeFade < 0.0f || s.edgeFade > 0.5f)
    why << "edgeFade = " << s.edgeFade << " (must be 0..0.5); ";
  if (!finite(s.cameraFadeStart) || !finite(s.cameraFadeEnd) || s.cameraFadeEnd < s.cameraFadeStart)
    why << "cameraFadeStart/End = " << s.cameraFadeStart << "/" << s.cameraFadeEnd
        << " (must be finite, start <= end); ";
  if (!(s.roughnessCutoff >= 0.0f && s.roughnessCutoff <= 1.0f))
    why << "roughnessCutoff = " << s.roughnessCutoff << " (must be 0..1, a roughness); ";
  if (!finite(s.minReflectance)) why << "minReflectance is not finite; ";
  if (!finite(s.blurMaxRadiusPx) || s.blurMaxRadiusPx < 0.0f || s.blurMaxRadiusPx > 32.0f)
    why << "blurMaxRadiusPx = " << s.blurMaxRadiusPx << " (must be 0..32); ";
  if (!finite(s.blurConeScale) || s.blurConeScale < 0.0f)
    why << "blurConeScale = " << s.blurConeScale << " (must be >= 0); ";
  if (!finite(s.blurDepthSigma) || s.blurDepthSigma <= 0.0f)
    why << "blurDepthSigma = " << s.blurDepthSigma << " (must be > 0); ";
  if (!finite(s.blurNormalPower) || s.blurNormalPower < 0.0f)
    why << "blurNormalPower = " << s.blurNormalPower << " (must be >= 0); ";
  const PositionBufferSettings& pb = s.positionBuffer;
  if (!(pb.maxDistance > 0.0f) || !finite(pb.maxDistance))
    why << "positionBuffer.maxDistance = " << pb.maxDistance << " (must be > 0); ";
  if (!(pb.resolution > 0.0f && pb.resolution <= 1.0f))
    why << "positionBuffer.resolution = " << pb.resolution << " (must be in (0, 1]); ";
  if (pb.steps < 0 || pb.steps > 64) why << "positionBuffer.steps = " << pb.steps << " (must be 0..64); ";
  if (!(pb.thickness > 0.0f) || !finite(pb.thickness))
    why << "positionBuffer.thickness = " << pb.thickness << " (must be > 0); ";
  const DdaSettings& dda = s.dda;
  if (!finite(dda.stride) || dda.stride < 1.0f || dda.stride > 64.0f)
    why << "dda.stride = " << dda.stride << " (must be 1..64 pixels); ";
  if (!finite(dda.thickness) || dda.thickness < 0.0f)
    why << "dda.thickness = " << dda.thickness << " (must be >= 0); ";
  if (!(dda.maxDistance > 0.0f)) why << "dda.maxDistance = " << dda.maxDistance << " (must be > 0); ";
  if (dda.maxSteps < 1 || dda.maxSteps > 16384) why << "dda.maxSteps = " << dda.maxSteps << " (must be 1..16384); ";
  if (!finite(s.ffx.depthBufferThickness) || !(s.ffx.depthBufferThickness > 0.0f))
    why << "ffx.depthBufferThickness = " << s.ffx.depthBufferThickness << " (must be > 0); ";
  if (s.ffx.maxTraversalIntersections < 1 || s.ffx.maxTraversalIntersections > 16384)
    why << "ffx.maxTraversalIntersections = " << s.ffx.maxTraversalIntersections << " (must be 1..16384); ";
  if (s.method != Method::AdaptiveL && s.method != Method::HierarchicalDepth && s.method != Method::PositionBuffer &&
      s.method != Method::ScreenSpaceDDA && s.method != Method::FidelityFxSssr)
    why << "method = " << static_cast<int>(s.method) << " (not a sslr::Method); ";
  if (!finite(s.temporalWeight) || s.temporalWeight < 0.0f || s.temporalWeight > 0.98f)
    why << "temporalWeight = " << s.temporalWeight << " (must be 0..0.98); ";
  if (s.halfResolution && s.method == Method::PositionBuffer)
    why << "halfResolution works with the depth-only methods, not Method::PositionBuffer; ";
  std::string text = why.str();
  if (!text.empty()) text = "sslr: invalid Settings: " + text.substr(0, text.size() - 2);
  return text;
}

}  // namespace sslr
