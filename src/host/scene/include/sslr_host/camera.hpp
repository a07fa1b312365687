// Cameras and the projection matrices of every depth convention, built in double.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "sslr/sslr.hpp"

namespace sslr::host {

// The depth conventions the tools can rasterize with (the library accepts any of them).
enum class DepthMode {
  GlDefault,         // D24, clip z in [-1,1], near -> 0, far -> 1 (no glClipControl)
  ZeroToOne,         // D32F, glClipControl(LOWER_LEFT, ZERO_TO_ONE), near -> 0, far -> 1
  Reversed,          // D32F, ZERO_TO_ONE, near -> 1, far -> 0 (the default: best precision)
  ReversedInfinite,  // D32F, ZERO_TO_ONE, near -> 1, infinitely far -> 0
};
const char* toString(DepthMode mode);
bool parseDepthMode(const std::string& text, DepthMode& mode);
DepthConvention depthConvention(DepthMode mode);

// The largest |coordinate| of a point: how far from the origin it reaches along an axis (the
// length of a far point would overflow).
inline double maxAbsComponent(glm::dvec3 v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

struct Camera {
  glm::dvec3 eye{0.0, 2.0, 8.0};
  glm::dvec3 target{0.0, 1.0, 0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fovyDegrees = 50.0;
  double nearPlane = 0.1;
  double farPlane = 200.0;
  bool orthographic = false;
  double orthoHeight = 10.0;  // full height of the view volume (orthographic)

  glm::dmat4 viewFromWorld() const;
  // Perspective or orthographic for the given convention; offset (in pixels) shifts the frustum
  // for off-centre / jittered projections. For ReversedInfinite + orthographic the far plane
  // stays finite (an orthographic projection cannot have an infinite far plane).
  glm::dmat4 clipFromView(DepthMode mode, double aspect, glm::dvec2 offsetPx = {0.0, 0.0},
                          glm::dvec2 sizePx = {1.0, 1.0}) const;
  // "" if usable, else why not (degenerate eye/target/up, bad planes or angles).
  std::string validate() const;
};

}  // namespace sslr::host
