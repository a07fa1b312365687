// Several views in the same dispatches (ContextDesc::views, integration.md "Stereo and
// multiview"): a context of N views given a layered G-buffer (2D arrays, layer v = view v, each
// view with its own matrices) writes into each layer of its outputs exactly what a one-view context
// given that layer as textures of its own writes, frame after frame; every bad input is refused
// with what is wrong.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl_fixture.hpp"
#include "sslr/sslr.hpp"
#include "sslr_host/gbuffer.hpp"
#include "sslr_host/frame_renderer.hpp"
#include "sslr_host/scene.hpp"
#include "sslr_host/views_renderer.hpp"

using namespace sslr;
using namespace sslr::host;

namespace {

constexpr int kW = 96, kH = 64;

std::unique_ptr<Context> makeViewsContext(int views, DeviceProfile device = DeviceProfile::Auto,
                                          TraversalPass pass = TraversalPass::Auto) {
  ContextDesc d;
  d.width = kW;
  d.height = kH;
  d.getProcAddress = HeadlessContext::getProcAddress();
  d.device = device;
  d.traversalPass = pass;
  d.views = views;
  auto c = Context::create(d);
  EXPECT_TRUE(c) << c.error();
  return c ? std::move(c.value()) : nullptr;
}

// Layer `layer` of a 2D array texture (or the texture itself, layer 0, when it is 2D).
Image readLayer(GLuint texture, int layer, int channels) {
  Image img;
  img.width = kW;
  img.height = kH;
  img.channels = channels;
  img.pixels.assign(static_cast<size_t>(kW) * kH * channels, 0.0f);
  if (texture == 0) return img;
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureSubImage(texture, 0, 0, 0, layer, kW, kH, 1, channels == 1 ? GL_RED : GL_RGBA, GL_FLOAT,
                       static_cast<GLsizei>(img.pixels.size() * sizeof(float)), img.pixels.data());
  return img;
}

size_t differing(const Image& a, const Image& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) n += a.pixels[i] != b.pixels[i];
  return n;
}

// A scene seen by `views` cameras side by side, 0.064 units apart: each camera's G-buffer in
// textures of its own, and the same G-buffers as 2D arrays (the tools' ViewsRenderer, which keeps
// them).
struct Views {
  std::unique_ptr<ViewsRenderer> renderer;
  std::vector<FrameInputs> ownInputs, layeredInputs;
};

std::unique_ptr<Views> makeViews(const char* sceneName, int views, const GBufferOptions& options = {},
                                 bool lastViewOrthographic = false) {
  auto scene = makeBuiltinScene(sceneName);
  EXPECT_TRUE(scene);
  if (!scene) return nullptr;
  GpuScene gpu(scene.value());
  GBufferOptions o = options;
  o.width = kW;
  o.height = kH;
  auto renderer = ViewsRenderer::create(o, views);
  EXPECT_TRUE(renderer) << renderer.error();
  if (!renderer) return nullptr;
  auto out = std::make_unique<Views>();
  out->renderer = std::move(renderer.value());
  std::vector<Camera> cameras = sideBySideCameras(*scene.value().camera, views, 0.064);
  if (lastViewOrthographic) {
    cameras.back().orthographic = true;
    cameras.back().orthoHeight = 7.0;
  }
  EXPECT_TRUE(out->renderer->render(gpu, cameras, nullptr));
  for (int v = 0; v < views; ++v) out->ownInputs.push_back(out->renderer->viewInputs(v));
  const auto layered = out->renderer->layeredInputs();
  out->layeredInputs.assign(layered.begin(), layered.end());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  return out;
}

// The composite (additive) of `view` into a kW x kH framebuffer cleared to zero, read back.
Image compositeOf(Context& ctx, int view) {
  CompositeOptions o;
  o.view = view;
  return sslr::test::compositeImage(ctx, kW, kH, o);
}

struct Case {
  const char* name;
  const char* scene;
  int views;
  Settings settings;
  int frames;
  DeviceProfile device;
  // Odd frames trace this rectangle of the textures (FrameInputs::viewport; width 0: the whole),
  // even frames the whole: each change starts a new area (outputs cleared, no history).
  Viewport oddFrames{};
  GBufferOptions gbuffer{};  // which inputs the G-buffers hand over (position, back-face depth)
  // Each view's projection shifted off centre by this much a view (an HMD's asymmetric frusta;
  // both contexts get the same matrices, so the comparison stays exact).
  double frustumShift = 0.0;
  TraversalPass pass = TraversalPass::Auto;  // ContextDesc::traversalPass
  // The last view orthographic, the others perspective: views that disagree on the projection's
  // kind get the programs that read it from the block, one-view contexts have it compiled in.
  bool lastViewOrthographic = false;
};

// Each view's outputs, frame after frame, against one-view contexts given that view's textures.
void expectLayersMatchOwnContexts(const Case& c) {
  SCOPED_TRACE(c.name);
  auto views = makeViews(c.scene, c.views, c.gbuffer, c.lastViewOrthographic);
  ASSERT_TRUE(views);
  auto layered = makeViewsContext(c.views, c.device, c.pass);
  ASSERT_TRUE(layered);
  std::vector<std::unique_ptr<Context>> own;
  for (int v = 0; v < c.views; ++v) {
    own.push_back(makeViewsContext(1, c.device, c.pass));
    ASSERT_TRUE(own.back());
  }
  size_t hits = 0;
  for (int frame = 0; frame < c.frames; ++frame) {
    // Temporal reuse: a still camera (each view's previous projection is its own).
    std::vector<FrameInputs> layeredIn = views->layeredInputs, ownIn = views->ownInputs;
    for (int v = 0; v < c.views; ++v) {
      layeredIn[v].previousClipFromView = layeredIn[v].clipFromView;
      ownIn[v].previousClipFromView = ownIn[v].clipFromView;
      if (frame % 2 == 1) layeredIn[v].viewport = ownIn[v].viewport = c.oddFrames;
      const double shift = c.frustumShift * (v % 2 == 0 ? -1.0 : 1.0);
      layeredIn[v].clipFromView[2][0] += shift;
      ownIn[v].clipFromView[2][0] += shift;
    }
    ASSERT_TRUE(layered->dispatch(std::span<const FrameInputs>(layeredIn), c.settings));
    for (int v = 0; v < c.views; ++v) ASSERT_TRUE(own[v]->dispatch(ownIn[v], c.settings));
    for (int v = 0; v < c.views; ++v) {
      SCOPED_TRACE("frame " + std::to_string(frame) + ", view " + std::to_string(v));
      EXPECT_EQ(differing(readLayer(layered->reflectionTexture(), v, 4), readLayer(own[v]->reflectionTexture(), 0, 4)), 0u);
      EXPECT_EQ(differing(readLayer(layered->resolvedTexture(), v, 4), readLayer(own[v]->resolvedTexture(), 0, 4)), 0u);
      if (c.settings.debug.outputs) {
        const Image hit = readLayer(layered->hitTexture(), v, 4);
        EXPECT_EQ(differing(hit, readLayer(own[v]->hitTexture(), 0, 4)), 0u);
        for (int i = 0; i < kW * kH; ++i) hits += hit.pixels[static_cast<size_t>(i) * 4 + 2] > 0.5f;
      }
      if (c.settings.hitDistance)
        EXPECT_EQ(differing(readLayer(layered->hitDistanceTexture(), v, 1), readLayer(own[v]->hitDistanceTexture(), 0, 1)), 0u);
      if (c.settings.temporal.outputConfidence)
        EXPECT_EQ(differing(readLayer(layered->historyConfidenceTexture(), v, 1),
                            readLayer(own[v]->historyConfidenceTexture(), 0, 1)),
                  0u);
    }
  }
  for (int v = 0; v < c.views; ++v) {
    SCOPED_TRACE("composite of view " + std::to_string(v));
    EXPECT_EQ(differing(compositeOf(*layered, v), compositeOf(*own[v], 0)), 0u);
  }
  if (c.settings.debug.outputs) {
    EXPECT_GT(hits, static_cast<size_t>(c.views * c.frames) * 300u);  // every view sees reflections
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

class MultiView : public sslr::test::GlTest {};

TEST_F(MultiView, EachLayerIsWhatAOneViewContextMakesOfItsTextures) {
  Settings debug;
  debug.debug.outputs = true;
  debug.hitDistance = true;
  Settings halfTemporal = debug;
  halfTemporal.halfResolution = true;
  halfTemporal.temporal.enabled = true;
  halfTemporal.temporal.outputConfidence = true;
  GBufferOptions withBackDepth;
  withBackDepth.withBackDepth = true;
  Settings stochastic = debug;
  stochastic.glossy.mode = GlossyMode::Stochastic;
  stochastic.temporal.enabled = true;
  const Case cases[] = {
      {"stereo, the default with its debug outputs", "mirror-room", 2, debug, 2, DeviceProfile::Auto},
      {"stereo, curved solids", "sphere-over-mirror-32", 2, debug, 1, DeviceProfile::Auto},
      {"stereo, half resolution and temporal reuse", "mirror-room", 2, halfTemporal, 3, DeviceProfile::Auto},
      {"stereo, Gpu profile, half resolution", "mirror-room", 2, halfTemporal, 2, DeviceProfile::Gpu},
      {"stereo, deferred traversal", "thin-objects", 2, debug, 1, DeviceProfile::Auto, {}, {}, 0.0, TraversalPass::Deferred},
      {"stereo, stochastic glossy", "glossy", 2, stochastic, 2, DeviceProfile::Auto},
      {"four views", "mirror-walls", 4, debug, 1, DeviceProfile::Auto},
      {"stereo in a viewport and out of it", "mirror-room", 2, halfTemporal, 4, DeviceProfile::Auto, {13, 7, 61, 43}},
      {"stereo with the measured back-face depth", "thin-objects", 2, debug, 1, DeviceProfile::Auto, {}, withBackDepth},
      {"stereo with asymmetric frusta", "mirror-room", 2, debug, 1, DeviceProfile::Auto, {}, {}, 0.15},
      {"a perspective and an orthographic view", "mirror-room", 2, debug, 1, DeviceProfile::Auto, {}, {}, 0.0,
       TraversalPass::Auto, true},
      {"the same, half resolution, Gpu profile", "mirror-room", 2, halfTemporal, 2, DeviceProfile::Gpu, {}, {}, 0.0,
       TraversalPass::Auto, true},
  };
  for (const Case& c : cases) expectLayersMatchOwnContexts(c);
}

TEST_F(MultiView, TheComparisonMethodsTraceEveryLayerAsTheirOwn) {
  GBufferOptions withPosition;
  withPosition.withPosition = true;  // the tutorial's method reads a position texture (an array here)
  for (Method m : {Method::ScreenSpaceDDA, Method::FidelityFxSssr, Method::HierarchicalDepth, Method::PositionBuffer}) {
    Settings s;
    s.debug.outputs = true;
    s.method = m;
    expectLayersMatchOwnContexts({"a comparison method", "mirror-corridor", 2, s, 1, DeviceProfile::Auto, {}, withPosition});
  }
}

TEST_F(MultiView, BadViewsAreRefusedWithWhatIsWrong) {
  for (int bad : {0, -1, kMaxViews + 1}) {
    ContextDesc d;
    d.width = kW;
    d.height = kH;
    d.getProcAddress = HeadlessContext::getProcAddress();
    d.views = bad;
    auto c = Context::create(d);
    ASSERT_FALSE(c);
    EXPECT_NE(c.error().find("ContextDesc views"), std::string::npos) << c.error();
  }
  auto views = makeViews("mirror-room", 2);
  ASSERT_TRUE(views);
  auto ctx = makeViewsContext(2);
  ASSERT_TRUE(ctx);
  EXPECT_EQ(ctx->views(), 2);
  const Settings s;
  auto refused = [&](const std::vector<FrameInputs>& in, const char* expected) {
    const Status st = ctx->dispatch(std::span<const FrameInputs>(in), s);
    EXPECT_FALSE(st) << expected;
    EXPECT_NE(st.message().find(expected), std::string::npos) << st.message();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  };
  // One FrameInputs, or three, for two views.
  refused({views->layeredInputs[0]}, "1 FrameInputs for a context of 2 view(s)");
  refused({views->layeredInputs[0], views->layeredInputs[1], views->layeredInputs[1]}, "3 FrameInputs");
  EXPECT_FALSE(ctx->dispatch(views->layeredInputs[0], s));  // the one-view call
  // One-view textures (GL_TEXTURE_2D) to a context of two views.
  refused({views->ownInputs[0], views->ownInputs[0]}, "is not a GL_TEXTURE_2D_ARRAY");
  // A view naming other textures than the first.
  std::vector<FrameInputs> mixed = views->layeredInputs;
  mixed[1].colorTexture = views->ownInputs[1].colorTexture;
  refused(mixed, "views[1] names colorTexture");
  // A view with another layout or history reset.
  mixed = views->layeredInputs;
  mixed[1].surface.constantRoughness = 0.5f;
  mixed[1].surface.roughnessChannel = -1;
  refused(mixed, "views may differ only in their matrices");
  mixed = views->layeredInputs;
  mixed[1].historyReset = true;
  refused(mixed, "historyReset differs");
  // Another exposure, with the radiance clamp off (the default), where the uniform block holds none.
  mixed = views->layeredInputs;
  mixed[1].exposure = 2.0f;
  refused(mixed, "views[1] exposure 2.000000 differs from views[0]'s 1.000000");
  // A bad projection names its view.
  mixed = views->layeredInputs;
  mixed[1].clipFromView = glm::dmat4(0.0);
  refused(mixed, "(view 1)");
  // Arrays with fewer layers than views.
  auto three = makeViewsContext(3);
  ASSERT_TRUE(three);
  const std::vector<FrameInputs> threeIn = {views->layeredInputs[0], views->layeredInputs[1], views->layeredInputs[1]};
  const Status st = three->dispatch(std::span<const FrameInputs>(threeIn), s);
  EXPECT_FALSE(st);
  EXPECT_NE(st.message().find("has 2 layer(s)"), std::string::npos) << st.message();
  // A view to composite the context does not have.
  ASSERT_TRUE(ctx->dispatch(std::span<const FrameInputs>(views->layeredInputs), s));
  for (int bad : {-1, 2}) {
    CompositeOptions o;
    o.view = bad;
    const Status cs = ctx->composite(0, o);
    EXPECT_FALSE(cs);
    EXPECT_NE(cs.message().find("CompositeOptions::view"), std::string::npos) << cs.message();
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// The tools' pipeline for several views (ViewsRenderer: sslr-render --views, sslr-bench's views
// study): each view's final image is bit for bit what the one-view pipeline (FrameRenderer) makes
// of the same camera, frame after frame with temporal reuse.
TEST_F(MultiView, TheToolsViewsPipelineGivesEachViewItsOwnFrame) {
  auto scene = makeBuiltinScene("mirror-walls");
  ASSERT_TRUE(scene);
  GpuScene gpu(scene.value());
  GBufferOptions o;
  o.width = kW;
  o.height = kH;
  auto views = ViewsRenderer::create(o, 2);
  ASSERT_TRUE(views) << views.error();
  const std::vector<Camera> cameras = sideBySideCameras(*scene.value().camera, 2, 0.2);
  EXPECT_NEAR(glm::length(cameras[1].eye - cameras[0].eye), 0.2, 1e-9);
  EXPECT_NEAR(glm::length(0.5 * (cameras[0].eye + cameras[1].eye) - scene.value().camera->eye), 0.0, 1e-9);
  std::unique_ptr<FrameRenderer> own[2];
  for (auto& r : own) {
    auto created = FrameRenderer::create(o);
    ASSERT_TRUE(created) << created.error();
    r = std::move(created.value());
  }
  Settings s;
  s.temporal.enabled = true;
  for (int frame = 0; frame < 2; ++frame) {
    ASSERT_TRUE(views.value()->render(gpu, cameras, &s));
    for (int v = 0; v < 2; ++v) {
      SCOPED_TRACE("frame " + std::to_string(frame) + ", view " + std::to_string(v));
      ASSERT_TRUE(own[v]->render(gpu, cameras[static_cast<size_t>(v)], &s));
      EXPECT_EQ(differing(views.value()->readFinal(v), own[v]->readFinal()), 0u);
    }
  }
  EXPECT_GT(differing(views.value()->readFinal(0), views.value()->readFinal(1)), 1000u);  // parallax
  EXPECT_FALSE(views.value()->render(gpu, std::span<const Camera>(cameras.data(), 1), &s));  // one camera, two views
  for (int bad : {1, kMaxViews + 1}) EXPECT_FALSE(ViewsRenderer::create(o, bad)) << bad << " views";
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// A context of several views binds 2D arrays to its units: dispatch and composite put back what
// the host had on both targets of every unit, as a one-view context does for the 2D target.
TEST_F(MultiView, PutsBackTheHostsTextureBindingsOfBothTargets) {
  auto views = makeViews("mirror-room", 2);
  ASSERT_TRUE(views);
  auto ctx = makeViewsContext(2);
  ASSERT_TRUE(ctx);
  constexpr int kUnits = 12;
  GLuint planes[kUnits] = {}, arrays[kUnits] = {};
  glCreateTextures(GL_TEXTURE_2D, kUnits, planes);
  glCreateTextures(GL_TEXTURE_2D_ARRAY, kUnits, arrays);
  for (int u = 0; u < kUnits; ++u) {
    glTextureStorage2D(planes[u], 1, GL_RGBA8, 4, 4);
    glTextureStorage3D(arrays[u], 1, GL_RGBA8, 4, 4, 2);
    glActiveTexture(GL_TEXTURE0 + u);
    glBindTexture(GL_TEXTURE_2D, planes[u]);
    glBindTexture(GL_TEXTURE_2D_ARRAY, arrays[u]);
  }
  glActiveTexture(GL_TEXTURE3);
  ASSERT_TRUE(ctx->dispatch(std::span<const FrameInputs>(views->layeredInputs), Settings{}));
  compositeOf(*ctx, 1);  // the composite, into a framebuffer of its own (DSA calls: nothing bound)
  GLint active = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  EXPECT_EQ(active, GL_TEXTURE3);
  for (int u = 0; u < kUnits; ++u) {
    glActiveTexture(GL_TEXTURE0 + u);
    GLint plane = 0, array = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &plane);
    glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &array);
    EXPECT_EQ(plane, static_cast<GLint>(planes[u])) << "unit " << u;
    EXPECT_EQ(array, static_cast<GLint>(arrays[u])) << "unit " << u;
  }
  glActiveTexture(GL_TEXTURE0);
  glDeleteTextures(kUnits, planes);
  glDeleteTextures(kUnits, arrays);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
