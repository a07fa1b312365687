// frameConstants: FrameInputs + Settings -> the std140 block the passes read (sslr_shared.h).
#include "sslr/reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "projection.hpp"

namespace sslr {

namespace {

// FrameInputs' enumerations (from a host's cast or memory, an unknown value would be read as one
// of the others) and its exposure.
Status checkInputValues(const FrameInputs& in) {
  auto notA = [](const char* field, int value, const char* type) {
    return Status::error(StatusCode::InvalidInput, std::string("sslr: FrameInputs::") + field + " = " +
                         std::to_string(value) + " (not a sslr::" + type + ")");
  };
  if (in.surface.normals != NormalEncoding::Octahedral && in.surface.normals != NormalEncoding::XyzUnorm)
    return notA("surface.normals", static_cast<int>(in.surface.normals), "NormalEncoding");
  if (in.surface.space != NormalSpace::View && in.surface.space != NormalSpace::World)
    return notA("surface.space", static_cast<int>(in.surface.space), "NormalSpace");
  if (in.depth.range != DepthRange::NegativeOneToOne && in.depth.range != DepthRange::ZeroToOne)
    return notA("depth.range", static_cast<int>(in.depth.range), "DepthRange");
  if (!std::isfinite(in.exposure) || !(in.exposure > 0.0f))
    return Status::error(StatusCode::InvalidInput, "sslr: FrameInputs::exposure = " + std::to_string(in.exposure) +
                         " (must be finite and > 0; 1 = the colour texture's own units)");
  return {};
}

// How the passes read the G-buffer: layout, convention, optional inputs, world-space normals.
Status surfaceConstants(const FrameInputs& in, int width, int height, shared::SslrFrame& f) {
  f.surface.normalEncoding =
      in.surface.normals == NormalEncoding::Octahedral ? SSLR_NORMALS_OCTAHEDRAL : SSLR_NORMALS_XYZ_UNORM;
  f.surface.roughnessChannel = in.surface.roughnessChannel;
  f.surface.reflectanceChannel = in.surface.reflectanceChannel;
  f.surface.reversedZ = in.depth.reversedZ ? 1 : 0;
  f.surface.constantRoughness = in.surface.constantRoughness;
  f.surface.constantReflectance = in.surface.constantReflectance;
  f.surface.separateMaterial = in.materialTexture != 0 ? 1 : 0;
  f.surface.hasMask = in.maskTexture != 0 ? 1 : 0;
  f.surface.hasBackDepth = in.backDepthTexture != 0 ? 1 : 0;
  f.surface.width = static_cast<float>(width);
  f.surface.height = static_cast<float>(height);
  const float scale = in.surface.normalScale, bias = in.surface.normalBias;
  if (!std::isfinite(scale) || !std::isfinite(bias) || scale == 0.0f)
    return Status::error(StatusCode::InvalidInput, "sslr: SurfaceLayout::normalScale/normalBias = " + std::to_string(scale) +
                         "/" + std::to_string(bias) + " (must be finite, the scale not 0: 2/-1 for unsigned formats, "
                         "1/0 for signed ones)");
  f.surface.metalnessChannel = in.surface.metalnessChannel;
  f.surface.normalScale = scale;
  f.surface.normalBias = bias;
  if (in.surface.space == NormalSpace::World) {
    // Normals transform by the inverse transpose (right for any affine view, scaled ones too).
    if (in.viewFromWorld == glm::dmat4(0.0))
      return Status::error(StatusCode::InvalidInput, "sslr: SurfaceLayout::space is NormalSpace::World but FrameInputs::viewFromWorld is "
                           "not given (all zeros): set it to the frame's view matrix");
    const glm::dmat3 linear(in.viewFromWorld);
    const double det = glm::determinant(linear);
    bool finite = std::isfinite(det);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) finite = finite && std::isfinite(in.viewFromWorld[c][r]);
    if (!finite || std::abs(det) < 1e-12)
      return Status::error(StatusCode::InvalidInput, "sslr: FrameInputs::viewFromWorld is singular or not finite (determinant " +
                           std::to_string(det) + "); NormalSpace::World needs the frame's view matrix");
    const glm::dmat3 normalFromWorld = glm::transpose(glm::inverse(linear));
    f.surface.normalFromStored0 = glm::vec4(glm::vec3(normalFromWorld[0]), 1.0f);
    f.surface.normalFromStored1 = glm::vec4(glm::vec3(normalFromWorld[1]), 0.0f);
    f.surface.normalFromStored2 = glm::vec4(glm::vec3(normalFromWorld[2]), 0.0f);
  }
  return {};
}

// The tracers' parameters, and the comparison methods'.
void traceConstants(const FrameInputs& in, const Settings& s, int width, int height, shared::SslrFrame& f) {
  shared::SslrTraceParams& t = f.trace;
  // At least 4 pixels: a shorter first step leaves the probe in or next to its own pixel, whose
  // depth says nothing about the ray.
  t.initialLengthPixels = std::max(s.adaptiveL.initialLengthScreen * static_cast<float>(height), 4.0f);
  t.convergenceEps = s.adaptiveL.convergenceEps;
  t.errorK = s.fades.errorK;
  t.maxDistance = s.fades.maxDistance;
  t.screenEdge = s.fades.screenEdge;
  t.cameraStart = s.fades.cameraStart;
  t.cameraEnd = s.fades.cameraEnd;
  t.roughnessCutoff = s.selection.roughnessCutoff;
  t.minReflectance = s.selection.minReflectance;
  t.maxRadiusPx = s.blur.maxRadiusPx;
  t.coneScale = s.blur.coneScale;
  t.depthSigma = s.blur.depthSigma;
  t.normalPower = s.blur.normalPower;
  t.maxIterations = s.adaptiveL.maxIterations;
  t.fresnel = s.fresnel == FresnelMode::Classic ? SSLR_FRESNEL_CLASSIC : SSLR_FRESNEL_SCHLICK;
  t.outputRadiance = s.output == OutputMode::Radiance ? 1 : 0;
  t.stochasticFrom = s.glossy.mode == GlossyMode::Stochastic ? s.glossy.stochasticFrom : SSLR_NO_STOCHASTIC_RAYS;
  // The limit is in display units (luminance x exposure): in the colour texture's, / exposure.
  // A limit too small for a float after the division stays a limit (the smallest normal float),
  // not 0, which would turn the clamp off.
  t.maxLuminance = s.radianceClamp.maxLuminance > 0.0f
                          ? std::max(s.radianceClamp.maxLuminance / in.exposure, std::numeric_limits<float>::min())
                          : 0.0f;
  // A measured thickness (back-face depth) replaces the curved solids' estimate.
  t.curvedSolids = in.backDepthTexture == 0 && s.method != Method::FidelityFxSssr ? 1 : 0;
  // FidelityFX SSSR's raymarch reads the pyramid too (its nearest depths).
  t.hizMode = s.method == Method::HierarchicalDepth || s.method == Method::FidelityFxSssr
                  ? SSLR_HIZ_ONLY
                  : (s.method == Method::AdaptiveL && s.traversal.maxSteps > 0 ? SSLR_HIZ_TRAVERSAL_FIRST : SSLR_HIZ_OFF);
  t.maxSteps = s.traversal.maxSteps;
  t.objectDepthRelative = s.traversal.objectDepthRelative;
  t.hiddenGuess = s.traversal.hiddenGuess;
  t.thinObjectHits = t.hizMode == SSLR_HIZ_TRAVERSAL_FIRST ? 1 : 0;
  t.depthBufferThickness = s.ffx.depthBufferThickness;
  t.maxTraversalIntersections = s.ffx.maxTraversalIntersections;
  t.hizLevels = shared::sslrHiZLevelCount(width, height);
  f.positionBuffer.maxDistance = s.positionBuffer.maxDistance;
  f.positionBuffer.resolution = s.positionBuffer.resolution;
  f.positionBuffer.hitTolerance = s.positionBuffer.hitTolerance;
  f.positionBuffer.steps = s.positionBuffer.steps;
  f.dda.stride = s.dda.stride;
  f.dda.objectDepth = s.dda.objectDepth;
  f.dda.maxDistance = s.dda.maxDistance;
  f.dda.maxSteps = s.dda.maxSteps;
  f.dda.jitter = s.dda.jitter ? 1 : 0;
  f.dda.refine = s.dda.refine ? 1 : 0;
}

// Temporal reuse's reprojection (Settings::temporal only).
Status temporalConstants(const FrameInputs& in, const Settings& s, shared::SslrFrame& f) {
  if (s.temporal.enabled) {
    bool finite = true, zero = true;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) {
        finite = finite && std::isfinite(in.previousClipFromView[c][r]);
        zero = zero && in.previousClipFromView[c][r] == 0.0;
      }
    if (zero)
      return Status::error(StatusCode::InvalidInput, "sslr: Settings::temporal needs FrameInputs::previousClipFromView (the previous "
                           "frame's clipFromView x viewFromWorld x this frame's worldFromView); it is all zeros");
    if (!finite) return Status::error(StatusCode::InvalidInput, "sslr: FrameInputs::previousClipFromView is not finite");
    f.temporal.previousClipFromView = glm::mat4(in.previousClipFromView);
    f.temporal.historyWeight = s.temporal.historyWeight;
    // 2% of the depth: a surface seen again, within a pixel's slope at grazing angles; the
    // four history texels around the reprojected point are tried, so a slope costs nothing.
    f.temporal.keyTolerance = 0.02f;
    f.temporal.hasMotion = in.motionTexture != 0 ? 1 : 0;
    // The previous eye: the point the previous projection sends to clip w = 0 with x = y = 0, i.e.
    // inverse(previousClipFromView) (0, 0, 1, 0) (perspective only; orthographic has no eye).
    if (f.proj.orthographic == 0) {
      const glm::dvec4 e = glm::inverse(in.previousClipFromView) * glm::dvec4(0.0, 0.0, 1.0, 0.0);
      const glm::dvec3 eye = glm::dvec3(e) / e.w;
      if (std::abs(e.w) > 1e-12 && std::isfinite(eye.x) && std::isfinite(eye.y) && std::isfinite(eye.z))
        f.temporal.previousEye = glm::vec4(glm::vec3(eye), 1.0f);
    }
  }
  return {};
}

}  // namespace

Expected<Viewport> frameViewport(const FrameInputs& in, int textureWidth, int textureHeight) {
  const Viewport& v = in.viewport;
  if (v.x == 0 && v.y == 0 && v.width == 0 && v.height == 0) return Viewport{0, 0, textureWidth, textureHeight};
  // (64-bit sums: no overflow on hostile values)
  if (v.x < 0 || v.y < 0 || v.width < 1 || v.height < 1 || std::int64_t(v.x) + v.width > textureWidth ||
      std::int64_t(v.y) + v.height > textureHeight)
    return Status::error(StatusCode::InvalidInput, "sslr: FrameInputs::viewport (x " + std::to_string(v.x) + ", y " +
                         std::to_string(v.y) + ", " + std::to_string(v.width) + "x" + std::to_string(v.height) +
                         ") does not lie inside the " + std::to_string(textureWidth) + "x" +
                         std::to_string(textureHeight) + " textures (all zeros: the whole of them)");
  return v;
}

Expected<shared::SslrFrame> frameConstants(const FrameInputs& in, const Settings& s, int width, int height) {
  if (std::string why = validate(s); !why.empty()) return Status::error(StatusCode::InvalidSettings, why);
  if (Status st = checkInputValues(in); !st) return st;
  auto proj = detail::reduceProjection(in.clipFromView, in.depth);
  if (!proj) return proj.status();
  auto viewport = frameViewport(in, width, height);
  if (!viewport) return viewport.status();
  const Viewport v = viewport.value();
  shared::SslrFrame f{};
  f.proj = proj.value();
  if (Status st = surfaceConstants(in, v.width, v.height, f); !st) return st;
  f.surface.originX = v.x;
  f.surface.originY = v.y;
  f.surface.textureWidth = width;
  f.surface.textureHeight = height;
  f.surface.viewportInside = v.width != width || v.height != height ? 1 : 0;
  traceConstants(in, s, v.width, v.height, f);
  if (Status st = temporalConstants(in, s, f); !st) return st;
  return f;
}

}  // namespace sslr
