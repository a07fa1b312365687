#include "sslr_host/camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

namespace sslr::host {

const char* toString(DepthMode mode) {
  switch (mode) {
    case DepthMode::GlDefault: return "gl-default";
    case DepthMode::ZeroToOne: return "zero-to-one";
    case DepthMode::Reversed: return "reversed";
    case DepthMode::ReversedInfinite: return "reversed-infinite";
  }
  return "?";
}

bool parseDepthMode(const std::string& text, DepthMode& mode) {
  for (DepthMode m : {DepthMode::GlDefault, DepthMode::ZeroToOne, DepthMode::Reversed,
                      DepthMode::ReversedInfinite})
    if (text == toString(m)) {
      mode = m;
      return true;
    }
  return false;
}

DepthConvention depthConvention(DepthMode mode) {
  switch (mode) {
    case DepthMode::GlDefault: return DepthConvention::glDefault();
    case DepthMode::ZeroToOne: return DepthConvention::zeroToOne();
    case DepthMode::Reversed:
    case DepthMode::ReversedInfinite: return DepthConvention::reversed();
  }
  return {};
}

glm::dmat4 Camera::viewFromWorld() const { return glm::lookAtRH(eye, target, up); }

glm::dmat4 Camera::clipFromView(DepthMode mode, double aspect, glm::dvec2 offsetPx,
                                glm::dvec2 sizePx) const {
  const double n = nearPlane, f = farPlane;
  glm::dmat4 p(0.0);
  double xScale, yScale;
  if (orthographic) {
    yScale = 2.0 / orthoHeight;
    xScale = yScale / aspect;
    p[0][0] = xScale;
    p[1][1] = yScale;
    p[3][3] = 1.0;
    switch (mode) {
      case DepthMode::GlDefault:  // z_ndc = -2/(f-n) z - (f+n)/(f-n)
        p[2][2] = -2.0 / (f - n);
        p[3][2] = -(f + n) / (f - n);
        break;
      case DepthMode::ZeroToOne:  // z_ndc = -z/(f-n) - n/(f-n)
        p[2][2] = -1.0 / (f - n);
        p[3][2] = -n / (f - n);
        break;
      case DepthMode::Reversed:
      case DepthMode::ReversedInfinite:  // z_ndc = z/(f-n) + f/(f-n)
        p[2][2] = 1.0 / (f - n);
        p[3][2] = f / (f - n);
        break;
    }
    // Offsets (in ndc) go to the translation column for orthographic projections.
    p[3][0] = 2.0 * offsetPx.x / sizePx.x;
    p[3][1] = 2.0 * offsetPx.y / sizePx.y;
    return p;
  }
  yScale = 1.0 / std::tan(glm::radians(fovyDegrees) * 0.5);
  xScale = yScale / aspect;
  p[0][0] = xScale;
  p[1][1] = yScale;
  p[2][3] = -1.0;
  switch (mode) {
    case DepthMode::GlDefault:
      p[2][2] = -(f + n) / (f - n);
      p[3][2] = -2.0 * f * n / (f - n);
      break;
    case DepthMode::ZeroToOne:
      p[2][2] = -f / (f - n);
      p[3][2] = -f * n / (f - n);
      break;
    case DepthMode::Reversed:
      p[2][2] = n / (f - n);
      p[3][2] = f * n / (f - n);
      break;
    case DepthMode::ReversedInfinite:
      p[2][2] = 0.0;
      p[3][2] = n;
      break;
  }
  // A pixel offset shifts clip x by offset * 2/size * w, with w = -z: it goes to column 2.
  p[2][0] = -2.0 * offsetPx.x / sizePx.x;
  p[2][1] = -2.0 * offsetPx.y / sizePx.y;
  return p;
}

namespace {
constexpr double kMinPlane = 1e-20, kMaxPlane = 1e20, kMaxFarOverNear = 1e9;
}  // namespace

std::string Camera::validate() const {
  auto finite3 = [](glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite3(eye) || !finite3(target) || !finite3(up)) return "camera eye/target/up must be finite";
  // Beyond this a double can no longer tell a pixel's worth of view direction apart.
  const double far = std::max(maxAbsComponent(eye), maxAbsComponent(target));
  if (!(far <= 1e15)) {
    char text[128];
    std::snprintf(text, sizeof text, "camera eye/target lie %.3g units from the origin (at most 1e15 supported)", far);
    return text;
  }
  if (glm::length(target - eye) <= 1e-12 * std::max(far, 1.0)) return "camera eye and target coincide";
  if (glm::length(glm::cross(glm::normalize(target - eye), up)) < 1e-9)
    return "camera up is parallel to the view direction (or zero)";
  // The projection is built in double and used in float: its planes must be normal floats, far
  // enough apart to be told apart in float, and not so far apart that depth has no precision left.
  if (!(nearPlane >= kMinPlane)) return "near plane must be >= 1e-20";
  if (!(farPlane > nearPlane) || !(farPlane <= kMaxPlane)) return "far plane must be > near and <= 1e20";
  if (!(farPlane >= nearPlane * (1.0 + 1e-5)))
    return "near and far planes are too close (far must exceed near by 1e-5 of near, or depth has no range)";
  if (!(farPlane <= nearPlane * kMaxFarOverNear))
    return "far / near is above 1e9: depth keeps no precision (move the near plane out or the far plane in)";
  if (orthographic) {
    if (!(orthoHeight >= kMinPlane) || !(orthoHeight <= kMaxPlane)) return "orthographic height must be in [1e-20, 1e20]";
  } else if (!(fovyDegrees >= 1e-3 && fovyDegrees < 180.0)) {
    return "vertical field of view must be in [0.001, 180) degrees";
  }
  return "";
}

}  // namespace sslr::host
