// Ray-traced ground truth (Embree 3 on the CPU) for reflections, and the error metrics that
// compare a screen-space trace against it. Same triangles, same camera, pixel centres.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "sslr/sslr.hpp"
#include "sslr_host/gbuffer.hpp"
#include "sslr_host/image_io.hpp"
#include "sslr_host/scene.hpp"

namespace sslr::host {

// Classes of a reflective pixel's true reflection (docs/results.md, measuring protocol).
enum class TruthClass : std::uint8_t {
  NotReflective = 0,  // not traced by the SSR pass (background, rough, not reflective)
  Visible = 1,        // A: hits geometry on screen and visible there
  Occluded = 2,       // B: hits geometry on screen, hidden behind something else
  OffScreen = 3,      // C: hits geometry off screen or behind the camera
  Escaped = 4,        // D: hits nothing (background)
};

struct TruthPixel {
  TruthClass cls = TruthClass::NotReflective;
  glm::vec2 uvHit{0.0f};   // true hit projected to uv (classes A, B)
  float length = 0.0f;     // reflected ray length to the hit (view units)
  // Class A: a pixel within 1 px of the hit shows the hit's surface (its primary ray hits the same
  // mesh with a normal within 25 degrees). When none does (a face seen edge-on, thinner than a
  // pixel) the G-buffer holds no sample of the hit: no screen-space method can find it.
  bool shown = true;
};

struct GroundTruth {
  int width = 0, height = 0;
  std::vector<TruthPixel> pixels;  // GL row order
  size_t count(TruthClass c) const;
  size_t reflective() const { return pixels.size() - count(TruthClass::NotReflective); }
};

// Embree scene of the triangles in view space (view space keeps precision far from the origin).
class RayTracer {
 public:
  static Expected<std::unique_ptr<RayTracer>> create(const Scene& scene, const glm::dmat4& viewFromWorld);
  ~RayTracer();
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  struct Hit {
    bool hit = false;
    float t = 0.0f;
    glm::vec3 vsPosition{0.0f};
    glm::vec3 vsNormal{0.0f};  // interpolated vertex normal (facing the ray origin side)
    unsigned mesh = 0;         // index of the scene mesh hit
    unsigned primitive = 0;    // its triangle
    glm::vec2 barycentric{0.0f};  // (u, v): weights of the triangle's 2nd and 3rd vertex
  };
  Hit intersect(glm::vec3 vsOrigin, glm::vec3 vsDirection, float tFar = 1e30f) const;
  bool occluded(glm::vec3 vsOrigin, glm::vec3 vsDirection, float tFar) const;

 private:
  RayTracer() = default;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Primary rays through pixel centres, built in double from the exact matrix.
struct PrimaryRays {
  glm::dmat4 viewFromClip;
  bool ortho;
  int width, height;
  void at(int x, int y, glm::dvec3& origin, glm::dvec3& dir) const {
    const glm::dvec2 ndc((x + 0.5) / width * 2.0 - 1.0, (y + 0.5) / height * 2.0 - 1.0);
    glm::dvec4 nearPt = viewFromClip * glm::dvec4(ndc, -1.0, 1.0);
    glm::dvec4 farPt = viewFromClip * glm::dvec4(ndc, 0.5, 1.0);
    nearPt /= nearPt.w;
    farPt /= farPt.w;
    origin = ortho ? glm::dvec3(nearPt.x, nearPt.y, 0.0) : glm::dvec3(0.0);
    dir = ortho ? glm::dvec3(0, 0, -1) : glm::normalize(glm::dvec3(farPt));
  }
};

// Where a secondary ray leaves a primary hit: a hair off the surface along its normal, relative to
// the distance (against self-intersection).
inline glm::vec3 offsetFromSurface(const RayTracer::Hit& primary) {
  return primary.vsPosition + primary.vsNormal * (1e-5f * std::max(1.0f, glm::length(primary.vsPosition)));
}

// The exact reflection of a primary hit seen along `viewDir`: the ray reflected about the hit's
// interpolated normal, and what it meets.
struct Reflection {
  glm::vec3 direction{0.0f};
  RayTracer::Hit hit;
};
inline Reflection traceReflection(const RayTracer& tracer, const RayTracer::Hit& primary, glm::vec3 viewDir) {
  Reflection r;
  r.direction = glm::normalize(glm::reflect(viewDir, primary.vsNormal));
  r.hit = tracer.intersect(offsetFromSurface(primary), r.direction);
  return r;
}

// Which pixels the SSR pass traces (sslrShouldTrace on the read-back G-buffer).
std::vector<std::uint8_t> reflectiveMask(const Image& depth, const Image& normalPacked, const FrameInputs& in,
                                         const Settings& settings);

// Traces the exact reflection of every reflective pixel (primary ray through the pixel centre,
// interpolated normal) and classifies it.
GroundTruth computeGroundTruth(const RayTracer& tracer, const glm::dmat4& clipFromView, int width, int height,
                               const std::vector<std::uint8_t>& reflective);

// The whole protocol for what `gbuffer` last rendered of `scene`: Embree over the same triangles
// in the same view space, restricted to the pixels `settings` traces.
Expected<GroundTruth> groundTruthFor(const Scene& scene, const GBuffer& gbuffer, const Settings& settings);
// The same over a tracer already built for that frame's scene and view (the reference image reuses it).
GroundTruth groundTruthFor(const RayTracer& tracer, const GBuffer& gbuffer, const Settings& settings);

// A hit counts as reported when its confidence exceeds this (the measuring protocol's 0.5).
inline constexpr float kReportedConfidence = 0.5f;

// Error of a traced hit image (RG = uvHit, B = confidence) against the ground truth.
struct HitMetrics {
  size_t visible = 0, occluded = 0, offScreen = 0, escaped = 0;
  double recall1px = 0, recall2px = 0, recall4px = 0;  // A pixels reported within N px
  size_t unshown = 0;            // A pixels whose hit no pixel within 1 px shows (TruthPixel::shown)
  double recallShown1px = 0;     // recall1px over the other A pixels: what screen space can find
  double medianErrorPx = 0, p95ErrorPx = 0;            // over A pixels that reported a hit
  double falseHitRate = 0;                             // B+C+D pixels reporting a hit
  // The same, less the B pixels that report their true hit point within 1 px: a point hidden by
  // less than a pixel (a contact line) that the G-buffer cannot tell from a visible one.
  double falseHitRateBeyond1px = 0;
  size_t nonFinite = 0;                                // NaN/Inf pixels in the hit image
  // Reflection on A pixels: the colour at the reported hit (0 if none) against the colour at the
  // true hit, both sampled bilinearly from the lit colour buffer (linear RGB).
  double reflectionRmse = 0, reflectionPsnr = 0;  // PSNR with peak 1.0
};
// Error map of a hit image: black = exact, green = up to 1 px, yellow = 2 px, red >= 4 px;
// magenta = visible (A) but missed; white = a false hit (B, C or D reported).
Image hitErrorImage(const GroundTruth& truth, const Image& hit);

// The truth per pixel, to inspect beside hit.exr: R, G = the true hit's uv (classes A and B),
// B = the class (TruthClass: 0 not reflective, 1 A, 2 B, 3 C, 4 D), A = 1 where the hit is shown
// (TruthPixel::shown).
Image truthImage(const GroundTruth& truth);

// `color` (optional) enables the reflection RMSE / PSNR.
HitMetrics compareHits(const GroundTruth& truth, const Image& hit, float confidenceThreshold = kReportedConfidence,
                       const Image* color = nullptr);

}  // namespace sslr::host
