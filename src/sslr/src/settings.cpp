// Settings: the presets and the validation dispatch() runs (also public: sslr::validate).
#include <cmath>
#include <sstream>

#include "sslr/sslr.hpp"

namespace sslr {

Settings Settings::preset(Preset preset) {
  Settings s;
  switch (preset) {
    case Preset::Low:
      // Adaptive L alone: with few iterations it fails often enough that a fallback would make
      // the cheapest preset the slowest. From the surface it needs a longer first step than after
      // the walk (0.09 of the screen height), and 12 iterations, not 8, once nothing fades its
      // long answers out (docs/results.md, "Presets").
      s.adaptiveL.maxIterations = 12;
      s.adaptiveL.convergenceEps = 0.01f;
      s.adaptiveL.initialLengthScreen = 0.09f;
      s.traversal.maxSteps = 0;
      s.fades.errorK = 0.0f;
      s.fades.screenEdge = 0.0075f;
      s.blur.maxRadiusPx = 4.0f;
      s.selection.roughnessCutoff = 0.3f;
      break;
    case Preset::Medium:
      // High's tracer with a 24-step cap (adaptive L resumes where the walk stops), a narrower
      // blur and fewer rough pixels traced. Low, medium and ultra sit on the measured front of
      // time against image error, which the fades only raise: no error fade, a narrow border fade.
      // High keeps the article's look (docs/results.md, "Presets").
      s.traversal.maxSteps = 24;
      s.fades.errorK = 0.0f;
      s.fades.screenEdge = 0.0075f;
      s.blur.maxRadiusPx = 6.0f;
      s.selection.roughnessCutoff = 0.4f;
      break;
    case Preset::High:
      break;  // the defaults: the traversal first, adaptive L where it has no hit
    case Preset::Ultra:
      // High's tracer (256 steps and 32 iterations found nothing more: results.md, "Presets")
      // without the fades, as low and medium: no error fade, and the screen border's fade a
      // quarter of high's. A wider blur; rougher pixels traced.
      s.fades.errorK = 0.0f;
      s.fades.screenEdge = 0.0075f;
      s.blur.maxRadiusPx = 12.0f;
      s.selection.roughnessCutoff = 0.6f;
      break;
  }
  return s;
}

namespace {

// Each group of Settings' checks appends "field = value (must be ...); " for what it finds wrong.
bool finite(float v) { return std::isfinite(v); }

// What steers the trace: adaptive L, the traversal, the hit tolerance.
void checkTracer(const Settings& s, std::ostringstream& why) {
  if (s.adaptiveL.maxIterations < 1 || s.adaptiveL.maxIterations > 256)
    why << "adaptiveL.maxIterations = " << s.adaptiveL.maxIterations << " (must be 1..256); ";
  const int minSteps = s.method == Method::HierarchicalDepth ? 1 : 0;  // 0: adaptive L alone
  if (s.traversal.maxSteps < minSteps || s.traversal.maxSteps > 1024)
    why << "traversal.maxSteps = " << s.traversal.maxSteps << " (must be " << minSteps << "..1024"
        << (minSteps == 1 ? " for Method::HierarchicalDepth" : "") << "); ";
  if (!(s.traversal.hiddenGuess >= 0.0f && s.traversal.hiddenGuess <= 1.0f))
    why << "traversal.hiddenGuess = " << s.traversal.hiddenGuess << " (must be 0..1); ";
  if (!finite(s.traversal.objectDepthRelative) || s.traversal.objectDepthRelative < 0.0f)
    why << "traversal.objectDepthRelative = " << s.traversal.objectDepthRelative << " (must be >= 0); ";
  if (!finite(s.adaptiveL.convergenceEps) || s.adaptiveL.convergenceEps < 0.0f)
    why << "adaptiveL.convergenceEps = " << s.adaptiveL.convergenceEps << " (must be >= 0); ";
  if (!finite(s.adaptiveL.initialLengthScreen) || s.adaptiveL.initialLengthScreen <= 0.0f || s.adaptiveL.initialLengthScreen > 1.0f)
    why << "adaptiveL.initialLengthScreen = " << s.adaptiveL.initialLengthScreen << " (must be in (0, 1]); ";
}

// What weighs, blurs and reuses the hits: fades, selection, blur, output, glossy, temporal.
void checkShading(const Settings& s, std::ostringstream& why) {
  if (!finite(s.fades.errorK) || s.fades.errorK < 0.0f) why << "fades.errorK = " << s.fades.errorK << " (must be >= 0); ";
  if (!(s.fades.maxDistance > 0.0f)) why << "fades.maxDistance = " << s.fades.maxDistance << " (must be > 0); ";
  if (!finite(s.fades.screenEdge) || s.fades.screenEdge < 0.0f || s.fades.screenEdge > 0.5f)
    why << "fades.screenEdge = " << s.fades.screenEdge << " (must be 0..0.5); ";
  if (!finite(s.fades.cameraStart) || !finite(s.fades.cameraEnd) || s.fades.cameraEnd < s.fades.cameraStart)
    why << "fades.cameraStart/cameraEnd = " << s.fades.cameraStart << "/" << s.fades.cameraEnd
        << " (must be finite, start <= end); ";
  if (!(s.selection.roughnessCutoff >= 0.0f && s.selection.roughnessCutoff <= 1.0f))
    why << "selection.roughnessCutoff = " << s.selection.roughnessCutoff << " (must be 0..1, a roughness); ";
  if (!finite(s.selection.minReflectance)) why << "selection.minReflectance is not finite; ";
  if (!finite(s.blur.maxRadiusPx) || s.blur.maxRadiusPx < 0.0f || s.blur.maxRadiusPx > 32.0f)
    why << "blur.maxRadiusPx = " << s.blur.maxRadiusPx << " (must be 0..32); ";
  if (!finite(s.blur.coneScale) || s.blur.coneScale < 0.0f)
    why << "blur.coneScale = " << s.blur.coneScale << " (must be >= 0); ";
  if (!finite(s.blur.depthSigma) || s.blur.depthSigma <= 0.0f)
    why << "blur.depthSigma = " << s.blur.depthSigma << " (must be > 0); ";
  if (!finite(s.blur.normalPower) || s.blur.normalPower < 0.0f)
    why << "blur.normalPower = " << s.blur.normalPower << " (must be >= 0); ";
  if (!finite(s.radianceClamp.maxLuminance) || s.radianceClamp.maxLuminance < 0.0f)
    why << "radianceClamp.maxLuminance = " << s.radianceClamp.maxLuminance << " (must be >= 0; 0 = off); ";
  if (!finite(s.temporal.historyWeight) || s.temporal.historyWeight < 0.0f || s.temporal.historyWeight > 0.98f)
    why << "temporal.historyWeight = " << s.temporal.historyWeight << " (must be 0..0.98); ";
  if (s.fresnel != FresnelMode::Classic && s.fresnel != FresnelMode::Schlick)
    why << "fresnel = " << static_cast<int>(s.fresnel) << " (not a sslr::FresnelMode); ";
  if (s.output != OutputMode::Weighted && s.output != OutputMode::Radiance)
    why << "output = " << static_cast<int>(s.output) << " (not a sslr::OutputMode); ";
  if (s.glossy.mode != GlossyMode::ConeBlur && s.glossy.mode != GlossyMode::Stochastic)
    why << "glossy.mode = " << static_cast<int>(s.glossy.mode) << " (not a sslr::GlossyMode); ";
  if (!(s.glossy.stochasticFrom >= 0.0f && s.glossy.stochasticFrom <= 1.0f))
    why << "glossy.stochasticFrom = " << s.glossy.stochasticFrom << " (must be 0..1, a roughness); ";
}

// The method and the comparison methods' parameters.
void checkComparisons(const Settings& s, std::ostringstream& why) {
  const PositionBufferSettings& pb = s.positionBuffer;
  if (!(pb.maxDistance > 0.0f) || !finite(pb.maxDistance))
    why << "positionBuffer.maxDistance = " << pb.maxDistance << " (must be > 0); ";
  if (!(pb.resolution > 0.0f && pb.resolution <= 1.0f))
    why << "positionBuffer.resolution = " << pb.resolution << " (must be in (0, 1]); ";
  if (pb.steps < 0 || pb.steps > 64) why << "positionBuffer.steps = " << pb.steps << " (must be 0..64); ";
  if (!(pb.hitTolerance > 0.0f) || !finite(pb.hitTolerance))
    why << "positionBuffer.hitTolerance = " << pb.hitTolerance << " (must be > 0); ";
  const DdaSettings& dda = s.dda;
  if (!finite(dda.stride) || dda.stride < 1.0f || dda.stride > 64.0f)
    why << "dda.stride = " << dda.stride << " (must be 1..64 pixels); ";
  if (!finite(dda.objectDepth) || dda.objectDepth < 0.0f)
    why << "dda.objectDepth = " << dda.objectDepth << " (must be >= 0); ";
  if (!(dda.maxDistance > 0.0f)) why << "dda.maxDistance = " << dda.maxDistance << " (must be > 0); ";
  if (dda.maxSteps < 1 || dda.maxSteps > 16384) why << "dda.maxSteps = " << dda.maxSteps << " (must be 1..16384); ";
  if (!finite(s.ffx.depthBufferThickness) || !(s.ffx.depthBufferThickness > 0.0f))
    why << "ffx.depthBufferThickness = " << s.ffx.depthBufferThickness << " (must be > 0); ";
  if (s.ffx.maxTraversalIntersections < 1 || s.ffx.maxTraversalIntersections > 16384)
    why << "ffx.maxTraversalIntersections = " << s.ffx.maxTraversalIntersections << " (must be 1..16384); ";
  if (s.method != Method::AdaptiveL && s.method != Method::HierarchicalDepth && s.method != Method::PositionBuffer &&
      s.method != Method::ScreenSpaceDDA && s.method != Method::FidelityFxSssr)
    why << "method = " << static_cast<int>(s.method) << " (not a sslr::Method); ";
}

}  // namespace

std::string validate(const Settings& s) {
  std::ostringstream why;
  checkTracer(s, why);
  checkShading(s, why);
  checkComparisons(s, why);
  // Settings that do not combine.
  if (s.halfResolution && s.method == Method::PositionBuffer)
    why << "halfResolution works with the depth-only methods, not Method::PositionBuffer; ";
  if (s.temporal.outputConfidence && !s.temporal.enabled)
    why << "temporal.outputConfidence needs temporal.enabled (it is the temporal blend's); ";
  if (s.glossy.mode == GlossyMode::Stochastic && s.halfResolution)
    why << "glossy.mode Stochastic does not work with halfResolution (a quad's pixels reuse its mirror ray); ";
  std::string text = why.str();
  if (!text.empty()) text = "sslr: invalid Settings: " + text.substr(0, text.size() - 2);
  return text;
}

}  // namespace sslr
