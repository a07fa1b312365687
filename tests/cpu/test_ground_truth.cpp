// Ground truth (Embree) against analytic ray-plane and ray-box hits, the four reflection
// classes, and the hit metrics on synthetic inputs with known answers.
#include <gtest/gtest.h>

#include "sslr_host/ground_truth.hpp"
#include "sslr_host/reference_image.hpp"

using namespace sslr;
using namespace sslr::host;

namespace {

Scene planeAndBox() {
  Scene s;
  s.materials.push_back(Material{});
  s.meshes.push_back(makeQuad({0, 0, 0}, {10, 10}, {0, 1, 0}, 0));
  s.meshes.push_back(makeBox({0, 1, -3}, {2, 2, 2}, 0));
  return s;
}

TEST(RayTracer, MatchesAnalyticPlaneAndBoxHits) {
  auto rt = RayTracer::create(planeAndBox(), glm::dmat4(1.0));  // view = world
  ASSERT_TRUE(rt) << rt.error();
  // Straight down onto the plane from (1, 2, 1): t = 2, normal +y.
  auto h = rt.value()->intersect({1, 2, 1}, {0, -1, 0});
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 2.0f, 1e-5f);
  EXPECT_NEAR(h.vsNormal.y, 1.0f, 1e-5f);
  // Towards -z at height 1: the box's front face at z = -2, t = 2 + 2 = 4 from z = 2.
  h = rt.value()->intersect({0.3f, 1.0f, 2.0f}, {0, 0, -1});
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 4.0f, 1e-5f);
  EXPECT_NEAR(h.vsNormal.z, 1.0f, 1e-5f);
  // Upwards: nothing.
  EXPECT_FALSE(rt.value()->intersect({0, 1, 5}, {0, 1, 0}).hit);
  // Occlusion up to tFar.
  EXPECT_TRUE(rt.value()->occluded({0.3f, 1.0f, 2.0f}, {0, 0, -1}, 10.0f));
  EXPECT_FALSE(rt.value()->occluded({0.3f, 1.0f, 2.0f}, {0, 0, -1}, 3.9f));
}

TEST(GroundTruth, ClassifiesVisibleOccludedOffScreenAndEscaped) {
  // Camera at the origin looking down -z over a mirror floor at y = -1 with a box ahead.
  Scene s;
  s.materials.push_back(Material{});
  s.meshes.push_back(makeQuad({0, -1, -10}, {40, 40}, {0, 1, 0}, 0));
  s.meshes.push_back(makeBox({0, 0, -8}, {2, 2, 2}, 0));         // in view: reflections visible
  s.meshes.push_back(makeBox({0, -0.5, -4}, {0.6, 0.5, 0.6}, 0));  // low box occluding the big box
  auto rt = RayTracer::create(s, glm::dmat4(1.0));
  ASSERT_TRUE(rt);
  Camera cam;
  cam.eye = {0, 0, 0};
  cam.target = {0, -0.2, -1};
  cam.fovyDegrees = 60;
  const int w = 64, h = 48;
  auto rtView = RayTracer::create(s, cam.viewFromWorld());
  ASSERT_TRUE(rtView);
  const glm::dmat4 P = cam.clipFromView(DepthMode::Reversed, double(w) / h);
  std::vector<std::uint8_t> all(static_cast<size_t>(w) * h, 1);
  const GroundTruth gt = computeGroundTruth(*rtView.value(), P, w, h, all);
  EXPECT_GT(gt.count(TruthClass::Visible), 0u);
  EXPECT_GT(gt.count(TruthClass::Occluded), 0u) << "the low box hides part of the big box's reflection";
  EXPECT_GT(gt.count(TruthClass::Escaped), 0u) << "floor far away reflects the empty sky";
  EXPECT_GT(gt.count(TruthClass::OffScreen), 0u) << "the box's top reflects out of the frame";
  // A floor pixel straight below the box: its reflection hits the box's front face on screen.
  // Pick the pixel whose primary ray hits the floor at z = -6.5 under the box centre.
  for (const TruthPixel& p : gt.pixels)
    if (p.cls == TruthClass::Visible) {
      EXPECT_GE(p.uvHit.x, 0.0f);
      EXPECT_LE(p.uvHit.x, 1.0f);
      EXPECT_GT(p.length, 0.0f);
    }
}

// A shelf just above the eye is seen edge-on: thinner than a pixel, so no pixel shows it, yet the
// floor mirror's rays hit its underside in plain view of the camera. Those visible hits are
// "unshown" (no screen-space method can find them); raised well above the eye, it is shown.
TEST(GroundTruth, VisibleHitsNoPixelShowsAreUnshown) {
  auto truthWithShelfAt = [](double shelfY, glm::dvec2& shelfUv) {
    Scene s;
    s.materials.push_back(Material{});
    s.meshes.push_back(makeQuad({0, 0, -10}, {40, 40}, {0, 1, 0}, 0));    // mirror floor
    s.meshes.push_back(makeQuad({0, 5, -12}, {40, 10}, {0, 0, 1}, 0));    // back wall
    s.meshes.push_back(makeQuad({0, shelfY, -4.5}, {6, 3}, {0, -1, 0}, 0));  // shelf, facing down
    Camera cam;
    cam.eye = {0, 1, 0};
    cam.target = {0, 0.6, -5};
    cam.fovyDegrees = 60;
    const int w = 64, h = 48;
    auto rt = RayTracer::create(s, cam.viewFromWorld());
    EXPECT_TRUE(rt);
    const glm::dmat4 clipFromView = cam.clipFromView(DepthMode::Reversed, double(w) / h);
    const glm::dvec4 clip = clipFromView * cam.viewFromWorld() * glm::dvec4(0, shelfY, -4.5, 1);
    shelfUv = glm::dvec2(clip) / clip.w * 0.5 + 0.5;
    return computeGroundTruth(*rt.value(), clipFromView, w, h, std::vector<std::uint8_t>(size_t(w) * h, 1));
  };
  glm::dvec2 shelfUv;
  const GroundTruth sliver = truthWithShelfAt(1.01, shelfUv);
  size_t unshown = 0;
  for (const TruthPixel& p : sliver.pixels)
    if (p.cls == TruthClass::Visible && !p.shown) {
      ++unshown;
      EXPECT_NEAR(p.uvHit.y * sliver.height, shelfUv.y * sliver.height, 1.5) << "an unshown hit off the shelf";
    }
  EXPECT_GT(unshown, 10u) << "the floor reflects the shelf's underside";
  const GroundTruth raised = truthWithShelfAt(1.6, shelfUv);
  size_t raisedVisible = 0, raisedUnshown = 0;
  for (const TruthPixel& p : raised.pixels) {
    raisedVisible += p.cls == TruthClass::Visible;
    raisedUnshown += p.cls == TruthClass::Visible && !p.shown;
  }
  EXPECT_GT(raisedVisible, 100u);
  EXPECT_EQ(raisedUnshown, 0u) << "a shelf several pixels tall is shown wherever the floor reflects it";
}

TEST(HitMetrics, KnownAnswers) {
  GroundTruth gt;
  gt.width = 10;
  gt.height = 1;
  gt.pixels.resize(10);
  Image hit;
  hit.width = 10;
  hit.height = 1;
  hit.channels = 4;
  hit.pixels.assign(40, 0.0f);
  // 4 visible pixels: errors 0, 0.5, 1.5, 3 px (x only) -> recall1 = 0.5, recall2 = 0.75, recall4 = 1.
  const float errs[4] = {0.0f, 0.5f, 1.5f, 3.0f};
  for (int i = 0; i < 4; ++i) {
    gt.pixels[i].cls = TruthClass::Visible;
    gt.pixels[i].uvHit = {0.5f, 0.5f};
    hit.pixels[i * 4 + 0] = 0.5f + errs[i] / 10.0f;
    hit.pixels[i * 4 + 1] = 0.5f;
    hit.pixels[i * 4 + 2] = 1.0f;
  }
  // 4 negatives, one of which reports a hit -> false-hit rate 0.25.
  gt.pixels[4].cls = TruthClass::Occluded;
  gt.pixels[5].cls = TruthClass::OffScreen;
  gt.pixels[6].cls = TruthClass::Escaped;
  gt.pixels[7].cls = TruthClass::Escaped;
  hit.pixels[6 * 4 + 2] = 0.9f;
  hit.pixels[7 * 4 + 2] = 0.4f;  // below the 0.5 threshold: not a reported hit
  // One NaN pixel outside any class still counts as non-finite output.
  hit.pixels[9 * 4 + 0] = NAN;
  const HitMetrics m = compareHits(gt, hit);
  EXPECT_EQ(m.visible, 4u);
  EXPECT_DOUBLE_EQ(m.recall1px, 0.5);
  EXPECT_DOUBLE_EQ(m.recall2px, 0.75);
  EXPECT_DOUBLE_EQ(m.recall4px, 1.0);
  EXPECT_NEAR(m.medianErrorPx, 1.5, 1e-5);
  EXPECT_NEAR(m.p95ErrorPx, 3.0, 1e-5);
  EXPECT_DOUBLE_EQ(m.falseHitRate, 0.25);
  EXPECT_EQ(m.nonFinite, 1u);
  EXPECT_EQ(m.unshown, 0u);
  EXPECT_DOUBLE_EQ(m.recallShown1px, 0.5);
  // The exact hit's pixel shown by no pixel: it leaves the shown recall (1 of 3 within 1 px).
  gt.pixels[0].shown = false;
  const HitMetrics u = compareHits(gt, hit);
  EXPECT_EQ(u.unshown, 1u);
  EXPECT_DOUBLE_EQ(u.recall1px, 0.5) << "recall still counts every visible pixel";
  EXPECT_DOUBLE_EQ(u.recallShown1px, 1.0 / 3.0);
}

// The composite's image error: an analytic RMSE over the scored pixels only, and no number at all
// (NaN, not a perfect 0) where a frame has no mirror pixel to score.
TEST(CompositeImageError, ScoresOnlyMirrorPixelsAndNothingWithoutThem) {
  ReferenceImage reference;
  reference.composite = Image{2, 1, 3, {0.5f, 0.5f, 0.5f, 0.0f, 0.0f, 0.0f}};
  reference.scored = {1, 0};
  reference.scoredCount = 1;
  // The scored pixel off by (0.1, 0.2, 0.2): RMSE sqrt(0.09 / 3); the unscored one off by 1.
  const Image composite{2, 1, 3, {0.6f, 0.7f, 0.3f, 1.0f, 1.0f, 1.0f}};
  const ImageError e = compositeError(reference, composite);
  EXPECT_EQ(e.pixels, 1u);
  EXPECT_NEAR(e.rmse, std::sqrt(0.09 / 3.0), 1e-6);
  EXPECT_NEAR(e.psnr, 20.0 * std::log10(1.0 / std::sqrt(0.03)), 1e-4);

  reference.scored = {0, 0};
  reference.scoredCount = 0;
  const ImageError none = compositeError(reference, composite);
  EXPECT_EQ(none.pixels, 0u);
  EXPECT_FALSE(std::isfinite(none.rmse));
  EXPECT_FALSE(std::isfinite(none.psnr));
}

// The composite error by what the method reported, on six pixels with known answers: a hit within
// 1 px, a wrong hit (reported where the truth is occluded), a guess below the reporting threshold,
// an escaped ray left alone, an unscored pixel that counts nowhere and a visible reflection missed.
// The wrong hit's pixel is also scored as the colour a miss would have shown there. The same error
// split by the truth's class.
TEST(CompositeBreakdown, SortsTheErrorByWhatWasReportedAndByTheTruthAndScoresWrongHitsAsMisses) {
  GroundTruth gt;
  gt.width = 6;
  gt.height = 1;
  gt.pixels.resize(6);
  gt.pixels[0].cls = TruthClass::Visible;
  gt.pixels[0].uvHit = {0.5f, 0.5f};
  gt.pixels[1].cls = TruthClass::Occluded;
  gt.pixels[2].cls = TruthClass::Visible;
  gt.pixels[2].uvHit = {0.1f, 0.5f};
  gt.pixels[3].cls = TruthClass::Escaped;
  gt.pixels[4].cls = TruthClass::Visible;
  gt.pixels[5].cls = TruthClass::Visible;
  gt.pixels[5].uvHit = {0.7f, 0.5f};
  Image hit{6, 1, 4, std::vector<float>(24, 0.0f)};
  const float reported[6][3] = {{0.55f, 0.5f, 1.0f},   // 0.3 px off: within 1 px
                                {0.3f, 0.5f, 0.9f},    // a false hit
                                {0.1f, 0.5f, 0.4f},    // below the reporting threshold: a guess
                                {0.0f, 0.0f, 0.0f},    // nothing
                                {0.9f, 0.5f, 1.0f},    // unscored
                                {0.0f, 0.0f, 0.0f}};   // nothing: a miss
  for (int p = 0; p < 6; ++p)
    for (int c = 0; c < 3; ++c) hit.pixels[p * 4 + c] = reported[p][c];
  ReferenceImage reference;
  reference.composite = Image{6, 1, 3, std::vector<float>(18, 0.5f)};
  reference.scored = {1, 1, 1, 1, 0, 1};
  reference.scoredCount = 5;
  // Squared errors (sum over RGB): 0.03, 0.12, 0.27, 0.48, 0.0075; the unscored pixel's 3 counts
  // nowhere.
  const float off[6] = {0.1f, 0.2f, 0.3f, 0.4f, 1.0f, 0.05f};
  Image composite{6, 1, 3, {}};
  for (float o : off) composite.pixels.insert(composite.pixels.end(), {0.5f + o, 0.5f + o, 0.5f + o});
  // What a miss shows at the wrong hit's pixel: 0.1 off in one channel (squared error 0.01).
  Image colour{6, 1, 3, std::vector<float>(18, 0.5f)};
  colour.pixels[1 * 3 + 0] = 0.6f;

  const CompositeBreakdown b = compositeBreakdown(reference, composite, gt, hit, colour);
  EXPECT_EQ(b.hit.pixels, 1u);
  EXPECT_EQ(b.wrong.pixels, 1u);
  EXPECT_EQ(b.guessed.pixels, 1u) << "confidence 0.4 blends a guess in: neither a hit nor a miss";
  EXPECT_EQ(b.missed.pixels, 1u);
  EXPECT_EQ(b.unreachable.pixels, 1u);
  const double total = 0.03 + 0.12 + 0.27 + 0.48 + 0.0075;
  EXPECT_NEAR(b.hit.rmse, 0.1, 1e-6);
  EXPECT_NEAR(b.wrong.rmse, 0.2, 1e-6);
  EXPECT_NEAR(b.guessed.rmse, 0.3, 1e-6);
  EXPECT_NEAR(b.missed.rmse, 0.05, 1e-6);
  EXPECT_NEAR(b.unreachable.rmse, 0.4, 1e-6);
  EXPECT_NEAR(b.hit.share, 0.03 / total, 1e-6);
  EXPECT_NEAR(b.wrong.share, 0.12 / total, 1e-6);
  EXPECT_NEAR(b.guessed.share, 0.27 / total, 1e-6);
  EXPECT_NEAR(b.hit.share + b.wrong.share + b.guessed.share + b.missed.share + b.unreachable.share, 1.0, 1e-9);
  EXPECT_EQ(b.wrongAsMisses.pixels, 1u);
  EXPECT_NEAR(b.wrongAsMisses.rmse, std::sqrt(0.01 / 3.0), 1e-6) << "the wrong pixel as a miss: the colour there";
  EXPECT_NEAR(b.wrongAsMisses.share, 0.01 / total, 1e-6);
  EXPECT_LT(b.wrongAsMisses.rmse, b.wrong.rmse) << "here a miss would have served the pixel better";
  // By where the truth lies: pixels 0, 2 and 5 on the screen (0.03 + 0.27 + 0.0075), 1 a hidden
  // side (0.12), 3 escaped (0.48), none off the screen.
  EXPECT_EQ(b.byTruth.visible.pixels, 3u);
  EXPECT_NEAR(b.byTruth.visible.rmse, std::sqrt((0.03 + 0.27 + 0.0075) / 9.0), 1e-6);
  EXPECT_NEAR(b.byTruth.visible.share, 0.3075 / total, 1e-6);
  EXPECT_EQ(b.byTruth.occluded.pixels, 1u);
  EXPECT_NEAR(b.byTruth.occluded.rmse, 0.2, 1e-6) << "the false hit's pixel counts where its truth lies";
  EXPECT_EQ(b.byTruth.offScreen.pixels, 0u);
  EXPECT_EQ(b.byTruth.offScreen.share, 0.0);
  EXPECT_EQ(b.byTruth.escaped.pixels, 1u);
  EXPECT_NEAR(b.byTruth.escaped.share, 0.48 / total, 1e-6);

  // No wrong hit: nothing to score as a miss.
  hit.pixels[1 * 4 + 2] = 0.0f;
  const CompositeBreakdown none = compositeBreakdown(reference, composite, gt, hit, colour);
  EXPECT_EQ(none.wrong.pixels, 0u);
  EXPECT_EQ(none.wrongAsMisses.pixels, 0u);
  EXPECT_EQ(none.wrongAsMisses.share, 0.0);
  EXPECT_EQ(none.unreachable.pixels, 2u) << "an occluded reflection not reported is unreachable";
}

// The references' colours as the G-buffer stores them (R11F_G11F_B10F): exact where the format
// is (small integers, powers of two), otherwise rounded towards zero to its 6 mantissa bits in red
// and green (less than one step: 2^-6 relative) and 5 in blue (2^-5), as glm packs them and Mesa
// stores them (test ReferenceShading: the stored shade is the G-buffer's colour exactly on 84-97%
// of the visible hits); stored again, unchanged.
TEST(StoredColor, IsTheColourBuffersValueTowardsZero) {
  EXPECT_EQ(asStoredColor(glm::vec3(1.0f, 0.5f, 4.0f)), glm::vec3(1.0f, 0.5f, 4.0f));
  EXPECT_EQ(asStoredColor(glm::vec3(0.0f)), glm::vec3(0.0f));
  for (float v = 0.013f; v < 300.0f; v *= 1.37f) {
    const glm::vec3 in(v, v * 1.11f, v * 0.93f);
    const glm::vec3 out = asStoredColor(in);
    for (int c = 0; c < 3; ++c) {
      EXPECT_LE(out[c], in[c]) << v << " channel " << c;
      EXPECT_GT(out[c], in[c] * (1.0f - (c == 2 ? 0.03125f : 0.015625f))) << v << " channel " << c;
    }
    EXPECT_EQ(asStoredColor(out), out) << v;
  }
  // 0.7044 is not a value of the format: 6 bits give steps of 2^-7 = 0.0078125 in [0.5, 1).
  EXPECT_EQ(asStoredColor(glm::vec3(0.7044f)).r, 0.703125f);
}

}  // namespace

// A reflected ray that meets a box's back face (turned away from the camera) brings back that face
// lit on its own side and its fallback specular seen along the ray, not the inside of the solid lit
// from the camera's side. Camera at the origin (view = world) looking down -z at a unit box around
// (0, 0, -6); the light travels along +z, so only the back face (z = -7, normal -z) is lit by it.
// Metal, base colour 0.5: reflectance 0.5, diffuse share 0.15, ambient 0.18 on a vertical face.
TEST(ReferenceShading, ReflectedBackFaceIsLitOnTheSideTheRayMeets) {
  Scene s;
  Material metal;
  metal.baseColor = glm::vec3(0.5f);
  metal.metallic = 1.0f;
  s.materials.push_back(metal);
  s.meshes.push_back(makeBox({0, 0, -6}, {2, 2, 2}, 0));
  s.lightDirection = {0.0f, 0.0f, 1.0f};
  s.background = glm::vec3(1.0f);
  auto rt = RayTracer::create(s, glm::dmat4(1.0));
  ASSERT_TRUE(rt) << rt.error();
  // From behind the box, up and towards the camera: meets z = -7 at (0, 0, -7) at 36.9 deg.
  const glm::vec3 dir(0.0f, 0.6f, 0.8f);
  const RayTracer::Hit back = rt.value()->intersect({0.0f, -2.25f, -10.0f}, dir);
  ASSERT_TRUE(back.hit);
  ASSERT_NEAR(back.vsPosition.z, -7.0f, 1e-5f);
  // Lit: 0.5 x 0.15 x (0.85 x 1 + 0.18) = 0.07725. Fallback specular along the ray: 0.5 x
  // 2.8 (1 - 0.8)^2 x the sky (the mirror direction (0, 0.6, -0.8) points up) = 0.056.
  const float expected = 0.07725f + 0.056f;
  for (bool cameraSees : {false, true}) {
    const glm::vec3 got = reflectedRadiance(s, back, dir, glm::dmat4(1.0), false, cameraSees);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected, 1e-5f) << "camera sees: " << cameraSees;
  }
  // The camera's side of that face (the solid's inside) is dark: ambient only, no Fresnel.
  const glm::vec3 fromCamera = shadeAsGBuffer(s, back, glm::dmat4(1.0), false);
  EXPECT_NEAR(fromCamera.r, 0.5f * 0.15f * 0.18f, 1e-5f);
  // The front face, which the camera sees on the side a ray from the camera's side meets: the
  // colour buffer's stored shade of it, as a screen-space method reads it.
  const glm::vec3 toFront = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
  const RayTracer::Hit front = rt.value()->intersect({0.0f, 0.0f, -2.0f}, toFront);
  ASSERT_TRUE(front.hit);
  ASSERT_NEAR(front.vsPosition.z, -5.0f, 1e-5f);
  EXPECT_EQ(reflectedRadiance(s, front, toFront, glm::dmat4(1.0), false, true),
            asStoredColor(shadeAsGBuffer(s, front, glm::dmat4(1.0), false)));
  // Off the screen or hidden: exact, seen along the ray.
  const glm::vec3 exact = reflectedRadiance(s, front, toFront, glm::dmat4(1.0), false, false);
  const glm::vec3 alongRay = shadeSeenFrom(s, front, glm::dmat4(1.0), -toFront);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(exact[c], alongRay[c], 1e-6f);
}
