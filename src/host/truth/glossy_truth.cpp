#include "sslr_host/glossy_truth.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "sslr/reference.hpp"
#include "sslr_host/reference_image.hpp"
#include "sslr_shared.h"

namespace sslr::host {

namespace {

// A pixel's rotation of the stratified pattern (a hash of its index): neighbours' patterns differ.
glm::vec2 pixelRotation(std::uint32_t p) {
  const std::uint32_t h = shared::sslrHash(p);
  return glm::vec2(float(h >> 8), float(shared::sslrHash(h ^ 0x9e3779b9u) >> 8)) / 16777216.0f;
}

// Sample k of n: a Hammersley point, rotated (Cranley-Patterson) and wrapped into [0, 1).
glm::vec2 samplePoint(int k, int n, glm::vec2 rotation) {
  const glm::vec2 u = shared::sslrHammersley(k, n) + rotation;
  return u - glm::floor(u);
}

// An orthonormal frame around n (Duff et al. 2017).
void tangentFrame(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

// Where (`hit`, and `uv` on screen) the ray from `start` along `vsL` meets the scene, if the
// camera sees that point (within the depth range, nothing in between): what the screen shows of
// the ray.
bool visibleOnScreen(const RayTracer& tracer, const glm::dmat4& clipFromView, bool ortho, glm::vec3 start,
                     glm::vec3 vsL, RayTracer::Hit& hit, glm::vec2& uv) {
  hit = tracer.intersect(start, vsL);
  if (!hit.hit) return false;
  const glm::dvec4 clip = clipFromView * glm::dvec4(glm::dvec3(hit.vsPosition), 1.0);
  if (!(clip.w > 0.0)) return false;
  const glm::dvec3 ndcHit = glm::dvec3(clip) / clip.w;
  uv = glm::vec2(glm::dvec2(ndcHit) * 0.5 + 0.5);
  if (uv.x < 0.0f || uv.x > 1.0f || uv.y < 0.0f || uv.y > 1.0f || ndcHit.z < -1.0 - 1e-9 || ndcHit.z > 1.0 + 1e-9)
    return false;
  const glm::vec3 camera = ortho ? glm::vec3(hit.vsPosition.x, hit.vsPosition.y, 0.0f) : glm::vec3(0.0f);
  const glm::vec3 toHit = hit.vsPosition - camera;
  const float dist = glm::length(toHit);
  return !tracer.occluded(camera, toHit / dist, dist * (1.0f - 1e-4f));
}

}  // namespace

GlossyTruth computeGlossyTruth(const RayTracer& tracer, const glm::dmat4& clipFromView, const Image& color,
                               const Image& roughness, const std::vector<std::uint8_t>& mask, int samples) {
  return computeGlossyTruth(
      tracer, clipFromView, [&color](const RayTracer::Hit&, glm::vec3, glm::vec2 uv) { return sampleBilinear(color, uv); },
      roughness, mask, samples);
}

GlossyTruth computeGlossyTruth(const RayTracer& tracer, const glm::dmat4& clipFromView, const GlossyRadianceAt& radianceAt,
                               const Image& roughness, const std::vector<std::uint8_t>& mask, int samples) {
  GlossyTruth g;
  g.width = roughness.width;
  g.height = roughness.height;
  g.samples = samples;
  const size_t count = static_cast<size_t>(g.width) * g.height;
  g.radiance.assign(count, glm::vec3(0.0f));
  g.halfSpread.assign(count, glm::vec3(0.0f));
  g.visibleShare.assign(count, -1.0f);
  g.roughness.assign(count, 0.0f);
  const bool ortho = clipFromView[3][3] == 1.0;
  const PrimaryRays rays{glm::inverse(clipFromView), ortho, g.width, g.height};
  auto row = [&](int y) {
    for (int x = 0; x < g.width; ++x) {
      const size_t p = static_cast<size_t>(y) * g.width + x;
      g.roughness[p] = roughness.pixels[p * roughness.channels];
      if (!mask[p]) continue;
      // The primary ray through the pixel centre (as the mirror truth's).
      glm::dvec3 dOrigin, dDir;
      rays.at(x, y, dOrigin, dDir);
      const glm::vec3 dir(dDir);
      const RayTracer::Hit primary = tracer.intersect(glm::vec3(dOrigin), dir);
      g.visibleShare[p] = 0.0f;
      if (!primary.hit) continue;
      const glm::vec3 n = primary.vsNormal;
      glm::vec3 t, b;
      tangentFrame(n, t, b);
      const glm::vec3 toEye = -dir;
      const glm::vec3 ve(glm::dot(toEye, t), glm::dot(toEye, b), glm::dot(toEye, n));
      if (!(ve.z > 0.0f)) continue;
      const float alpha = std::max(g.roughness[p] * g.roughness[p], 1e-4f);
      const glm::vec3 start = offsetFromSurface(primary);
      // Two halves, each a whole stratified set under a rotation of its own (randomized
      // quasi-Monte Carlo): their difference measures the estimate's own error.
      const glm::vec2 rotations[2] = {pixelRotation(static_cast<std::uint32_t>(p)),
                                      pixelRotation(static_cast<std::uint32_t>(p) ^ 0x80000000u)};
      const int halfCount = samples / 2;
      glm::vec3 sum[2] = {glm::vec3(0.0f), glm::vec3(0.0f)};
      double weight[2] = {0.0, 0.0}, known[2] = {0.0, 0.0};
      for (int k = 0; k < 2 * halfCount; ++k) {
        const int half = k / halfCount;
        const glm::vec3 h =
            shared::sslrSampleGgxVndf(ve, alpha, samplePoint(k % halfCount, halfCount, rotations[half]));
        const glm::vec3 l = glm::reflect(-ve, h);
        const float w = shared::sslrSmithG1(l.z, alpha);
        if (!(w > 0.0f)) continue;  // below the surface: the lobe's masked part
        weight[half] += w;
        const glm::vec3 vsL = glm::normalize(t * l.x + b * l.y + n * l.z);
        glm::vec2 uv;
        RayTracer::Hit hit;
        if (!visibleOnScreen(tracer, clipFromView, ortho, start, vsL, hit, uv)) continue;
        sum[half] += radianceAt(hit, vsL, uv) * w;
        known[half] += w;
      }
      const double totalWeight = weight[0] + weight[1], totalKnown = known[0] + known[1];
      if (!(totalWeight > 0.0)) continue;
      g.visibleShare[p] = float(totalKnown / totalWeight);
      if (!(totalKnown > 0.0)) continue;
      g.radiance[p] = (sum[0] + sum[1]) / float(totalKnown);
      if (known[0] > 0.0 && known[1] > 0.0)
        g.halfSpread[p] = glm::abs(sum[0] / float(known[0]) - sum[1] / float(known[1])) * 0.5f;
    }
  };
  const int threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i)
    pool.emplace_back([&, i] {
      for (int y = i; y < g.height; y += threads) row(y);
    });
  for (std::thread& th : pool) th.join();
  return g;
}

Expected<GlossyTruth> glossyTruthFor(const Scene& scene, const GBuffer& gbuffer, const Settings& settings,
                                     int samples) {
  if (samples < 2 || samples > 65536)
    return Status::error("glossy truth: " + std::to_string(samples) + " samples per pixel (must be 2..65536)");
  auto tracer = RayTracer::create(scene, gbuffer.viewFromWorld());
  if (!tracer) return Status::error(tracer.error());
  const Image depth = gbuffer.readDepth(), packed = gbuffer.readNormalPacked();
  const FrameInputs in = gbuffer.frameInputs();
  auto frame = frameConstants(in, settings, gbuffer.width(), gbuffer.height());
  if (!frame) return Status::error(frame.status().message());
  Image rough;
  rough.width = packed.width;
  rough.height = packed.height;
  rough.channels = 1;
  rough.pixels.resize(static_cast<size_t>(packed.width) * packed.height);
  for (size_t p = 0; p < rough.pixels.size(); ++p) {
    const float* n = &packed.pixels[p * packed.channels];
    rough.pixels[p] = shared::sslrRoughness(frame.value().surface, glm::vec4(n[0], n[1], n[2], n[3]));
  }
  const auto mask = reflectiveMask(depth, packed, in, settings);
  // Each visible hit shaded as the mirror reference shades it (reflectedRadiance): as the colour
  // buffer stores it where the camera sees the side the lobe ray meets, lit on that side otherwise.
  const glm::dmat4 viewFromWorld = gbuffer.viewFromWorld();
  const bool ortho = gbuffer.clipFromView()[3][3] == 1.0;
  auto radianceAt = [&](const RayTracer::Hit& hit, glm::vec3 vsDirection, glm::vec2) {
    return reflectedRadiance(scene, hit, vsDirection, viewFromWorld, ortho, true);
  };
  return computeGlossyTruth(*tracer.value(), gbuffer.clipFromView(), radianceAt, rough, mask, samples);
}

namespace {
bool scoredPixel(const GlossyTruth& t, size_t p, float minRoughness, float minVisibleShare) {
  return t.visibleShare[p] >= minVisibleShare && t.roughness[p] >= minRoughness;
}
glm::vec3 estimateAt(const Image& resolved, size_t p, bool* covered) {
  const float* r = &resolved.pixels[p * resolved.channels];
  *covered = std::isfinite(r[3]) && r[3] >= 1e-3f;
  return *covered ? glm::vec3(r[0], r[1], r[2]) / r[3] : glm::vec3(0.0f);
}
}  // namespace

GlossyMetrics compareGlossy(const GlossyTruth& truth, const Image& resolved, float minRoughness, float minVisibleShare) {
  GlossyMetrics m;
  double sq = 0.0, ref = 0.0, noise = 0.0, display = 0.0;
  auto toDisplay = [](glm::vec3 c) { return c / (glm::vec3(1.0f) + glm::max(c, glm::vec3(0.0f))); };
  size_t uncovered = 0;
  for (size_t p = 0; p < truth.radiance.size(); ++p) {
    if (!scoredPixel(truth, p, minRoughness, minVisibleShare)) continue;
    bool covered = false;
    const glm::vec3 e = estimateAt(resolved, p, &covered);
    const glm::vec3 d = e - truth.radiance[p];
    uncovered += covered ? 0 : 1;
    sq += (std::isfinite(glm::dot(d, d)) ? glm::dot(d, d) : 1e6) / 3.0;
    const glm::vec3 dd = toDisplay(e) - toDisplay(truth.radiance[p]);
    display += (std::isfinite(glm::dot(dd, dd)) ? glm::dot(dd, dd) : 1.0) / 3.0;
    ref += glm::dot(truth.radiance[p], truth.radiance[p]) / 3.0;
    noise += glm::dot(truth.halfSpread[p], truth.halfSpread[p]) / 3.0;
    ++m.scored;
  }
  if (m.scored == 0) return m;
  m.rmse = std::sqrt(sq / m.scored);
  m.displayRmse = std::sqrt(display / m.scored);
  m.relativeRmse = ref > 0.0 ? m.rmse / std::sqrt(ref / m.scored) : 0.0;
  m.referenceNoise = std::sqrt(noise / m.scored);
  m.rmseAboveNoise = std::sqrt(std::max(0.0, m.rmse * m.rmse - m.referenceNoise * m.referenceNoise));
  m.uncovered = double(uncovered) / m.scored;
  return m;
}

namespace {
// An RGB image of the truth's size, dark grey (the colour of "not scored").
Image notScoredImage(const GlossyTruth& truth) {
  return Image{truth.width, truth.height, 3, std::vector<float>(truth.radiance.size() * 3, 0.08f)};
}
}  // namespace

Image glossyErrorImage(const GlossyTruth& truth, const Image& resolved, float gain, float minRoughness,
                       float minVisibleShare) {
  Image img = notScoredImage(truth);
  for (size_t p = 0; p < truth.radiance.size(); ++p) {
    if (!scoredPixel(truth, p, minRoughness, minVisibleShare)) continue;
    bool covered = false;
    const glm::vec3 e = estimateAt(resolved, p, &covered);
    const glm::vec3 v = covered ? glm::min(glm::abs(e - truth.radiance[p]) * gain, glm::vec3(1.0f)) : glm::vec3(0, 0, 1);
    img.pixels[p * 3] = v.x;
    img.pixels[p * 3 + 1] = v.y;
    img.pixels[p * 3 + 2] = v.z;
  }
  return img;
}

Image glossyTruthImage(const GlossyTruth& truth, float minRoughness, float minVisibleShare) {
  Image img = notScoredImage(truth);
  for (size_t p = 0; p < truth.radiance.size(); ++p) {
    if (!scoredPixel(truth, p, minRoughness, minVisibleShare)) continue;
    for (int c = 0; c < 3; ++c) img.pixels[p * 3 + c] = truth.radiance[p][c];
  }
  return img;
}

}  // namespace sslr::host
