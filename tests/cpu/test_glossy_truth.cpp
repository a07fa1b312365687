// The GGX lobe's math (sslr_shared.h) against its closed forms, and the glossy reference
// (glossy_truth.hpp) against the mirror truth where the lobe is a mirror, against a uniform
// colour, and on what it leaves unscored.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sslr_host/glossy_truth.hpp"
#include "sslr_shared.h"

using namespace sslr;
using namespace sslr::host;

namespace {

// A Hammersley set (sslr_shared.h): deterministic, so the tolerances below hold on every run.
glm::vec2 hammersley(int k, int n) { return shared::sslrHammersley(k, n); }

// Seen along the normal, the visible normals are GGX's normals weighted by their cosine, whose
// tan^2 of the angle to the normal is alpha^2 u / (1 - u) for u uniform: its quartiles are
// alpha^2 / 3, alpha^2 and 3 alpha^2.
TEST(GgxLobe, VisibleNormalsSeenAlongTheNormalFollowGgx) {
  for (float alpha : {0.09f, 0.3f, 0.7f}) {
    SCOPED_TRACE("alpha " + std::to_string(alpha));
    const int n = 4096;
    std::vector<float> t2(n);
    for (int k = 0; k < n; ++k) {
      const glm::vec3 h = shared::sslrSampleGgxVndf({0, 0, 1}, alpha, hammersley(k, n));
      ASSERT_NEAR(glm::length(h), 1.0f, 1e-5f);
      t2[k] = (1.0f - h.z * h.z) / (h.z * h.z) / (alpha * alpha);
    }
    std::sort(t2.begin(), t2.end());
    // 4096 stratified samples: the quantiles within 2% (the sampling's own error is below 0.1%).
    EXPECT_NEAR(t2[n / 4], 1.0f / 3.0f, 0.02f / 3.0f);
    EXPECT_NEAR(t2[n / 2], 1.0f, 0.02f);
    EXPECT_NEAR(t2[3 * n / 4], 3.0f, 0.06f);
  }
}

// Only normals the view can see: never below the surface, never facing away from the view.
TEST(GgxLobe, SampledNormalsFaceTheView) {
  for (float degrees : {0.0f, 45.0f, 80.0f, 89.5f}) {
    const float a = glm::radians(degrees);
    const glm::vec3 ve(std::sin(a), 0.0f, std::cos(a));
    for (float alpha : {0.01f, 0.3f, 1.0f})
      for (int k = 0; k < 1024; ++k) {
        const glm::vec3 h = shared::sslrSampleGgxVndf(ve, alpha, hammersley(k, 1024));
        ASSERT_GE(h.z, 0.0f);
        ASSERT_GE(glm::dot(h, ve), -1e-5f) << degrees << " deg, alpha " << alpha;
      }
  }
}

TEST(GgxLobe, SmithMaskingClosedForms) {
  EXPECT_NEAR(shared::sslrSmithG1(1.0f, 0.5f), 1.0f, 1e-6f);   // along the normal nothing is masked
  EXPECT_NEAR(shared::sslrSmithG1(0.3f, 0.0f), 1.0f, 1e-6f);   // a mirror masks nothing
  EXPECT_EQ(shared::sslrSmithG1(0.0f, 0.5f), 0.0f);             // grazing
  EXPECT_EQ(shared::sslrSmithG1(-0.2f, 0.5f), 0.0f);            // below the surface
  // alpha 0.5, cos 0.5: 2 * 0.5 / (0.5 + sqrt(0.25 + 0.75 * 0.25)).
  EXPECT_NEAR(shared::sslrSmithG1(0.5f, 0.5f), 1.0f / (0.5f + std::sqrt(0.4375f)), 1e-6f);
  float last = 0.0f;
  for (float c = 0.05f; c <= 1.0f; c += 0.05f) {  // more masked the more grazing
    const float g = shared::sslrSmithG1(c, 0.4f);
    EXPECT_GT(g, last);
    last = g;
  }
}

// A camera at the origin looking down -z over a floor (y = -1) towards a wall (z = -12) that rises
// to y = 3: the floor's reflections show the wall near the horizon and the sky below.
struct FloorAndWall {
  static constexpr int w = 64, h = 48;
  std::unique_ptr<RayTracer> tracer;
  glm::dmat4 clipFromView;
  FloorAndWall() {
    Scene s;
    s.materials.push_back(Material{});
    s.meshes.push_back(makeQuad({0, -1, -6}, {40, 12}, {0, 1, 0}, 0));
    s.meshes.push_back(makeQuad({0, 1, -12}, {40, 4}, {0, 0, 1}, 0));
    Camera cam;
    cam.eye = {0, 0, 0};
    cam.target = {0, -0.35, -1};
    cam.fovyDegrees = 60;
    auto rt = RayTracer::create(s, cam.viewFromWorld());
    EXPECT_TRUE(rt) << rt.error();
    tracer = std::move(rt.value());
    clipFromView = cam.clipFromView(DepthMode::Reversed, double(w) / h);
  }
  static Image image(int channels, float value) {
    return Image{w, h, channels, std::vector<float>(static_cast<size_t>(w) * h * channels, value)};
  }
};

// The radiance callback gets each visible hit itself (glossyTruthFor shades that exact point): the
// floor's lobe can only reach the wall and the wall's only the floor (both are planes), so with
// red for a wall hit and blue for a floor hit each pixel's mean is pure red or pure blue.
TEST(GlossyTruth, EachVisibleHitIsShadedWhereItLies) {
  FloorAndWall f;
  const std::vector<std::uint8_t> all(static_cast<size_t>(f.w) * f.h, 1);
  const GlossyRadianceAt byMesh = [](const RayTracer::Hit& hit, glm::vec3, glm::vec2) {
    return hit.mesh == 1 ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
  };
  const GlossyTruth g = computeGlossyTruth(*f.tracer, f.clipFromView, byMesh, FloorAndWall::image(1, 0.4f), all, 64);
  ASSERT_EQ(g.width, f.w);
  ASSERT_EQ(g.height, f.h);
  size_t red = 0, blue = 0;
  for (size_t p = 0; p < g.radiance.size(); ++p) {
    if (!(g.visibleShare[p] > 0.0f)) continue;
    const glm::vec3 c = g.radiance[p];
    const bool isRed = std::abs(c.r - 1.0f) < 1e-5f && c.b == 0.0f, isBlue = c.r == 0.0f && std::abs(c.b - 1.0f) < 1e-5f;
    EXPECT_TRUE(isRed || isBlue) << "pixel " << p << ": " << c.r << " " << c.g << " " << c.b;
    red += isRed;
    blue += isBlue;
  }
  EXPECT_GT(red, 100u) << "floor pixels reflecting the wall";
  EXPECT_GT(blue, 10u) << "wall pixels reflecting the floor";
}

// Under a colour the same everywhere the lobe's mean is that colour, whatever it reaches, and its
// two halves agree.
TEST(GlossyTruth, UniformColourIsItsOwnMean) {
  FloorAndWall f;
  Image color = FloorAndWall::image(3, 0.0f);
  for (size_t p = 0; p < color.pixels.size() / 3; ++p) color.pixels[p * 3] = 0.25f, color.pixels[p * 3 + 1] = 0.5f;
  const std::vector<std::uint8_t> all(static_cast<size_t>(FloorAndWall::w) * FloorAndWall::h, 1);
  const GlossyTruth g = computeGlossyTruth(*f.tracer, f.clipFromView, color, FloorAndWall::image(1, 0.4f), all, 64);
  size_t known = 0;
  for (size_t p = 0; p < g.radiance.size(); ++p) {
    if (!(g.visibleShare[p] > 0.0f)) continue;
    ++known;
    EXPECT_NEAR(g.radiance[p].x, 0.25f, 1e-5f);
    EXPECT_NEAR(g.radiance[p].y, 0.5f, 1e-5f);
    EXPECT_NEAR(g.radiance[p].z, 0.0f, 1e-6f);
    EXPECT_LT(glm::length(g.halfSpread[p]), 1e-5f);
  }
  EXPECT_GT(known, 300u);
}

// A lobe 0.03 rough is all but a mirror: its radiance is the colour at the mirror truth's hit, and
// what it knows is what the mirror truth classes visible (the wall) or not (the sky).
TEST(GlossyTruth, NearlyMirrorLobeMatchesTheMirrorTruth) {
  FloorAndWall f;
  Image color = FloorAndWall::image(3, 0.0f);  // a gradient: a misplaced sample shows
  for (int y = 0; y < FloorAndWall::h; ++y)
    for (int x = 0; x < FloorAndWall::w; ++x) {
      color.at(x, y, 0) = float(x) / FloorAndWall::w;
      color.at(x, y, 1) = float(y) / FloorAndWall::h;
    }
  const std::vector<std::uint8_t> all(static_cast<size_t>(FloorAndWall::w) * FloorAndWall::h, 1);
  const GlossyTruth g = computeGlossyTruth(*f.tracer, f.clipFromView, color, FloorAndWall::image(1, 0.03f), all, 32);
  const GroundTruth mirror = computeGroundTruth(*f.tracer, f.clipFromView, FloorAndWall::w, FloorAndWall::h, all);
  size_t visible = 0, escaped = 0, partlyKnown = 0;
  for (size_t p = 0; p < g.radiance.size(); ++p) {
    const TruthPixel& t = mirror.pixels[p];
    if (t.cls == TruthClass::Visible && g.visibleShare[p] > 0.99f) {
      ++visible;
      const glm::vec3 expected = sampleBilinear(color, t.uvHit);
      // alpha = 0.0009: the lobe spreads its rays over a few hundredths of a pixel here.
      EXPECT_NEAR(g.radiance[p].x, expected.x, 0.01f) << p;
      EXPECT_NEAR(g.radiance[p].y, expected.y, 0.01f) << p;
    }
    if (t.cls == TruthClass::Escaped && g.visibleShare[p] >= 0.0f) {
      ++escaped;
      partlyKnown += g.visibleShare[p] > 0.0f;
      // The sky is not known to screen space (a pixel whose lobe grazes the wall's top edge
      // knows the few rays that meet it).
      EXPECT_LE(g.visibleShare[p], 0.1f);
    }
  }
  EXPECT_GT(visible, 200u);
  EXPECT_GT(escaped, 200u);
  EXPECT_LE(partlyKnown, escaped / 20) << "only pixels along the wall's edge";
}

// The reference's own error estimate (its two independently rotated halves) is an error
// measure: it shrinks with more samples, and it predicts how far a 64-ray reference lies from a
// 1024-ray one.
TEST(GlossyTruth, ItsErrorEstimateShrinksWithSamplesAndPredictsTheError) {
  FloorAndWall f;
  Image color = FloorAndWall::image(3, 0.0f);
  for (int y = 0; y < FloorAndWall::h; ++y)
    for (int x = 0; x < FloorAndWall::w; ++x) color.at(x, y, 0) = float((x / 4 + y / 4) % 2);  // a checkerboard
  const std::vector<std::uint8_t> all(static_cast<size_t>(FloorAndWall::w) * FloorAndWall::h, 1);
  const Image rough = FloorAndWall::image(1, 0.3f);
  const GlossyTruth coarse = computeGlossyTruth(*f.tracer, f.clipFromView, color, rough, all, 64);
  const GlossyTruth fine = computeGlossyTruth(*f.tracer, f.clipFromView, color, rough, all, 1024);
  double noiseCoarse = 0, noiseFine = 0, actual = 0;
  size_t n = 0;
  for (size_t p = 0; p < coarse.radiance.size(); ++p) {
    if (!(coarse.visibleShare[p] > 0.5f && fine.visibleShare[p] > 0.5f)) continue;
    noiseCoarse += coarse.halfSpread[p].x * coarse.halfSpread[p].x;
    noiseFine += fine.halfSpread[p].x * fine.halfSpread[p].x;
    const double d = coarse.radiance[p].x - fine.radiance[p].x;
    actual += d * d;
    ++n;
  }
  ASSERT_GT(n, 200u);
  noiseCoarse = std::sqrt(noiseCoarse / n), noiseFine = std::sqrt(noiseFine / n), actual = std::sqrt(actual / n);
  std::printf("%zu pixels: estimated error %.5f (64 rays), %.5f (1024); 64 against 1024: %.5f\n", n, noiseCoarse,
              noiseFine, actual);
  EXPECT_GT(noiseCoarse, 1e-3);
  EXPECT_LT(noiseFine, noiseCoarse / 3.0);  // 16x the rays: 4x less at the Monte Carlo rate, more when stratified
  EXPECT_GT(actual, noiseCoarse / 3.0);
  EXPECT_LT(actual, noiseCoarse * 3.0);
}

// Scoring: only pixels at least as rough as asked and mostly on screen count; an output without
// coverage counts as missing, an exact one scores zero error.
TEST(GlossyTruth, ScoresOnlyKnownGlossyPixels) {
  GlossyTruth t;
  t.width = 4;
  t.height = 1;
  t.samples = 8;
  t.radiance = {glm::vec3(0.5f), glm::vec3(0.5f), glm::vec3(0.5f), glm::vec3(0.5f)};
  t.halfSpread.assign(4, glm::vec3(0.0f));
  t.visibleShare = {1.0f, 1.0f, 0.5f, -1.0f};   // the third mostly off screen, the fourth not traced
  t.roughness = {0.3f, 0.05f, 0.3f, 0.3f};      // the second too smooth to count
  Image exact{4, 1, 4, {0.5f, 0.5f, 0.5f, 1.0f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}};
  GlossyMetrics m = compareGlossy(t, exact);
  EXPECT_EQ(m.scored, 1u);
  EXPECT_NEAR(m.rmse, 0.0, 1e-9);
  EXPECT_EQ(m.uncovered, 0.0);
  // Premultiplied: rgb 0.25 at coverage 0.5 is radiance 0.5.
  Image half{4, 1, 4, {0.25f, 0.25f, 0.25f, 0.5f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}};
  EXPECT_NEAR(compareGlossy(t, half).rmse, 0.0, 1e-7);
  Image none = FloorAndWall::image(4, 0.0f);
  none.width = 4, none.height = 1, none.pixels.assign(16, 0.0f);
  m = compareGlossy(t, none);
  EXPECT_EQ(m.uncovered, 1.0);
  EXPECT_NEAR(m.rmse, 0.5, 1e-6);
  EXPECT_NEAR(m.relativeRmse, 1.0, 1e-6);
}

}  // namespace
