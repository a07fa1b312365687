// Ray-traced reference of glossy reflections (Embree, the CPU): what a GGX lobe gathers of what
// the screen shows, to score how far screen-space glossy reflections (the roughness blur of the
// mirror reflection, or stochastic rays) are from it.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "sslr_host/ground_truth.hpp"

namespace sslr::host {

// Per pixel: the GGX lobe's mean incoming radiance over its light directions, each the reflection
// of the view about a microfacet normal drawn from the distribution of visible normals
// (sslrSampleGgxVndf), weighted by its masking (sslrSmithG1): the lobe's radiance without its
// Fresnel term (what sslr's OutputMode::Radiance estimates). A direction counts only where its
// ray hits geometry visible on screen (the class A of the mirror truth); its radiance is then that
// point's (glossyTruthFor: its lit colour, as stored by the G-buffer). Elsewhere (the sky, off screen,
// hidden) screen space cannot know the radiance: `visibleShare` says how much of the lobe's weight
// is known.
struct GlossyTruth {
  int width = 0, height = 0, samples = 0;
  std::vector<glm::vec3> radiance;     // GL row order; 0 where not glossy
  std::vector<glm::vec3> halfSpread;   // |mean of one half - mean of the other| / 2, each half a stratified
                                       // set rotated independently: the reference's own error (RMS)
  std::vector<float> visibleShare;     // 0..1; -1: not a pixel the SSR pass traces
  std::vector<float> roughness;        // the G-buffer's, per pixel
};

// The radiance a lobe ray travelling along `vsDirection` brings back from `hit`, a point the camera
// sees at `uv`. Called from several threads at once.
using GlossyRadianceAt = std::function<glm::vec3(const RayTracer::Hit& hit, glm::vec3 vsDirection, glm::vec2 uv)>;

// The lobe at each pixel `mask` marks, from the G-buffer's roughness image (one channel, its size
// the truth's), `samples` directions per pixel (two Hammersley sets of samples / 2, each rotated
// by a hash of the pixel: fixed, so runs agree), each visible hit's radiance by `radianceAt`.
// Threads over rows.
GlossyTruth computeGlossyTruth(const RayTracer& tracer, const glm::dmat4& clipFromView, const GlossyRadianceAt& radianceAt,
                               const Image& roughness, const std::vector<std::uint8_t>& mask, int samples);
// ... each hit's radiance read from the lit colour image at its uv, bilinearly, as a tracer reads
// the screen.
GlossyTruth computeGlossyTruth(const RayTracer& tracer, const glm::dmat4& clipFromView, const Image& color,
                               const Image& roughness, const std::vector<std::uint8_t>& mask, int samples);

// The whole protocol for what `gbuffer` last rendered of `scene` (the pixels `settings` traces).
Expected<GlossyTruth> glossyTruthFor(const Scene& scene, const GBuffer& gbuffer, const Settings& settings,
                                     int samples);

// A radiance estimate (rgb / a of a Radiance-mode resolved output: the mean reflected colour over
// what was found, 0 where a < 1e-3) against the truth, over the pixels with roughness at least
// `minRoughness` whose lobe is at least `minVisibleShare` on screen.
struct GlossyMetrics {
  size_t scored = 0;         // pixels compared
  double rmse = 0.0;         // per channel, linear colour
  double relativeRmse = 0.0; // rmse / the reference's RMS over the same pixels
  double referenceNoise = 0.0;  // RMS of the truth's halfSpread over them: the floor of any score
  double rmseAboveNoise = 0.0;  // sqrt(max(0, rmse^2 - referenceNoise^2)): the error itself, the
                                // reference's noise (independent of it) taken out
  double uncovered = 0.0;    // share of them with no estimate (a < 1e-3)
  // RMSE after the display transform x / (1 + x) per channel (Reinhard, at the colour texture's
  // exposure): what a viewer sees of HDR radiance, where a linear RMSE is all the brightest pixels'.
  double displayRmse = 0.0;
};
GlossyMetrics compareGlossy(const GlossyTruth& truth, const Image& resolved, float minRoughness = 0.1f,
                            float minVisibleShare = 0.9f);

// Error map: |estimate - truth| per channel x `gain`, over the scored pixels; blue where no
// estimate, dark grey where not scored.
Image glossyErrorImage(const GlossyTruth& truth, const Image& resolved, float gain = 4.0f, float minRoughness = 0.1f,
                       float minVisibleShare = 0.9f);
// The truth itself as an image (radiance; not scored pixels dark grey).
Image glossyTruthImage(const GlossyTruth& truth, float minRoughness = 0.1f, float minVisibleShare = 0.9f);

}  // namespace sslr::host
