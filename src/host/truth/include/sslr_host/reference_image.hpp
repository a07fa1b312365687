// The ray-traced reference of what a user sees: each mirror pixel's composite with its exact
// reflection, shaded by Embree's hit with the G-buffer pass's own lighting on the side the reflected
// ray meets (whether the camera sees that point or not; escaped rays get the fallback environment),
// and the image error of a method's composite against it (docs/results.md, "How these numbers were obtained").
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "sslr_host/gbuffer.hpp"
#include "sslr_host/ground_truth.hpp"
#include "sslr_host/image_io.hpp"
#include "sslr_host/scene.hpp"

namespace sslr::host {

// Mirror pixels: the primary surface's material roughness at most this (rough pixels are blurred
// by a cone; their reference is the glossy study's).
constexpr float kReferenceMaxRoughness = 0.02f;

struct ReferenceImage {
  // RGB, linear: colour - fallback specular + reflectance x Fresnel (classic) x the exact
  // reflection (as stored, asStoredColor, where the camera sees it), on the scored pixels; the
  // G-buffer colour elsewhere.
  Image composite;
  std::vector<std::uint8_t> scored;  // 1: a mirror pixel sslr traces, compared
  size_t scoredCount = 0;
};

// The reference for what `gbuffer` last rendered of `scene` (`truth`: its reflective pixels).
ReferenceImage referenceComposite(const Scene& scene, const RayTracer& tracer, const GBuffer& gbuffer,
                                  const GroundTruth& truth);

// The same, with a ray tracer of its own over `scene` (Embree; an error names what failed).
Expected<ReferenceImage> referenceFor(const Scene& scene, const GBuffer& gbuffer, const GroundTruth& truth);

// The G-buffer pass's lit colour of a point the tracer hit (its shader: a directional light, a
// sky/ground ambient, emission and the fallback specular), seen from `vsToViewer` (unit, from the
// point towards whoever looks): the face turned to the viewer is lit, and the view-dependent
// fallback specular is the one seen from there.
glm::vec3 shadeSeenFrom(const Scene& scene, const RayTracer::Hit& hit, const glm::dmat4& viewFromWorld,
                        glm::vec3 vsToViewer);
// The same as the camera sees it: what the G-buffer pass wrote for that point.
glm::vec3 shadeAsGBuffer(const Scene& scene, const RayTracer::Hit& hit, const glm::dmat4& viewFromWorld,
                         bool orthographic);
// What a ray travelling along `vsRayDirection` brings back from `hit`, the light leaving the face it
// meets towards its origin. Where the camera sees that face (`cameraSeesHit`: nothing in between,
// and the camera in front of the same face), the colour buffer's stored shade of it (asStoredColor
// of shadeAsGBuffer: what a screen-space method reads at best); anywhere else (a hidden side, a
// point off the screen) shadeSeenFrom the ray's origin.
glm::vec3 reflectedRadiance(const Scene& scene, const RayTracer::Hit& hit, glm::vec3 vsRayDirection,
                            const glm::dmat4& viewFromWorld, bool orthographic, bool cameraSeesHit);
// `rgb` as the G-buffer's colour texture stores it (GBuffer: R11F_G11F_B10F, 6, 6 and 5 mantissa
// bits, rounded towards zero as glm packs and Mesa stores it): the finest colour a screen-space
// method can read of a point. Both references pass the shades of points the camera sees through
// it, so that they score the methods, not the colour format.
glm::vec3 asStoredColor(glm::vec3 rgb);

// NaN where no pixel was scored (a scene without mirrors): no error is not a perfect score.
struct ImageError {
  double rmse = NAN;  // over the scored pixels' RGB channels
  double psnr = NAN;  // dB, peak 1
  size_t pixels = 0;
};
ImageError compositeError(const ReferenceImage& reference, const Image& composite);

// Where the composite error comes from: the scored pixels by what the method reported (its hit
// image: RG = uv, B = confidence, reported above kReportedConfidence) against the truth.
struct CompositeBreakdown {
  struct Kind {
    size_t pixels = 0;
    double rmse = 0.0;   // over this kind's pixels
    double share = 0.0;  // of the total squared error
  };
  Kind hit;          // visible reflection, reported within 1 px of the true hit: fades, blur, shading
  Kind wrong;        // reported elsewhere: a false hit, or a visible reflection's hit over 1 px off
  Kind guessed;      // a guess below the reporting threshold (0 < confidence <= kReportedConfidence),
                     // whatever the truth: the composite shows a blend of it and the fallback
  Kind missed;       // visible reflection not reported at all (confidence 0): the fallback shows
  Kind unreachable;  // occluded, off screen or escaped, confidence 0: what no screen-space method sees
  // The wrong pixels scored as if they had been misses: showing `withoutReflection` (what the
  // composite shows at coverage 0) instead (share: of the total squared error as it is). Below
  // `wrong`, a miss would have served those pixels better than their hits.
  Kind wrongAsMisses;
  // The same squared error split by where the true reflection lies, whatever was reported: what
  // the screen shows (visible: a screen-space method can get it right), a hidden side (occluded)
  // or a point off the screen (both only guessed, or left to the fallback), or nothing (escaped:
  // right where nothing is reported). A scored pixel the truth did not trace counts in none.
  struct ByTruth {
    Kind visible, occluded, offScreen, escaped;
  } byTruth;
};
// `withoutReflection`: the frame as the composite leaves it where nothing was found; over the
// fallback (CompositeMode::BlendOverFallback) that is the G-buffer's colour, which holds the
// fallback specular. Per pixel: a miss would also change what the blur spreads to its neighbours.
CompositeBreakdown compositeBreakdown(const ReferenceImage& reference, const Image& composite, const GroundTruth& truth,
                                      const Image& hit, const Image& withoutReflection);

// |composite - reference| x 4 on the scored pixels, dark grey elsewhere (an sRGB image to look at).
Image compositeErrorMap(const ReferenceImage& reference, const Image& composite);

}  // namespace sslr::host
