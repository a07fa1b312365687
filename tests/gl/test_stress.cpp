// Numerical stability stress matrix (measuring.md): every depth convention x near/far x field of
// view x viewport shape, orthographic and off-centre projections, far camera offsets. Pass
// criteria: no NaN/Inf in any output, loop counts within the cap, no GL error (fixture), and
// hit quality that does not depend on where the world origin is.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/gl_fixture.hpp"
#include "sslr_host/frame_renderer.hpp"
#include "sslr_host/ground_truth.hpp"

using namespace sslr;
using namespace sslr::host;

namespace {

size_t nonFiniteOutputs(FrameRenderer& r) {
  return countNonFinite(r.readReflection()) + countNonFinite(r.readResolved()) + countNonFinite(r.readHit()) +
         countNonFinite(r.readIterations()) + countNonFinite(r.readFinal());
}

float maxIterations(FrameRenderer& r) {
  float m = 0.0f;
  for (float v : r.readIterations().pixels) m = std::max(m, v);
  return m;
}

class Stress : public sslr::test::GlTest {};

TEST_F(Stress, DepthConventionsNearFarFovAndViewports) {
  auto scene = makeBuiltinScene("mirror-box");
  ASSERT_TRUE(scene);
  GpuScene gpu(scene.value());
  const DepthMode modes[] = {DepthMode::GlDefault, DepthMode::ZeroToOne, DepthMode::Reversed, DepthMode::ReversedInfinite};
  const std::pair<double, double> planes[] = {{0.01, 1e5}, {0.1, 1e3}, {1.0, 100.0}};
  const double fovs[] = {1.0, 10.0, 60.0, 120.0, 170.0};
  const std::pair<int, int> sizes[] = {{1, 1}, {1, 17}, {7, 3}, {40, 30}};
  Settings s;
  s.debug.outputs = true;
  int cases = 0;
  for (auto [w, h] : sizes)
    for (DepthMode mode : modes) {
      GBufferOptions o;
      o.width = w;
      o.height = h;
      o.depth = mode;
      auto r = FrameRenderer::create(o);
      ASSERT_TRUE(r) << r.error();
      for (auto [n, f] : planes)
        for (double fov : fovs)
          for (bool ortho : {false, true}) {
            if (ortho && fov != 60.0) continue;  // orthographic has no field of view
            Camera cam = *scene.value().camera;
            cam.nearPlane = n;
            cam.farPlane = f;
            cam.fovyDegrees = fov;
            cam.orthographic = ortho;
            cam.orthoHeight = 8.0;
            // The default (adaptive L with the hierarchical fallback) and the traversal alone.
            for (Method method : {Method::AdaptiveL, Method::HierarchicalDepth}) {
              s.method = method;
              const Status st = r.value()->render(gpu, cam, &s, {0.3, -0.2});  // off-centre too
              ASSERT_TRUE(st) << st.message();
              const std::string what = std::string(toString(mode)) + " " + std::to_string(w) + "x" +
                                       std::to_string(h) + " n=" + std::to_string(n) + " f=" + std::to_string(f) +
                                       " fov=" + std::to_string(fov) + (ortho ? " ortho" : "") +
                                       (method == Method::AdaptiveL ? " adaptive-l" : " hiz");
              ASSERT_EQ(nonFiniteOutputs(*r.value()), 0u) << what;
              // Adaptive L's cap plus the hierarchical traversal's: every loop is bounded.
              ASSERT_LE(maxIterations(*r.value()), float(s.adaptiveL.maxIterations + s.traversal.maxSteps)) << what;
              ++cases;
            }
          }
    }
  EXPECT_GT(cases, 400);
}

// The whole world (scene and camera) moved by a translation and a uniform scale about the origin.
Scene transformedScene(Scene s, glm::dvec3 offset, double scale = 1.0) {
  const glm::dmat4 newFromOld = glm::scale(glm::translate(glm::dmat4(1.0), offset), glm::dvec3(scale));
  for (Mesh& m : s.meshes) m.worldFromModel = newFromOld * m.worldFromModel;
  s.camera->eye = glm::dvec3(newFromOld * glm::dvec4(s.camera->eye, 1.0));
  s.camera->target = glm::dvec3(newFromOld * glm::dvec4(s.camera->target, 1.0));
  s.camera->nearPlane *= scale;
  s.camera->farPlane *= scale;
  return s;
}

TEST_F(Stress, HitsDoNotDependOnTheDistanceFromTheWorldOrigin) {
  auto base = makeBuiltinScene("mirror-box");
  ASSERT_TRUE(base);
  GBufferOptions o;
  o.width = 128;
  o.height = 96;
  auto r = FrameRenderer::create(o);
  ASSERT_TRUE(r);
  Settings s;
  s.debug.outputs = true;
  double recallAtOrigin = 0.0;
  for (double d : {0.0, 1e3, 1e5, 1e6}) {
    const Scene scene = transformedScene(base.value(), {d, 0.5 * d, -d});
    GpuScene gpu(scene);
    ASSERT_TRUE(r.value()->render(gpu, *scene.camera, &s));
    auto gt = groundTruthFor(scene, r.value()->gbuffer(), s);
    ASSERT_TRUE(gt) << gt.error();
    const HitMetrics m = compareHits(gt.value(), r.value()->readHit());
    std::printf("offset %.0e: recall@1px %.4f p95 %.3f px false hits %.4f\n", d, m.recall1px, m.p95ErrorPx, m.falseHitRate);
    if (d == 0.0) recallAtOrigin = m.recall1px;
    // View-space reconstruction: nothing may degrade with the offset (matrices are composed in
    // double and the tracer never sees world coordinates).
    EXPECT_NEAR(m.recall1px, recallAtOrigin, 0.005) << "offset " << d;
    EXPECT_LE(m.p95ErrorPx, 0.05) << "offset " << d;
    EXPECT_EQ(m.nonFinite, 0u);
  }
}

TEST_F(Stress, ImageDoesNotDependOnTheSceneUnit) {
  // A scene modelled in millimetres or kilometres must look the same (both weightings).
  auto base = makeBuiltinScene("mirror-room");
  ASSERT_TRUE(base);
  GBufferOptions o;
  o.width = 96;
  o.height = 54;
  auto r = FrameRenderer::create(o);
  ASSERT_TRUE(r);
  for (FresnelMode fresnel : {FresnelMode::Classic, FresnelMode::Schlick}) {
    Settings s;
    s.fresnel = fresnel;
    Image reference;
    for (double scale : {1.0, 1e-3, 1e-1, 1e2, 1e4}) {
      const Scene scene = transformedScene(base.value(), glm::dvec3(0.0), scale);
      GpuScene gpu(scene);
      ASSERT_TRUE(r.value()->render(gpu, *scene.camera, &s));
      const Image reflection = r.value()->readResolved();
      if (scale == 1.0) {
        reference = reflection;
        double energy = 0.0;
        for (float v : reference.pixels) energy += v;
        ASSERT_GT(energy, 1.0) << "the reference frame must have reflections";
        continue;
      }
      // Float rounding of the scaled transforms moves a few edge pixels; the rest is identical.
      const ImageDiff d = compareImages(reflection, reference, 1.0f / 255.0f);
      std::printf("%s scale %g: max diff %.5f, %zu pixels over 1/255\n",
                  fresnel == FresnelMode::Classic ? "classic" : "schlick", scale, d.maxAbs, d.pixelsOver);
      EXPECT_LE(double(d.pixelsOver) / (o.width * o.height), 0.002) << "scale " << scale;
      EXPECT_LT(d.meanAbs, 1e-3) << "scale " << scale;
    }
  }
}

}  // namespace
