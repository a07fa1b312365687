// Temporal reuse: history through FrameInputs::previousClipFromView, the chain broken by anything
// that makes the stored frame not the host's previous one, and bad inputs refused.
#include <algorithm>
#include <cmath>

#include "gl/gl_fixture.hpp"
#include "sslr/sslr.hpp"
#include "sslr_host/gbuffer.hpp"

using namespace sslr;
using namespace sslr::host;

namespace {

constexpr int W = 96, H = 54;

struct Sequence {
  std::unique_ptr<GBuffer> gbuffer;
  std::unique_ptr<GpuScene> gpu;
  std::unique_ptr<Context> ctx;
  Camera camera;
  glm::dmat4 previousClipFromWorld{0.0};
  explicit Sequence(const char* sceneName = "mirror-room") {
    GBufferOptions o;
    o.width = W;
    o.height = H;
    gbuffer = std::move(GBuffer::create(o).value());
    auto s = makeBuiltinScene(sceneName);
    camera = *s.value().camera;
    gpu = std::make_unique<GpuScene>(s.value());
    ContextDesc d{W, H, HeadlessContext::getProcAddress(), {}};
    ctx = std::move(Context::create(d).value());
  }
  // Renders and dispatches one frame; the previous frame's matrices go in as the host would.
  Status frame(Settings s, glm::dvec2 jitterPx) {
    if (Status st = gbuffer->render(*gpu, camera, jitterPx); !st) return st;
    FrameInputs in = gbuffer->frameInputs();
    in.previousClipFromView = previousClipFromWorld * glm::inverse(gbuffer->viewFromWorld());
    if (previousClipFromWorld == glm::dmat4(0.0)) in.previousClipFromView = gbuffer->clipFromView();
    previousClipFromWorld = gbuffer->clipFromView() * gbuffer->viewFromWorld();
    return ctx->dispatch(in, s);
  }
  Image resolved() const { return readTexture(ctx->resolvedTexture(), W, H, 4); }
};

// Half resolution answers each 2x2 quad from a ray of a pixel that rotates per frame, so a static
// view changes from frame to frame; temporal reuse damps that. If the reprojection or the
// history keys were wrong, no history would be used and the change would stay the same.
double halfResolutionFlicker(bool temporal) {
  Sequence q;
  Settings s;
  s.temporal.enabled = temporal;
  s.halfResolution = true;
  double change = 0.0;
  Image previous;
  for (int i = 0; i < 8; ++i) {
    EXPECT_TRUE(q.frame(s, {0.0, 0.0}));
    Image now = q.resolved();
    if (i >= 4)
      for (size_t k = 0; k < now.pixels.size(); ++k) change += std::abs(now.pixels[k] - previous.pixels[k]);
    previous = std::move(now);
  }
  return change;
}

class Temporal : public sslr::test::GlTest {};

TEST_F(Temporal, HistoryDampsHalfResolutionFlicker) {
  const double without = halfResolutionFlicker(false), with = halfResolutionFlicker(true);
  std::printf("half resolution, static view, frame-to-frame change: %.2f without, %.2f with temporal reuse\n",
              without, with);
  EXPECT_GT(without, 10.0) << "the rotating quad pixel should change the reflection";
  // Weight 0.8 cuts a change that history can average to about 0.2x (measured 369.5 -> 66.6:
  // 0.18x); unused or clamped history would leave it near 1x.
  EXPECT_LT(with, 0.5 * without);
}

// A static frame repeated: the history equals the current output, so the output never drifts.
TEST_F(Temporal, StaticFramesStayPut) {
  Sequence q;
  Settings plain, temporal;
  temporal.temporal.enabled = true;
  ASSERT_TRUE(q.frame(plain, {0.0, 0.0}));
  const Image reference = q.resolved();
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(q.frame(temporal, {0.0, 0.0}));
  const Image out = q.resolved();
  for (size_t k = 0; k < out.pixels.size(); ++k)
    ASSERT_NEAR(out.pixels[k], reference.pixels[k], 2e-3f * std::max(1.0f, reference.pixels[k])) << k;
}

// The first temporal frame, and the first after a frame without temporal reuse, a failed dispatch
// or a resize, uses no history: it equals the plain output exactly.
TEST_F(Temporal, BrokenChainsUseNoHistory) {
  Sequence q;
  Settings plain, temporal;
  temporal.temporal.enabled = true;
  ASSERT_TRUE(q.frame(plain, {0.3, -0.2}));
  const Image reference = q.resolved();
  auto expectPlain = [&](const char* when) {
    ASSERT_TRUE(q.frame(temporal, {0.3, -0.2})) << when;
    EXPECT_EQ(q.resolved().pixels, reference.pixels) << when;
  };
  expectPlain("first temporal frame");
  ASSERT_TRUE(q.frame(temporal, {-0.3, 0.2}));
  ASSERT_TRUE(q.frame(plain, {0.0, 0.0}));
  expectPlain("after a frame without temporal reuse");
  ASSERT_TRUE(q.frame(temporal, {-0.3, 0.2}));
  Settings bad = temporal;
  bad.adaptiveL.maxIterations = -1;
  EXPECT_FALSE(q.frame(bad, {0.0, 0.0}));
  expectPlain("after a failed dispatch");
  ASSERT_TRUE(q.frame(temporal, {-0.3, 0.2}));
  ASSERT_TRUE(q.ctx->resize(W / 2, H / 2));
  ASSERT_TRUE(q.ctx->resize(W, H));
  expectPlain("after a resize");
}

// Host motion vectors replace the matrix reprojection where given: zero motion on a still camera
// finds the same history as the matrices; motion that points off the screen finds none (the
// plain output, bit for bit).
TEST_F(Temporal, MotionVectorsChooseWhereHistoryIsRead) {
  auto run = [](bool withMotion, glm::vec2 motion) {
    Sequence q;
    Settings s;
    s.temporal.enabled = true;
    s.halfResolution = true;  // a changing output, so that history shows
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RG16F, W, H);
    const float value[4] = {motion.x, motion.y, 0.0f, 0.0f};
    glClearTexImage(tex, 0, GL_RGBA, GL_FLOAT, value);
    for (int i = 0; i < 4; ++i) {
      EXPECT_TRUE(q.gbuffer->render(*q.gpu, q.camera));
      FrameInputs in = q.gbuffer->frameInputs();
      in.previousClipFromView = in.clipFromView;  // a still camera
      if (withMotion) in.motionTexture = tex;
      EXPECT_TRUE(q.ctx->dispatch(in, s));
    }
    glDeleteTextures(1, &tex);
    return q.resolved().pixels;
  };
  const auto matrices = run(false, {0.0f, 0.0f});
  const auto zeroMotion = run(true, {0.0f, 0.0f});
  // The matrices land within float rounding of the pixel centre, zero motion on it: the bilinear
  // weights differ in the last bits, the RGBA16F results by a rounding step at most.
  for (size_t k = 0; k < matrices.size(); ++k)
    ASSERT_NEAR(zeroMotion[k], matrices[k], 2e-3f * std::max(1.0f, matrices[k])) << k;
  // No history: each frame is its own half-resolution trace (frame 4's quad pixel).
  Sequence plain;
  Settings half;
  half.halfResolution = true;
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(plain.frame(half, {0.0, 0.0}));
  const auto offScreen = run(true, {5.0f, 5.0f});
  EXPECT_EQ(offScreen, plain.resolved().pixels);
  EXPECT_NE(offScreen, matrices);
  // Poisoned motion vectors find no history either, and spread nothing.
  EXPECT_EQ(run(true, {NAN, 0.0f}), plain.resolved().pixels);
  EXPECT_EQ(run(true, {INFINITY, -INFINITY}), plain.resolved().pixels);
}

TEST_F(Temporal, MissingOrBadInputsAreRefused) {
  Sequence q;
  ASSERT_TRUE(q.gbuffer->render(*q.gpu, q.camera));
  FrameInputs in = q.gbuffer->frameInputs();
  Settings s;
  s.temporal.enabled = true;
  // All zeros says "no previous frame": taken on the first frame and after a reset, where none
  // exists (nothing is reprojected), refused once a history does.
  Status st = q.ctx->dispatch(in, s);
  ASSERT_TRUE(st) << "the first temporal frame has no previous one: " << st.message();
  {
    Sequence given;  // the same first frame, given its own projection as the previous one
    ASSERT_TRUE(given.gbuffer->render(*given.gpu, given.camera));
    FrameInputs own = given.gbuffer->frameInputs();
    own.previousClipFromView = own.clipFromView;
    ASSERT_TRUE(given.ctx->dispatch(own, s));
    EXPECT_EQ(q.resolved().pixels, given.resolved().pixels);
  }
  st = q.ctx->dispatch(in, s);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("previousClipFromView"), std::string::npos) << st.message();
  in.historyReset = true;
  st = q.ctx->dispatch(in, s);
  EXPECT_TRUE(st) << "after a reset: " << st.message();
  in.historyReset = false;
  in.previousClipFromView = in.clipFromView;
  in.previousClipFromView[1][1] = NAN;
  st = q.ctx->dispatch(in, s);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("not finite"), std::string::npos) << st.message();
  in.previousClipFromView = in.clipFromView;
  s.temporal.historyWeight = 1.0f;
  st = q.ctx->dispatch(in, s);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("temporal.historyWeight"), std::string::npos) << st.message();
  s.temporal.historyWeight = 0.8f;
  GLuint oneChannel = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &oneChannel);
  glTextureStorage2D(oneChannel, 1, GL_R16F, W, H);
  in.motionTexture = oneChannel;
  st = q.ctx->dispatch(in, s);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("FrameInputs::motionTexture"), std::string::npos) << st.message();
  glDeleteTextures(1, &oneChannel);
  EXPECT_EQ(sslr::test::glContext()->glErrorCount(), 0);
}


}  // namespace

namespace {

// Settings::temporal.outputConfidence: historyConfidenceTexture() is history's share of each pixel.
// A still camera: history is trusted (historyWeight on the planar mirror floor) on nearly every
// reflective pixel from the second frame on (0 on the first: none yet). A box that stood in front
// of the floor and is gone in the next frame: inside where it was (its outline's pixels may blend
// the floor's history beside it), the floor has no history (its key was the box's), and the
// confidence is 0 there while it stays up elsewhere. A camera cut told by
// FrameInputs::historyReset: 0 everywhere, and the output is the plain first frame's.
TEST_F(Temporal, HistoryConfidenceSaysWhereHistoryWasUsed) {
  Sequence q;
  Settings s;
  s.temporal.enabled = true;
  s.temporal.outputConfidence = true;
  auto confidence = [&] { return readTexture(q.ctx->historyConfidenceTexture(), W, H, 1); };
  auto depth = [&] { return readTexture(q.gbuffer->depthTexture(), W, H, 1, GL_DEPTH_COMPONENT); };
  auto scene = makeBuiltinScene("mirror-room");
  ASSERT_TRUE(scene);
  Scene withBox = scene.value();
  withBox.meshes.push_back(makeBox({0.2, 0.5, 1.0}, {1.4, 1.0, 1.0}, 0));
  std::unique_ptr<GpuScene> plainScene = std::move(q.gpu);
  q.gpu = std::make_unique<GpuScene>(withBox);
  ASSERT_TRUE(q.frame(s, {0.0, 0.0}));
  ASSERT_NE(q.ctx->historyConfidenceTexture(), 0u);
  const Image first = confidence();
  EXPECT_EQ(*std::max_element(first.pixels.begin(), first.pixels.end()), 0.0f) << "no history on the first frame";
  const Image depthWithBox = depth();
  q.gpu = std::move(plainScene);
  ASSERT_TRUE(q.frame(s, {0.0, 0.0}));
  const Image depthNow = depth(), afterBox = confidence(), covered = q.resolved();
  auto changed = [&](int x, int y) {
    x = std::clamp(x, 0, W - 1);
    y = std::clamp(y, 0, H - 1);
    return depthWithBox.at(x, y, 0) != depthNow.at(x, y, 0);
  };
  size_t uncovered = 0, uncoveredTrusted = 0, stayed = 0, stayedTrusted = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (!(covered.at(x, y, 3) > 0.0f)) continue;
      bool inside = true;  // the box was at this pixel and at its eight neighbours
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) inside = inside && changed(x + dx, y + dy);
      const float c = afterBox.at(x, y, 0);
      if (inside) {
        ++uncovered;
        uncoveredTrusted += c > 0.0f;
      } else if (!changed(x, y)) {
        ++stayed;
        stayedTrusted += c > 0.5f;
      }
    }
  ASSERT_GT(uncovered, 20u) << "the box must have hidden some of the reflective floor";
  EXPECT_EQ(uncoveredTrusted, 0u) << "of " << uncovered << " pixels the box uncovered";
  EXPECT_GT(stayedTrusted, stayed * 8 / 10) << "of " << stayed;  // historyWeight 0.8 on the floor
  // A cut, told: no history anywhere, the output as a first frame's.
  Settings plain;
  Sequence fresh;
  ASSERT_TRUE(fresh.frame(plain, {0.0, 0.0}));
  q.camera = fresh.camera;
  q.previousClipFromWorld = glm::dmat4(0.0);  // (the host's matrices are the cut's business)
  ASSERT_TRUE(q.gbuffer->render(*q.gpu, q.camera));
  FrameInputs cut = q.gbuffer->frameInputs();
  cut.previousClipFromView = cut.clipFromView;
  cut.historyReset = true;
  ASSERT_TRUE(q.ctx->dispatch(cut, s));
  const Image afterCut = confidence();
  EXPECT_EQ(*std::max_element(afterCut.pixels.begin(), afterCut.pixels.end()), 0.0f);
  EXPECT_EQ(q.resolved().pixels, fresh.resolved().pixels) << "a reset frame is a first frame";
  // Off: no texture.
  Sequence off;
  Settings temporalOnly;
  temporalOnly.temporal.enabled = true;
  ASSERT_TRUE(off.frame(temporalOnly, {0.0, 0.0}));
  EXPECT_EQ(off.ctx->historyConfidenceTexture(), 0u);
}

// A curved mirror seen by a camera standing still: each surface point reprojects onto its own
// texel, so its history is its own reflection, not resampled, and takes the full historyWeight
// (sslrFindHistory's `still`), as a plane's does. Under the camera's motion of a resampled
// history, a curved pixel gets a quarter of it (docs/design-notes.md, "Temporal reuse").
TEST_F(Temporal, AStillCurvedMirrorTrustsItsOwnHistoryFully) {
  Settings s;
  s.temporal.enabled = true;
  s.temporal.outputConfidence = true;
  auto trustedShare = [](const Image& c, float level) {
    size_t used = 0, atLevel = 0;
    for (float v : c.pixels) {
      used += v > 0.0f;
      atLevel += v > 0.0f && std::abs(v - level) < 0.01f;
    }
    EXPECT_GT(used, 100u);
    return used ? double(atLevel) / double(used) : 0.0;
  };
  const float weight = s.temporal.historyWeight;
  Sequence still("curved-mirror");
  for (int i = 0; i < 2; ++i) ASSERT_TRUE(still.frame(s, {0.0, 0.0}));
  // (r8: the share is stored in steps of 1/255)
  EXPECT_GT(trustedShare(readTexture(still.ctx->historyConfidenceTexture(), W, H, 1), weight), 0.95) << "still";
  // The camera moved by a fraction of a pixel: resampled, a quarter on the curved mirror.
  Sequence moved("curved-mirror");
  ASSERT_TRUE(moved.frame(s, {0.0, 0.0}));
  moved.camera.eye += glm::dvec3(0.004, 0.0, 0.0);
  moved.camera.target += glm::dvec3(0.004, 0.0, 0.0);
  ASSERT_TRUE(moved.frame(s, {0.0, 0.0}));
  EXPECT_GT(trustedShare(readTexture(moved.ctx->historyConfidenceTexture(), W, H, 1), 0.25f * weight), 0.5) << "moved";
}

}  // namespace
