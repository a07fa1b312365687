// The drop-in API: creation, every invalid input rejected with a message (and no GL error),
// GL state restored, poisoned G-buffers never producing NaN/Inf, empty frames doing no work.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>

#include <EGL/egl.h>

#include "gl/gl_fixture.hpp"
#include "sslr/reference.hpp"
#include "sslr/sslr.hpp"
#include "sslr_host/frame_renderer.hpp"
#include "sslr_host/gbuffer.hpp"
#include "sslr_shared.h"

#include <glm/gtc/matrix_transform.hpp>

using namespace sslr;
using namespace sslr::host;

namespace {

constexpr int W = 64, H = 48;

std::unique_ptr<Context> makeContext(int w = W, int h = H, const ContextDesc& shapes = {}) {
  return sslr::test::makeSslrContext(w, h, shapes);
}

// Pass shapes with adaptive L after the traversal where `pass` says (ContextDesc::traversalPass).
ContextDesc traversalIn(TraversalPass pass, DeviceProfile device = DeviceProfile::Auto) {
  ContextDesc d;
  d.device = device;
  d.traversalPass = pass;
  return d;
}

GLuint makeTexture(GLenum format, int w = W, int h = H) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, w, h);
  return t;
}

// A G-buffer of a built-in scene, rendered by the host pass: by default a small one of the
// analytic mirror scene.
struct Frame {
  std::unique_ptr<GBuffer> gbuffer;
  std::unique_ptr<GpuScene> scene;
  Frame(DepthMode mode = DepthMode::Reversed, NormalEncoding normals = NormalEncoding::Octahedral,
        bool backDepth = false)
      : Frame("mirror-box", {.width = W, .height = H, .depth = mode, .normals = normals, .withBackDepth = backDepth}) {}
  Frame(const char* sceneName, const GBufferOptions& o) {
    auto g = GBuffer::create(o);
    EXPECT_TRUE(g) << g.error();
    gbuffer = std::move(g.value());
    auto s = makeBuiltinScene(sceneName);
    EXPECT_TRUE(s) << s.error();
    scene = std::make_unique<GpuScene>(s.value());
    EXPECT_TRUE(gbuffer->render(*scene, *s.value().camera));
  }
};

// The built-in `glossy` scene (panels of roughness 0, 0.1, ..., 0.5) rendered at 160x90, with its
// packed normal texels (roughness in B, the tools' layout).
struct GlossyPanels : Frame {
  static constexpr int kWidth = 160, kHeight = 90;
  Image packed;
  GlossyPanels() : Frame("glossy", {.width = kWidth, .height = kHeight}) { packed = gbuffer->readNormalPacked(); }
};

class Api : public sslr::test::GlTest {};

TEST_F(Api, CreateRejectsBadDescriptions) {
  ContextDesc d;
  d.width = 0;
  d.height = 10;
  d.getProcAddress = HeadlessContext::getProcAddress();
  auto c = Context::create(d);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().find("0x10"), std::string::npos) << c.error();
  d.width = 10;
  d.getProcAddress = nullptr;
  c = Context::create(d);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().find("getProcAddress"), std::string::npos) << c.error();
  d.getProcAddress = [](const char*) -> GLProc { return nullptr; };
  c = Context::create(d);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().find("glCreateTextures"), std::string::npos) << "names the missing entry points: " << c.error();
}

// ContextDesc::occupancyExit needs subgroup ballots: on a driver that lists neither extension (the
// loader's glGetStringi answers for one that lists only GL_KHR_debug), create() says which are
// missing and leaves no GL error; without the exit the same driver is fine.
static const GLubyte* KHRONOS_APIENTRY onlyDebugExtension(GLenum, GLuint) { return reinterpret_cast<const GLubyte*>("GL_KHR_debug"); }

TEST_F(Api, OccupancyExitNeedsSubgroupBallots) {
  ContextDesc d;
  d.width = 16;
  d.height = 16;
  d.getProcAddress = [](const char* name) -> GLProc {
    if (std::strcmp(name, "glGetStringi") == 0) return reinterpret_cast<GLProc>(&onlyDebugExtension);
    return HeadlessContext::getProcAddress()(name);
  };
  d.occupancyExit = true;
  auto c = Context::create(d);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().find("occupancyExit needs GL_ARB_shader_ballot and GL_ARB_gpu_shader_int64"), std::string::npos)
      << c.error();
  EXPECT_EQ(sslr::test::glContext()->glErrorCount(), 0);
  d.occupancyExit = false;
  EXPECT_TRUE(Context::create(d));
}

TEST_F(Api, DispatchRejectsEveryBadInputWithAMessage) {
  auto ctx = makeContext();
  Frame f;
  const FrameInputs good = f.gbuffer->frameInputs();
  const Settings s;
  ASSERT_TRUE(ctx->dispatch(good, s)) << ctx->dispatch(good, s).message();

  const GLuint wrongSize = makeTexture(GL_RGBA16F, W + 1, H);
  const GLuint integerTex = makeTexture(GL_RGBA16UI);
  const GLuint oneChannel = makeTexture(GL_R16);
  const GLuint depthAsColor = makeTexture(GL_DEPTH_COMPONENT32F);
  GLuint notTexture = 0;
  glCreateBuffers(1, &notTexture);  // a buffer name, not a texture
  struct Bad {
    const char* expect;
    std::function<void(FrameInputs&)> edit;
  };
  const std::vector<Bad> cases = {
      {"depthTexture (texture 0) is 0", [](FrameInputs& in) { in.depthTexture = 0; }},
      {"colorTexture", [](FrameInputs& in) { in.colorTexture = 0; }},
      {"normalTexture", [](FrameInputs& in) { in.normalTexture = 0; }},
      {"is not a texture name", [&](FrameInputs& in) { in.colorTexture = 987654; }},
      {"but the context is 64x48", [&](FrameInputs& in) { in.colorTexture = wrongSize; }},
      {"(RGBA16UI), an integer format", [&](FrameInputs& in) { in.normalTexture = integerTex; }},
      {"viewFromWorld is not given (all zeros)", [](FrameInputs& in) { in.surface.space = NormalSpace::World; }},
      {"expected a depth format", [&](FrameInputs& in) { in.depthTexture = good.colorTexture; }},
      {"expected a float or unorm colour format", [&](FrameInputs& in) { in.colorTexture = depthAsColor; }},
      {"needs 2", [&](FrameInputs& in) { in.normalTexture = oneChannel; }},
      {"roughnessChannel = 7", [](FrameInputs& in) { in.surface.roughnessChannel = 7; }},
      {"overlaps the normal", [](FrameInputs& in) { in.surface.reflectanceChannel = 1; }},
      {"not finite", [](FrameInputs& in) { in.clipFromView[2][2] = NAN; }},
      {"singular", [](FrameInputs& in) { in.clipFromView[0][0] = 0.0; }},
      {"neither", [](FrameInputs& in) { in.clipFromView = glm::dmat4(0.0); }},
      {"mismatch", [](FrameInputs& in) { in.depth = DepthConvention::glDefault(); }},
      {"finite", [](FrameInputs& in) { in.surface.constantReflectance = INFINITY; }},
  };
  for (const Bad& b : cases) {
    FrameInputs in = good;
    b.edit(in);
    const Status st = ctx->dispatch(in, s);
    ASSERT_FALSE(st) << b.expect;
    EXPECT_NE(st.message().find(b.expect), std::string::npos) << "got: " << st.message();
    EXPECT_EQ(sslr::test::glContext()->glErrorCount(), 0) << "after: " << b.expect;
  }
  Settings bad;
  bad.adaptiveL.maxIterations = -3;
  const Status st = ctx->dispatch(good, bad);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("adaptiveL.maxIterations"), std::string::npos) << st.message();
  Settings negativeCutoff;
  negativeCutoff.selection.roughnessCutoff = -0.1f;
  const Status cutoff = ctx->dispatch(good, negativeCutoff);
  ASSERT_FALSE(cutoff);
  EXPECT_NE(cutoff.message().find("selection.roughnessCutoff = -0.1 (must be 0..1"), std::string::npos) << cutoff.message();
  // A failed dispatch leaves nothing to composite.
  EXPECT_FALSE(ctx->composite(0));
  // Bad framebuffer names are refused.
  ASSERT_TRUE(ctx->dispatch(good, s));
  EXPECT_FALSE(ctx->composite(424242));
  const GLuint textures[] = {wrongSize, integerTex, oneChannel, depthAsColor};
  glDeleteTextures(4, textures);
  glDeleteBuffers(1, &notTexture);
}

TEST_F(Api, CompositeBeforeDispatchIsAnError) {
  auto ctx = makeContext();
  const Status st = ctx->composite(0);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("dispatch"), std::string::npos);
}

// Every piece of state the library documents as touched, captured as plain numbers.
struct Snapshot {
  std::vector<GLint64> values;
  static Snapshot take() {
    Snapshot s;
    auto i = [&](GLenum e) { GLint v = 0; glGetIntegerv(e, &v); s.values.push_back(v); };
    auto ii = [&](GLenum e, GLuint k) { GLint64 v = 0; glGetInteger64i_v(e, k, &v); s.values.push_back(v); };
    i(GL_CURRENT_PROGRAM);
    i(GL_ACTIVE_TEXTURE);
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int u = 0; u < 11; ++u) {
      glActiveTexture(GL_TEXTURE0 + u);
      for (GLenum target : {GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_CUBE_MAP, GL_TEXTURE_BINDING_3D,
                            GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_1D, GL_TEXTURE_BINDING_RECTANGLE,
                            GL_TEXTURE_BINDING_CUBE_MAP_ARRAY, GL_TEXTURE_BINDING_2D_MULTISAMPLE})
        i(target);
      i(GL_SAMPLER_BINDING);
    }
    glActiveTexture(static_cast<GLenum>(active));
    for (GLuint k = 0; k < 6; ++k) {  // 4 and 5: the pyramid's levels 6 and 7
      ii(GL_IMAGE_BINDING_NAME, k); ii(GL_IMAGE_BINDING_FORMAT, k); ii(GL_IMAGE_BINDING_ACCESS, k);
      ii(GL_IMAGE_BINDING_LEVEL, k);
    }
    for (GLuint k = 0; k < 4; ++k) {
      ii(GL_SHADER_STORAGE_BUFFER_BINDING, k); ii(GL_SHADER_STORAGE_BUFFER_START, k); ii(GL_SHADER_STORAGE_BUFFER_SIZE, k);
      ii(GL_UNIFORM_BUFFER_BINDING, k); ii(GL_UNIFORM_BUFFER_START, k); ii(GL_UNIFORM_BUFFER_SIZE, k);
    }
    for (GLenum e : {GL_SHADER_STORAGE_BUFFER_BINDING, GL_UNIFORM_BUFFER_BINDING, GL_DISPATCH_INDIRECT_BUFFER_BINDING,
                     GL_DRAW_INDIRECT_BUFFER_BINDING, GL_VERTEX_ARRAY_BINDING, GL_DRAW_FRAMEBUFFER_BINDING,
                     GL_READ_FRAMEBUFFER_BINDING, GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA,
                     GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA, GL_DEPTH_FUNC,
                     GL_ARRAY_BUFFER_BINDING, GL_PIXEL_PACK_BUFFER_BINDING})
      i(e);
    for (GLuint k = 0; k < 2; ++k) {  // indexed: glViewport and glDisable(GL_SCISSOR_TEST) set every index
      GLfloat vp[4];
      glGetFloati_v(GL_VIEWPORT, k, vp);
      s.values.insert(s.values.end(), vp, vp + 4);
      s.values.push_back(glIsEnabledi(GL_SCISSOR_TEST, k));
    }
    for (GLenum cap : {GL_COLOR_LOGIC_OP, GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SAMPLE_COVERAGE, GL_SAMPLE_MASK,
                       GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE7})
      s.values.push_back(glIsEnabled(cap));
    i(GL_LOGIC_OP_MODE);
    i(GL_CLIP_ORIGIN);
    i(GL_CLIP_DEPTH_MODE);
    GLint polygonMode[2] = {0, 0};
    glGetIntegerv(GL_POLYGON_MODE, polygonMode);
    s.values.push_back(polygonMode[0]);
    for (GLenum cap : {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_CULL_FACE, GL_SCISSOR_TEST, GL_BLEND, GL_RASTERIZER_DISCARD})
      s.values.push_back(glIsEnabled(cap));
    for (GLuint k = 0; k < 4; ++k) {
      GLboolean m[4];
      glGetBooleani_v(GL_COLOR_WRITEMASK, k, m);
      s.values.insert(s.values.end(), m, m + 4);
    }
    GLboolean depthMask = 0;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
    s.values.push_back(depthMask);
    return s;
  }
};

TEST_F(Api, RestoresEveryPieceOfGlStateItTouches) {
  auto ctx = makeContext();
  Frame f(DepthMode::Reversed, NormalEncoding::Octahedral, true);
  // Host state that sslr must not disturb: unusual values everywhere.
  GLuint hostTex[3], hostSampler = 0, hostBuf[3], hostVao = 0, hostFbo = 0;
  glCreateTextures(GL_TEXTURE_2D, 3, hostTex);
  for (GLuint t : hostTex) glTextureStorage2D(t, 1, GL_RGBA8, 4, 4);
  glCreateSamplers(1, &hostSampler);
  glCreateBuffers(3, hostBuf);
  for (GLuint b : hostBuf) glNamedBufferStorage(b, 1024, nullptr, 0);
  glCreateVertexArrays(1, &hostVao);
  GLuint fboTex = makeTexture(GL_RGBA16F);
  glCreateFramebuffers(1, &hostFbo);
  glNamedFramebufferTexture(hostFbo, GL_COLOR_ATTACHMENT0, fboTex, 0);
  // Textures of other targets on the same units: sslr binds only the 2D target of a unit.
  GLuint hostCube = 0, host3d = 0, hostArray = 0;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &hostCube);
  glTextureStorage2D(hostCube, 1, GL_RGBA8, 4, 4);
  glCreateTextures(GL_TEXTURE_3D, 1, &host3d);
  glTextureStorage3D(host3d, 1, GL_RGBA8, 4, 4, 4);
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &hostArray);
  glTextureStorage3D(hostArray, 1, GL_RGBA8, 4, 4, 2);
  for (int u = 0; u < 11; ++u) {  // every unit sslr uses (6: its depth pyramid, 7: material, 8: mask, 9: hit, 10: back depth)
    glBindTextureUnit(u, hostCube);
    glBindTextureUnit(u, host3d);
    glBindTextureUnit(u, hostArray);
    glBindTextureUnit(u, hostTex[u % 3]);
    glBindSampler(u, hostSampler);
  }
  glActiveTexture(GL_TEXTURE3);
  glBindImageTexture(0, hostTex[1], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
  glBindImageTexture(2, hostTex[2], 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
  glBindImageTexture(5, hostTex[0], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, hostBuf[0], 256, 512);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, hostBuf[1]);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, hostBuf[2], 0, 128);  // half resolution's list
  glBindBufferRange(GL_UNIFORM_BUFFER, 0, hostBuf[2], 0, 256);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, hostBuf[2]);
  glBindBuffer(GL_UNIFORM_BUFFER, hostBuf[0]);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, hostBuf[1]);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, hostBuf[2]);
  glBindVertexArray(hostVao);
  glBindFramebuffer(GL_FRAMEBUFFER, hostFbo);
  glViewport(3, 4, 20, 10);
  glViewportIndexedf(1, 1.5f, 2.0f, 7.0f, 9.0f);  // a second viewport (a host's layered pass)
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GEQUAL);
  glEnable(GL_CULL_FACE);
  glEnablei(GL_SCISSOR_TEST, 1);  // on index 1 only
  glEnable(GL_COLOR_LOGIC_OP);
  glLogicOp(GL_XOR);
  glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  glEnable(GL_CLIP_DISTANCE7);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
  glBlendEquationSeparate(GL_FUNC_SUBTRACT, GL_MAX);
  glColorMaski(0, GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  glColorMaski(1, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
  glDepthMask(GL_FALSE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);  // a wireframe debug view left on by the host
  glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);  // a D3D-style host
  GLuint hostProgram = glCreateProgram();  // any valid program name works as "current"
  (void)hostProgram;

  const Snapshot before = Snapshot::take();
  Settings s;
  s.debug.outputs = true;
  s.debug.collectStats = true;
  PrepareOptions warmComposite;  // prepare's warm-up frames and composite draw
  warmComposite.composite = true;
  warmComposite.framebuffer = hostFbo;
  warmComposite.compositeOptions = {CompositeMode::BlendOverFallback, f.gbuffer->fallbackSpecularTexture()};
  ASSERT_TRUE(ctx->prepare(f.gbuffer->frameInputs(), s, warmComposite));
  EXPECT_EQ(Snapshot::take().values, before.values) << "prepare changed GL state";
  FrameInputs depthOnly = f.gbuffer->frameInputs();
  depthOnly.backDepthTexture = 0;
  ASSERT_TRUE(ctx->dispatch(depthOnly, s));
  EXPECT_EQ(Snapshot::take().values, before.values) << "dispatch changed GL state";
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), s));  // with the back-face depth (unit 10)
  EXPECT_EQ(Snapshot::take().values, before.values) << "dispatch with a back-face depth changed GL state";
  Settings half = s;
  half.halfResolution = true;  // three more passes, two more textures and a buffer
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), half));
  EXPECT_EQ(Snapshot::take().values, before.values) << "half-resolution dispatch changed GL state";
  Settings temporal = s;
  temporal.temporal.enabled = true;  // two more passes, two more textures (the second dispatch reads them)
  FrameInputs withPrevious = f.gbuffer->frameInputs();
  withPrevious.previousClipFromView = withPrevious.clipFromView;
  for (int i = 0; i < 2; ++i) ASSERT_TRUE(ctx->dispatch(withPrevious, temporal));
  EXPECT_EQ(Snapshot::take().values, before.values) << "temporal dispatch changed GL state";
  ASSERT_TRUE(ctx->composite(hostFbo));
  EXPECT_EQ(Snapshot::take().values, before.values) << "composite changed GL state";
  ASSERT_TRUE(ctx->composite(hostFbo, {CompositeMode::BlendOverFallback, f.gbuffer->fallbackSpecularTexture()}));
  EXPECT_EQ(Snapshot::take().values, before.values) << "composite over the fallback changed GL state";

  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glViewportIndexedf(1, 0.0f, 0.0f, 1.0f, 1.0f);
  glDisable(GL_COLOR_LOGIC_OP);
  glLogicOp(GL_COPY);
  glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  glDisable(GL_CLIP_DISTANCE7);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glColorMaski(0, 1, 1, 1, 1);
  glColorMaski(1, 1, 1, 1, 1);
  glDepthFunc(GL_LESS);
  glBindSampler(0, 0);
  glDeleteProgram(hostProgram);
  glDeleteFramebuffers(1, &hostFbo);
  glDeleteTextures(3, hostTex);
  glDeleteTextures(1, &hostCube);
  glDeleteTextures(1, &host3d);
  glDeleteTextures(1, &hostArray);
  glDeleteTextures(1, &fboTex);
  glDeleteSamplers(1, &hostSampler);
  glDeleteBuffers(3, hostBuf);
  glDeleteVertexArrays(1, &hostVao);
  for (int u = 0; u < 10; ++u) {
    glBindTextureUnit(u, 0);
    glBindSampler(u, 0);
  }
  glActiveTexture(GL_TEXTURE0);
}

Image readAll(GLuint tex, int channels) { return readTexture(tex, W, H, channels); }

// Of the pixels with a confident hit in hit record `reference`: how many, and how many of them
// `other` also hits within half a pixel.
struct SameHits {
  size_t traced = 0, same = 0;
  double share() const { return traced ? double(same) / double(traced) : 0.0; }
};
SameHits sameHits(const Image& reference, const Image& other) {
  SameHits r;
  for (int p = 0; p < W * H; ++p) {
    const float* a = &reference.pixels[static_cast<size_t>(p) * 4];
    const float* b = &other.pixels[static_cast<size_t>(p) * 4];
    if (!(a[2] > 0.5f)) continue;
    ++r.traced;
    r.same += b[2] > 0.5f && std::hypot((a[0] - b[0]) * W, (a[1] - b[1]) * H) <= 0.5f;
  }
  return r;
}

TEST_F(Api, PoisonedGBufferNeverProducesNanOrInf) {
  auto ctx = makeContext();
  // Host-made textures filled with garbage: NaN/Inf colour, zero, non-unit and NaN normals,
  // depth at the clear value, the near value, denormals, NaN and random bits.
  const GLuint color = makeTexture(GL_RGBA16F), normal = makeTexture(GL_RGBA16F), depth = makeTexture(GL_DEPTH_COMPONENT32F);
  std::vector<float> c(W * H * 4), n(W * H * 4), d(W * H);
  std::uint32_t seed = 1234567u;
  auto rnd = [&]() { seed = seed * 1664525u + 1013904223u; return seed; };
  for (int p = 0; p < W * H; ++p) {
    const int kind = p % 8;
    const float specials[8] = {NAN, INFINITY, -INFINITY, 1e30f, -1.0f, 0.5f, 65504.0f, 0.0f};
    for (int k = 0; k < 4; ++k) c[p * 4 + k] = specials[(kind + k) % 8];
    const glm::vec4 normals[8] = {{0.5f, 0.5f, 0.0f, 1.0f}, {NAN, 0.5f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f, 1.0f},
                                  {1.0f, 1.0f, 0.0f, 1.0f}, {0.5f, 1.0f, 0.0f, INFINITY}, {0.5f, 0.75f, NAN, 1.0f},
                                  {0.3f, 0.9f, 0.0f, 0.9f}, {-5.0f, 9.0f, 0.0f, 1.0f}};
    std::memcpy(&n[p * 4], &normals[(kind + p / 8) % 8], 16);
    std::uint32_t bits = rnd();
    float randomFloat;
    std::memcpy(&randomFloat, &bits, 4);
    const float depths[8] = {0.0f, 1.0f, 1e-40f, 0.5f, 0.999999f, randomFloat, 1e-8f, 0.25f};
    d[p] = depths[(kind * 3 + p / 5) % 8];
  }
  glTextureSubImage2D(color, 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, c.data());
  glTextureSubImage2D(normal, 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, n.data());
  glTextureSubImage2D(depth, 0, 0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, d.data());
  Camera cam;
  for (DepthMode mode : {DepthMode::Reversed, DepthMode::ReversedInfinite, DepthMode::GlDefault}) {
    FrameInputs in;
    in.colorTexture = color;
    in.normalTexture = normal;
    in.depthTexture = depth;
    in.clipFromView = cam.clipFromView(mode, double(W) / H);
    in.depth = depthConvention(mode);
    for (NormalEncoding enc : {NormalEncoding::Octahedral, NormalEncoding::XyzUnorm})
    for (Method method : {Method::AdaptiveL, Method::HierarchicalDepth}) {  // the pyramid sees the garbage too
      in.surface.normals = enc;
      in.surface.roughnessChannel = enc == NormalEncoding::Octahedral ? 2 : -1;
      Settings s;
      s.method = method;
      s.debug.outputs = true;
      ASSERT_TRUE(ctx->dispatch(in, s));
      for (auto [tex, ch] : {std::pair{ctx->reflectionTexture(), 4}, {ctx->resolvedTexture(), 4},
                             {ctx->hitTexture(), 4}, {ctx->iterationsTexture(), 1}})
        EXPECT_EQ(countNonFinite(readAll(tex, ch)), 0u) << toString(mode);
      const Image iterations = readAll(ctx->iterationsTexture(), 1);
      // Loop counts bounded: adaptive L's cap plus the hierarchical fallback's.
      for (float it : iterations.pixels)
        ASSERT_LE(it, float(s.adaptiveL.maxIterations + s.traversal.maxSteps)) << "loop count bounded";
    }
  }
  const GLuint t[3] = {color, normal, depth};
  glDeleteTextures(3, t);
}

TEST_F(Api, EmptyFrameTracesNothing) {
  auto ctx = makeContext();
  Frame f;
  FrameInputs in = f.gbuffer->frameInputs();
  // Reflectance 0 everywhere (constant): no pixel is reflective.
  in.surface.reflectanceChannel = -1;
  in.surface.constantReflectance = 0.0f;
  Settings s;
  s.debug.collectStats = true;
  ASSERT_TRUE(ctx->dispatch(in, s));
  const FrameStats empty = ctx->waitForStats();
  EXPECT_EQ(empty.frame, 1u);
  EXPECT_EQ(empty.tiles, 0u);
  EXPECT_EQ(empty.tracedPixels, 0u);
  EXPECT_EQ(empty.fetches, 0u);
  const Image resolved = readAll(ctx->resolvedTexture(), 4);
  for (float v : resolved.pixels) ASSERT_EQ(v, 0.0f);
  // Reflective, but a constant roughness above the cutoff: nothing either.
  in = f.gbuffer->frameInputs();
  in.surface.roughnessChannel = -1;
  in.surface.constantRoughness = std::nextafter(s.selection.roughnessCutoff, 2.0f);
  ASSERT_TRUE(ctx->dispatch(in, s));
  EXPECT_EQ(ctx->waitForStats().tiles, 0u);
  // The same frame with reflectance traces and reports its work.
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), s));
  const FrameStats full = ctx->waitForStats();
  EXPECT_EQ(full.frame, 3u);
  EXPECT_GT(full.tiles, 0u);
  EXPECT_GT(full.tracedPixels, 0u);
  EXPECT_GE(full.fetches, full.tracedPixels);
}

// Stats are read a few frames late instead of stalling: lastStats() never waits and reports the
// newest dispatch whose GPU work is done (FrameStats::frame), waitForStats() the newest of all.
// Counts belong to the frame they say (alternating empty and full frames tell them apart), and
// with GL_TIMESTAMP the pass times are present and non-negative.
// FrameStats counts the commands each pass records: the structure of a frame, the same on every
// device (the traversal kept inline, as a GPU runs it). A change to a pass's dispatches or
// barriers shows here first, on purpose: they are what a GPU pays for with nothing to do.
TEST_F(Api, FrameStatsCountEachPassCommands) {
  for (DeviceProfile profile : {DeviceProfile::Software, DeviceProfile::Gpu}) {
    const bool gpu = profile == DeviceProfile::Gpu;
    SCOPED_TRACE(gpu ? "Gpu profile" : "Software profile");
    auto created = sslr::test::makeSslrContext(W, H, traversalIn(TraversalPass::Inline, profile));
    ASSERT_TRUE(created);
    Context* ctx = created.get();
    Frame f;
    Settings s;
    s.debug.collectStats = true;
    auto expect = [](const PassCommands& c, std::uint32_t direct, std::uint32_t indirect, std::uint32_t barriers,
                     std::uint32_t programs, const char* what) {
      EXPECT_EQ(c.dispatches, direct) << what;
      EXPECT_EQ(c.indirectDispatches, indirect) << what;
      EXPECT_EQ(c.barriers, barriers) << what;
      EXPECT_EQ(c.programs, programs) << what;
    };
    ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), s));
    FrameStats st = ctx->waitForStats();
    ASSERT_GT(st.tracedPixels, 0u);
    if (gpu) {
      expect(st.classifyCommands, 1, 0, 1, 1, "classify: the screen's tiles, the clean-up inside");
      expect(st.pyramidCommands, 0, 2, 2, 2, "pyramid: the curved quads, levels 2-7 (arguments set by classification)");
    } else {
      expect(st.classifyCommands, 1, 1, 2, 2, "classify: the screen's tiles, then the clean-up of the last frame's");
      expect(st.pyramidCommands, 1, 2, 3, 3, "pyramid: its arguments, the curved quads, levels 2-7");
    }
    expect(st.traceCommands, 0, 1, 1, 1, "trace: one indirect pass over the listed tiles");
    expect(st.blurCommands, 0, 2, 1, 2, "blur: horizontal and vertical over the listed tiles");
    expect(st.temporalCommands, 0, 0, 0, 0, "temporal: off");
    expect(st.finishCommands, 0, 0, 1, 0, "finish: one barrier for the host");
    EXPECT_GT(st.classifyCommands.uploads, 0u) << "the frame constants at least";

    Settings alone = s;
    alone.traversal.maxSteps = 0;  // adaptive L alone needs no pyramid
    ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), alone));
    st = ctx->waitForStats();
    expect(st.pyramidCommands, 0, 0, 0, 0, "no pyramid for adaptive L alone");
    expect(st.traceCommands, 0, 1, 1, 1, "trace");

    Settings temporal = s;
    temporal.temporal.enabled = true;
    FrameInputs in = f.gbuffer->frameInputs();
    in.previousClipFromView = in.clipFromView;
    for (int i = 0; i < 2; ++i) ASSERT_TRUE(ctx->dispatch(in, temporal));
    st = ctx->waitForStats();
    expect(st.temporalCommands, 0, 3, 3, 3, "temporal: blend, store, history clean-up");
  }
}

// FrameStats' texture traffic follows from the frame's counts and the G-buffer's formats (here
// D32F depth, RGBA16 normal with the material in its blue and alpha, R11F_G11F_B10F colour): an
// empty frame reads the screen's depth and material and nothing else; a full frame's trace writes
// two RGBA16F texels per pixel of its listed tiles, plus the debug images' when asked for.
TEST_F(Api, FrameStatsModelTextureTraffic) {
  auto ctx = makeContext();
  Frame f;
  const std::uint64_t P = std::uint64_t(W) * H, quads = std::uint64_t((W + 1) / 2) * ((H + 1) / 2);
  FrameInputs full = f.gbuffer->frameInputs(), empty = full;
  empty.surface.reflectanceChannel = -1;
  empty.surface.constantReflectance = 0.0f;
  Settings s;
  s.debug.collectStats = true;
  auto none = [](const PassTraffic& t, const char* what) {
    EXPECT_EQ(t.texelsRead + t.texelsWritten + t.bytesRead + t.bytesWritten, 0u) << what;
  };

  // A context's first frame writes the pyramid's levels 0 and 1 in classification (it cannot know
  // the frame lists no tile): per pixel its depth, one material gather (roughness; reflectance is
  // a constant here) and, for curved solids, two normal gathers; level 1 whole and level 0 at most
  // whole.
  ASSERT_TRUE(ctx->dispatch(empty, s));
  FrameStats st = ctx->waitForStats();
  ASSERT_EQ(st.tiles, 0u);
  EXPECT_EQ(st.classifyTraffic.texelsRead, 4 * P);
  EXPECT_EQ(st.classifyTraffic.bytesRead, P * (4 + 8 + 2 * 8));
  EXPECT_EQ(st.classifyTraffic.texelsWritten, quads + P);
  EXPECT_EQ(st.classifyTraffic.bytesWritten, (quads + P) * 8);
  none(st.pyramidTraffic, "pyramid: no tile listed");
  none(st.traceTraffic, "trace: no tile listed");
  none(st.blurTraffic, "blur");
  none(st.temporalTraffic, "temporal: off");

  // After an empty frame: the screen's depth and its one material channel, nothing written.
  ASSERT_TRUE(ctx->dispatch(empty, s));
  st = ctx->waitForStats();
  ASSERT_TRUE(st.followedEmptyFrame);
  EXPECT_EQ(st.classifyTraffic.bytesRead, P * (4 + 8));
  EXPECT_EQ(st.classifyTraffic.bytesWritten, 0u);

  // A full frame: the trace writes reflection and resolved for every pixel of its tiles, and reads
  // each pixel's normal and depth, every counted fetch (a pyramid texel at most, 8 B), and per ray
  // a bilinear colour read (4 texels of 4 B) and the hit's normal.
  ASSERT_TRUE(ctx->dispatch(full, s));
  st = ctx->waitForStats();
  ASSERT_TRUE(st.followedEmptyFrame);
  EXPECT_EQ(st.pyramidTraffic.bytesRead, P * (4 + 2 * 8) + quads * 8)
      << "levels 0 and 1 in a pass of their own (depth, curved normal gathers), then level 1 for the rest";
  ASSERT_TRUE(ctx->dispatch(full, s));
  st = ctx->waitForStats();
  ASSERT_GT(st.tiles, 0u);
  const std::uint64_t tilePixels = std::uint64_t(st.tiles) * 64;
  EXPECT_EQ(st.traceTraffic.texelsWritten, 2 * tilePixels);
  EXPECT_EQ(st.traceTraffic.bytesWritten, 16 * tilePixels);
  EXPECT_EQ(st.traceTraffic.bytesRead,
            tilePixels * (8 + 4) + std::uint64_t(st.fetches) * 8 + std::uint64_t(st.tracedPixels) * (4 * 4 + 8));
  EXPECT_GT(st.pyramidTraffic.bytesWritten, 0u) << "levels 2 and up";
  EXPECT_EQ(st.pyramidTraffic.bytesRead, quads * 8) << "level 1, once";
  const PassTraffic total = st.totalTraffic();
  EXPECT_EQ(total.bytesRead, st.classifyTraffic.bytesRead + st.pyramidTraffic.bytesRead + st.traceTraffic.bytesRead +
                                 st.blurTraffic.bytesRead + st.temporalTraffic.bytesRead);

  // The debug images add a hit record (RGBA32F) and an iteration count (R32F) per pixel.
  Settings debug = s;
  debug.debug.outputs = true;
  ASSERT_TRUE(ctx->dispatch(full, debug));
  const FrameStats withDebug = ctx->waitForStats();
  ASSERT_EQ(withDebug.tiles, st.tiles);
  EXPECT_EQ(withDebug.traceTraffic.bytesWritten, tilePixels * (16 + 16 + 4));
}

TEST_F(Api, StatsArriveLateWithoutStalling) {
  auto ctx = makeContext();
  Frame f;
  FrameInputs full = f.gbuffer->frameInputs(), empty = full;
  empty.surface.reflectanceChannel = -1;
  empty.surface.constantReflectance = 0.0f;
  Settings s;
  s.debug.collectStats = true;
  EXPECT_EQ(ctx->lastStats().frame, 0u);  // nothing dispatched yet
  // More frames than the ring holds, none read in between: the oldest slots are overwritten.
  for (int i = 1; i <= 7; ++i) ASSERT_TRUE(ctx->dispatch(i % 2 ? full : empty, s));
  const FrameStats newest = ctx->waitForStats();
  EXPECT_EQ(newest.frame, 7u);
  EXPECT_GT(newest.tracedPixels, 0u);  // frame 7 is a full one
  // After the GPU is idle, lastStats() has the newest without waiting; an empty frame reads empty.
  ASSERT_TRUE(ctx->dispatch(empty, s));
  glFinish();
  const FrameStats late = ctx->lastStats();
  EXPECT_EQ(late.frame, 8u);
  EXPECT_EQ(late.tracedPixels, 0u);
  EXPECT_EQ(late.tiles, 0u);
  GLint bits = 0;
  glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
  for (const FrameStats& st : {newest, late}) {
    if (bits > 0) {
      EXPECT_GE(st.classifyMs, 0.0);
      EXPECT_GE(st.pyramidMs, 0.0);
      EXPECT_GE(st.traceMs, 0.0);
      EXPECT_GE(st.blurMs, 0.0);
    } else {
      EXPECT_EQ(st.classifyMs, -1.0);
    }
  }
  // A dispatch without stats leaves the last ones as they were.
  Settings quiet;
  ASSERT_TRUE(ctx->dispatch(full, quiet));
  EXPECT_EQ(ctx->waitForStats().frame, 8u);
}

// The outputs are not cleared whole each frame: classification zeroes only the tiles a trace wrote
// before and that are not traced now. Whatever came before, a frame's outputs are exactly those
// of a fresh context.
TEST_F(Api, OutputsDoNotDependOnEarlierFrames) {
  Frame f;
  const FrameInputs full = f.gbuffer->frameInputs();
  FrameInputs none = full;  // reflectance 0 everywhere: nothing is traced
  none.surface.reflectanceChannel = -1;
  none.surface.constantReflectance = 0.0f;
  // Half resolution keeps more per frame (the quads' records, their per-tile counters) and reads
  // its neighbour quads' records, which only this frame's listed tiles hold.
  for (bool halfResolution : {false, true}) {
    SCOPED_TRACE(halfResolution ? "half resolution" : "full resolution");
    Settings s;
    s.halfResolution = halfResolution;
    // Fewer tiles: the same frame whose left half is rough (roughness channel 1: not traced).
    Frame roughLeft;
    const FrameInputs partial = roughLeft.gbuffer->frameInputs();
    const std::vector<float> rough(static_cast<size_t>(W / 2) * H * 4, 1.0f);
    glTextureSubImage2D(partial.normalTexture, 0, 0, 0, W / 2, H, GL_RGBA, GL_FLOAT, rough.data());
    // What a fresh context gives for `in` as its frame `frame`, after empty frames: half
    // resolution's traced pixel of a quad rotates with the frame index.
    auto expected = [&](const FrameInputs& in, int frame) {
      auto fresh = makeContext();
      for (int i = 1; i < frame; ++i) EXPECT_TRUE(fresh->dispatch(none, s));
      EXPECT_TRUE(fresh->dispatch(in, s));
      return std::pair{readAll(fresh->reflectionTexture(), 4).pixels, readAll(fresh->resolvedTexture(), 4).pixels};
    };
    const auto wantNone = expected(none, 1);
    for (float v : wantNone.second) ASSERT_EQ(v, 0.0f);
    ASSERT_NE(expected(full, 1).second, expected(partial, 1).second) << "the two frames must trace different tiles";
    auto ctx = makeContext();
    struct Step {
      const FrameInputs* in;
      const char* name;
    } steps[] = {{&full, "full"},       {&none, "none after full"},
                 {&none, "none again"}, {&full, "full after none"},
                 {&partial, "fewer tiles after full"}, {&full, "full again"}};
    int frame = 0;
    for (const Step& st : steps) {
      ASSERT_TRUE(ctx->dispatch(*st.in, s));
      const auto want = expected(*st.in, ++frame);
      EXPECT_EQ(readAll(ctx->reflectionTexture(), 4).pixels, want.first) << st.name;
      EXPECT_EQ(readAll(ctx->resolvedTexture(), 4).pixels, want.second) << st.name;
    }
    // A resize starts from zero outputs too.
    ASSERT_TRUE(ctx->resize(W / 2, H / 2));
    ASSERT_TRUE(ctx->resize(W, H));
    ASSERT_TRUE(ctx->dispatch(none, s));
    EXPECT_EQ(readAll(ctx->resolvedTexture(), 4).pixels, wantNone.second) << "after resize";
  }
}

// World-space normals with the view matrix give the hits of view-space normals; declared as
// view space they trace other reflections (what sslr cannot detect, docs/integration.md).
TEST_F(Api, WorldSpaceNormalsWithTheViewMatrixGiveTheSameHits) {
  auto ctx = makeContext();
  Frame f;
  const FrameInputs viewIn = f.gbuffer->frameInputs();
  Settings s;
  s.debug.outputs = true;
  ASSERT_TRUE(ctx->dispatch(viewIn, s));
  const Image hitView = readAll(ctx->hitTexture(), 4);
  // The same normals in world space, in a texture of the host's format (RGBA16 octahedral).
  const Image packed = readAll(viewIn.normalTexture, 4);
  const glm::dmat3 worldFromView = glm::inverse(glm::dmat3(f.gbuffer->viewFromWorld()));
  std::vector<std::uint16_t> world(static_cast<size_t>(W) * H * 4);
  for (int p = 0; p < W * H; ++p) {
    const float* t = &packed.pixels[static_cast<size_t>(p) * 4];
    const glm::vec3 n = sslr::shared::sslrOctDecode(glm::vec2(t[0], t[1]));
    const glm::vec2 e = sslr::shared::sslrOctEncode(glm::vec3(glm::normalize(worldFromView * glm::dvec3(n))));
    const float out[4] = {e.x, e.y, t[2], t[3]};  // roughness and reflectance as they were
    for (int c = 0; c < 4; ++c)
      world[static_cast<size_t>(p) * 4 + c] = static_cast<std::uint16_t>(std::lround(std::clamp(out[c], 0.0f, 1.0f) * 65535.0f));
  }
  const GLuint worldTex = makeTexture(GL_RGBA16);
  glTextureSubImage2D(worldTex, 0, 0, 0, W, H, GL_RGBA, GL_UNSIGNED_SHORT, world.data());
  FrameInputs worldIn = viewIn;
  worldIn.normalTexture = worldTex;
  worldIn.surface.space = NormalSpace::World;
  worldIn.viewFromWorld = f.gbuffer->viewFromWorld();
  ASSERT_TRUE(ctx->dispatch(worldIn, s));
  const Image hitWorld = readAll(ctx->hitTexture(), 4);
  worldIn.surface.space = NormalSpace::View;  // the mistake: world normals declared as view space
  ASSERT_TRUE(ctx->dispatch(worldIn, s));
  const Image hitWrong = readAll(ctx->hitTexture(), 4);
  const SameHits same = sameHits(hitView, hitWorld);
  ASSERT_GT(same.traced, 500u);
  // 16-bit octahedral normals re-encoded once: a few hits may move by a fraction of a pixel.
  EXPECT_GE(same.share(), 0.98) << same.same << " of " << same.traced;
  EXPECT_LT(sameHits(hitView, hitWrong).share(), 0.5) << "world normals read as view space must differ";
  // A singular view matrix is refused with the field named.
  worldIn.surface.space = NormalSpace::World;
  worldIn.viewFromWorld = glm::dmat4(0.0);
  const Status st = ctx->dispatch(worldIn, s);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("viewFromWorld"), std::string::npos) << st.message();
  glDeleteTextures(1, &worldTex);
}

// Normals in signed normalized formats (RG16_SNORM octahedral, RGBA16_SNORM xyz) with the signed
// unpack (SurfaceLayout::normalScale 1, normalBias 0) give the hits of the unsigned G-buffer; a
// decode that does not map the format's range onto [-1, 1], or a zero scale, is refused, named.
TEST_F(Api, SignedNormalFormatsGiveTheSameHits) {
  for (NormalEncoding encoding : {NormalEncoding::Octahedral, NormalEncoding::XyzUnorm}) {
    SCOPED_TRACE(encoding == NormalEncoding::Octahedral ? "octahedral, RG16_SNORM" : "xyz, RGBA16_SNORM");
    auto ctx = makeContext();
    Frame f(DepthMode::Reversed, encoding);
    const FrameInputs unsignedIn = f.gbuffer->frameInputs();
    Settings s;
    s.debug.outputs = true;
    ASSERT_TRUE(ctx->dispatch(unsignedIn, s));
    const Image hitUnsigned = readAll(ctx->hitTexture(), 4);
    // The same normals, signed, in a texture of their own; the material stays in the old one.
    const bool octahedral = encoding == NormalEncoding::Octahedral;
    const int channels = octahedral ? 2 : 4;
    const Image packed = readAll(unsignedIn.normalTexture, 4);
    std::vector<float> signedValues(static_cast<size_t>(W) * H * channels, 0.0f);
    for (int p = 0; p < W * H; ++p)
      for (int c = 0; c < (octahedral ? 2 : 3); ++c)
        signedValues[static_cast<size_t>(p) * channels + c] = packed.pixels[static_cast<size_t>(p) * 4 + c] * 2.0f - 1.0f;
    const GLuint signedTex = makeTexture(octahedral ? GL_RG16_SNORM : GL_RGBA16_SNORM);
    glTextureSubImage2D(signedTex, 0, 0, 0, W, H, octahedral ? GL_RG : GL_RGBA, GL_FLOAT, signedValues.data());
    FrameInputs signedIn = unsignedIn;
    signedIn.normalTexture = signedTex;
    signedIn.materialTexture = unsignedIn.normalTexture;  // roughness in B, reflectance in A
    signedIn.surface.normalScale = 1.0f;
    signedIn.surface.normalBias = 0.0f;
    ASSERT_TRUE(ctx->dispatch(signedIn, s));
    const Image hitSigned = readAll(ctx->hitTexture(), 4);
    const SameHits same = sameHits(hitUnsigned, hitSigned);
    ASSERT_GT(same.traced, 500u);
    // Requantized once, to 16 bits: a few hits may move by a fraction of a pixel.
    EXPECT_GE(same.share(), 0.98) << same.same << " of " << same.traced;
    // The mistakes: signed values left on the unsigned default (they would decode to [-3, 1] and
    // find almost no hit), and unsigned ones on the signed unpack ([0, 1]): refused, named.
    signedIn.surface.normalScale = 2.0f;
    signedIn.surface.normalBias = -1.0f;
    Status wrong = ctx->dispatch(signedIn, s);
    ASSERT_FALSE(wrong);
    EXPECT_EQ(wrong.code(), StatusCode::InvalidInput);
    EXPECT_NE(wrong.message().find(octahedral ? "is RG16_SNORM" : "is RGBA16_SNORM"), std::string::npos) << wrong.message();
    EXPECT_NE(wrong.message().find("use 1/0 for a signed (SNORM) format"), std::string::npos) << wrong.message();
    FrameInputs unsignedAsSigned = unsignedIn;
    unsignedAsSigned.surface.normalScale = 1.0f;
    unsignedAsSigned.surface.normalBias = 0.0f;
    wrong = ctx->dispatch(unsignedAsSigned, s);
    ASSERT_FALSE(wrong);
    EXPECT_NE(wrong.message().find("use 2/-1 for an unsigned (UNORM) format"), std::string::npos) << wrong.message();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    signedIn.surface.normalScale = 0.0f;
    const Status st = ctx->dispatch(signedIn, s);
    ASSERT_FALSE(st);
    EXPECT_EQ(st.code(), StatusCode::InvalidInput);
    EXPECT_NE(st.message().find("normalScale"), std::string::npos) << st.message();
    glDeleteTextures(1, &signedTex);
  }
}

// A float normal texture holds whatever the host wrote: [0, 1] on the unsigned default decode is
// right, -1..1 on it finds almost no hit. Not refusable from the format, so said: one warning in
// the log per texture naming the format and the fix; none with the signed decode (1/0), which then
// finds the unsigned G-buffer's hits.
TEST_F(Api, FloatNormalsOnTheUnsignedDecodeAreWarnedOfOnce) {
  std::vector<std::string> warnings;
  ContextDesc d;
  d.width = W;
  d.height = H;
  d.getProcAddress = HeadlessContext::getProcAddress();
  d.log = [&](LogLevel level, const std::string& text) {
    if (level == LogLevel::Warning) warnings.push_back(text);
  };
  auto created = Context::create(d);
  ASSERT_TRUE(created) << created.error();
  Context& ctx = *created.value();
  Frame f;
  const FrameInputs unsignedIn = f.gbuffer->frameInputs();
  Settings s;
  s.debug.outputs = true;
  ASSERT_TRUE(ctx.dispatch(unsignedIn, s));
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  const Image hitUnsigned = readAll(ctx.hitTexture(), 4);
  const Image packed = readAll(unsignedIn.normalTexture, 4);
  std::vector<float> signedValues(static_cast<size_t>(W) * H * 2, 0.0f);
  for (int p = 0; p < W * H; ++p)
    for (int c = 0; c < 2; ++c)
      signedValues[static_cast<size_t>(p) * 2 + c] = packed.pixels[static_cast<size_t>(p) * 4 + c] * 2.0f - 1.0f;
  const GLuint floatTex = makeTexture(GL_RG16F);
  glTextureSubImage2D(floatTex, 0, 0, 0, W, H, GL_RG, GL_FLOAT, signedValues.data());
  FrameInputs floatIn = unsignedIn;
  floatIn.normalTexture = floatTex;
  floatIn.materialTexture = unsignedIn.normalTexture;
  ASSERT_TRUE(ctx.dispatch(floatIn, s));
  ASSERT_TRUE(ctx.dispatch(floatIn, s));
  ASSERT_EQ(warnings.size(), 1u) << "once per texture";
  EXPECT_NE(warnings[0].find("is RG16F, a float format, decoded as holding [0, 1]"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("if it holds -1..1, set 1/0"), std::string::npos) << warnings[0];
  floatIn.surface.normalScale = 1.0f;
  floatIn.surface.normalBias = 0.0f;
  ASSERT_TRUE(ctx.dispatch(floatIn, s));
  EXPECT_EQ(warnings.size(), 1u) << "the signed decode is not warned of";
  const SameHits same = sameHits(hitUnsigned, readAll(ctx.hitTexture(), 4));
  ASSERT_GT(same.traced, 500u);
  EXPECT_GE(same.share(), 0.98) << same.same << " of " << same.traced;
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glDeleteTextures(1, &floatTex);
}

// GlossyMode::Stochastic with temporal reuse: the first frame (no history) blurs its rough pixels'
// rays as the cone blur does; a frame with history gives them no blur weight, so the blur runs over
// none of their tiles (the temporal blend filters them instead: 5_temporal_blend.comp). Measured
// at 160x90: 3,023 of the 11,072 rough pixels blurred in the first frame over 84 tiles, none and 0
// in the second.
TEST_F(Api, StochasticRaysWithHistoryAreFilteredByTheTemporalBlendNotBlurred) {
  const GlossyPanels panels;
  ASSERT_TRUE(panels.gbuffer);
  FrameInputs in = panels.gbuffer->frameInputs();
  in.previousClipFromView = in.clipFromView;
  const Image& packed = panels.packed;
  const int w = GlossyPanels::kWidth, h = GlossyPanels::kHeight;
  Settings s;
  s.debug.outputs = true;
  s.debug.collectStats = true;
  s.glossy.mode = GlossyMode::Stochastic;
  s.temporal.enabled = true;
  auto ctx = makeContext(w, h);
  ASSERT_TRUE(ctx->dispatch(in, s));  // no history yet
  const Image first = readTexture(ctx->reflectionTexture(), w, h, 4);
  const std::uint32_t firstBlurTiles = ctx->waitForStats().blurTiles;
  ASSERT_TRUE(ctx->dispatch(in, s));
  const Image second = readTexture(ctx->reflectionTexture(), w, h, 4);
  const std::uint32_t secondBlurTiles = ctx->waitForStats().blurTiles;
  size_t rough = 0, blurredFirst = 0, blurredSecond = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!(packed.at(x, y, 2) >= s.glossy.stochasticFrom)) continue;
      ++rough;
      blurredFirst += first.at(x, y, 3) > 0.0f ? 1 : 0;  // the reflection's alpha: its blur weight
      blurredSecond += second.at(x, y, 3) > 0.0f ? 1 : 0;
    }
  ASSERT_GT(rough, 2000u);
  EXPECT_GT(blurredFirst, 1000u) << "the first frame blurs the rays that hit";
  EXPECT_EQ(blurredSecond, 0u) << "a frame with history blurs no stochastic ray";
  EXPECT_GT(firstBlurTiles, 20u);
  EXPECT_LT(secondBlurTiles, firstBlurTiles / 4) << "the blur runs over the smooth panels' tiles alone";
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// GlossyMode::Stochastic changes the rays of the pixels at least glossy.stochasticFrom rough, and
// of no other: below the threshold the hits are the cone blur mode's bit for bit; above it they
// differ from the mirror rays' and from frame to frame (a new draw each dispatch).
TEST_F(Api, StochasticGlossyDrawsNewRaysOnRoughPixelsOnly) {
  const GlossyPanels panels;
  ASSERT_TRUE(panels.gbuffer);
  const FrameInputs in = panels.gbuffer->frameInputs();
  const Image& packed = panels.packed;
  const int w = GlossyPanels::kWidth, h = GlossyPanels::kHeight;
  Settings cone;
  cone.debug.outputs = true;
  Settings stochastic = cone;
  stochastic.glossy.mode = GlossyMode::Stochastic;
  stochastic.glossy.stochasticFrom = 0.25f;
  auto ctx = makeContext(w, h);
  ASSERT_TRUE(ctx->dispatch(in, cone));
  const Image hitCone = readTexture(ctx->hitTexture(), w, h, 4);
  ASSERT_TRUE(ctx->dispatch(in, stochastic));
  const Image hitA = readTexture(ctx->hitTexture(), w, h, 4);
  ASSERT_TRUE(ctx->dispatch(in, stochastic));
  const Image hitB = readTexture(ctx->hitTexture(), w, h, 4);
  size_t smooth = 0, smoothDiffering = 0, rough = 0, roughVsCone = 0, roughVsLastFrame = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!(hitCone.at(x, y, 2) > 0.5f)) continue;  // traced and hit
      const bool isRough = packed.at(x, y, 2) >= 0.25f;
      const bool sameAsCone = hitA.at(x, y, 0) == hitCone.at(x, y, 0) && hitA.at(x, y, 1) == hitCone.at(x, y, 1);
      const bool sameAsLast = hitA.at(x, y, 0) == hitB.at(x, y, 0) && hitA.at(x, y, 1) == hitB.at(x, y, 1);
      if (isRough) {
        ++rough;
        roughVsCone += sameAsCone ? 0 : 1;
        roughVsLastFrame += sameAsLast ? 0 : 1;
      } else {
        ++smooth;
        smoothDiffering += sameAsCone && sameAsLast ? 0 : 1;
      }
    }
  ASSERT_GT(smooth, 500u);
  ASSERT_GT(rough, 500u);
  EXPECT_EQ(smoothDiffering, 0u);
  EXPECT_GT(roughVsCone, rough * 9 / 10);
  EXPECT_GT(roughVsLastFrame, rough * 9 / 10);
  stochastic.halfResolution = true;
  const Status st = ctx->dispatch(in, stochastic);
  ASSERT_FALSE(st);
  EXPECT_EQ(st.code(), StatusCode::InvalidSettings);
  EXPECT_NE(st.message().find("glossy.mode"), std::string::npos) << st.message();
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// OutputMode::Radiance leaves the Fresnel term to the host: the reflection is the hit colour x
// coverage whatever the surface's reflectance, the weighted output bit for bit where the Fresnel
// term is 1 (Schlick with F0 = 1), with the weighted output's coverage; composite() refuses it.
TEST_F(Api, RadianceOutputLeavesTheFresnelTermToTheHost) {
  auto ctx = makeContext();
  Frame f;
  FrameInputs mirror = f.gbuffer->frameInputs();
  mirror.surface.reflectanceChannel = -1;
  mirror.surface.constantReflectance = 1.0f;
  FrameInputs dielectric = mirror;
  dielectric.surface.constantReflectance = 0.5f;
  Settings weighted;
  weighted.fresnel = FresnelMode::Schlick;
  weighted.blur.maxRadiusPx = 0.0f;
  Settings radiance = weighted;
  radiance.output = OutputMode::Radiance;
  auto run = [&](const FrameInputs& in, const Settings& s) {
    EXPECT_TRUE(ctx->dispatch(in, s));
    return std::pair{readAll(ctx->reflectionTexture(), 4), readAll(ctx->resolvedTexture(), 4)};
  };
  const auto mirrorWeighted = run(mirror, weighted);
  const auto dielectricWeighted = run(dielectric, weighted);
  const auto dielectricRadiance = run(dielectric, radiance);
  const Status refused = ctx->composite(0);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.code(), StatusCode::InvalidSettings);
  EXPECT_NE(refused.message().find("Radiance"), std::string::npos) << refused.message();
  const auto mirrorRadiance = run(mirror, radiance);
  // A weighted frame composites again (into a framebuffer of the context's size).
  const GLuint target = makeTexture(GL_RGBA16F);
  GLuint fbo = 0;
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
  EXPECT_FALSE(ctx->composite(fbo)) << "still the radiance frame";
  ASSERT_TRUE(ctx->dispatch(mirror, weighted));
  EXPECT_TRUE(ctx->composite(fbo));
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &target);

  EXPECT_EQ(mirrorRadiance.first.pixels, mirrorWeighted.first.pixels) << "F = 1: radiance is the weighted output";
  EXPECT_EQ(dielectricRadiance.first.pixels, mirrorRadiance.first.pixels) << "radiance does not depend on F0";
  double sumWeighted = 0.0, sumRadiance = 0.0;
  size_t covered = 0;
  for (int p = 0; p < W * H; ++p) {
    const float* w = &dielectricWeighted.second.pixels[static_cast<size_t>(p) * 4];
    const float* r = &dielectricRadiance.second.pixels[static_cast<size_t>(p) * 4];
    EXPECT_EQ(w[3], r[3]) << "the same coverage, pixel " << p;
    covered += r[3] > 0.0f;
    for (int c = 0; c < 3; ++c) {
      EXPECT_LE(w[c], r[c] * 1.001f + 1e-6f) << "F <= 1, pixel " << p;
      sumWeighted += w[c];
      sumRadiance += r[c];
    }
  }
  ASSERT_GT(covered, 500u);
  // Schlick with F0 = 0.5 lies in [0.5, 1]: most of the picture is the surfaces seen head-on.
  EXPECT_LT(sumWeighted, 0.9 * sumRadiance);
  EXPECT_GE(sumWeighted, 0.49 * sumRadiance);
}

// Coloured F0 (metalness x base colour): a metal's reflection takes its base colour through the
// Fresnel term channel by channel (Schlick with F0 = (1, 0.5, 0.25): red whole, green and blue at
// least half and a quarter, and green at least blue's share); metalness 0 gives the grey F0's
// output; a metalness channel without a base colour, or the reverse, is refused, named.
TEST_F(Api, ColoredF0TintsMetalsReflections) {
  auto ctx = makeContext();
  Frame f;
  const FrameInputs packedIn = f.gbuffer->frameInputs();  // roughness in B, reflectance in A
  Settings s;
  s.fresnel = FresnelMode::Schlick;
  s.blur.maxRadiusPx = 0.0f;
  ASSERT_TRUE(ctx->dispatch(packedIn, s));
  const Image grey = readAll(ctx->reflectionTexture(), 4);
  Settings radianceSettings = s;
  radianceSettings.output = OutputMode::Radiance;
  // Material RGBA16: R = reflectance, G = roughness, B = metalness.
  const Image packed = readAll(packedIn.normalTexture, 4);
  auto materialTexture = [&](float metalness) {
    std::vector<std::uint16_t> m(static_cast<size_t>(W) * H * 4);
    for (int p = 0; p < W * H; ++p) {
      const float* t = &packed.pixels[static_cast<size_t>(p) * 4];
      const float v[4] = {t[3], t[2], metalness, 1.0f};
      for (int c = 0; c < 4; ++c) m[static_cast<size_t>(p) * 4 + c] = static_cast<std::uint16_t>(std::lround(v[c] * 65535.0f));
    }
    const GLuint tex = makeTexture(GL_RGBA16);
    glTextureSubImage2D(tex, 0, 0, 0, W, H, GL_RGBA, GL_UNSIGNED_SHORT, m.data());
    return tex;
  };
  const GLuint metal = materialTexture(1.0f), dielectric = materialTexture(0.0f);
  const GLuint baseColor = makeTexture(GL_RGBA16F);
  const std::vector<float> tint(static_cast<size_t>(W) * H * 4, 0.0f);
  std::vector<float> colour = tint;
  for (int p = 0; p < W * H; ++p) {
    colour[static_cast<size_t>(p) * 4] = 1.0f;
    colour[static_cast<size_t>(p) * 4 + 1] = 0.5f;
    colour[static_cast<size_t>(p) * 4 + 2] = 0.25f;
  }
  glTextureSubImage2D(baseColor, 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, colour.data());
  FrameInputs in = packedIn;
  in.materialTexture = metal;
  in.baseColorTexture = baseColor;
  in.surface.reflectanceChannel = 0;
  in.surface.roughnessChannel = 1;
  in.surface.metalnessChannel = 2;
  ASSERT_TRUE(ctx->dispatch(in, radianceSettings));
  const Image radiance = readAll(ctx->reflectionTexture(), 4);
  ASSERT_TRUE(ctx->dispatch(in, s));
  const Image metallic = readAll(ctx->reflectionTexture(), 4);
  size_t lit = 0;
  for (int p = 0; p < W * H; ++p) {
    const float* r = &radiance.pixels[static_cast<size_t>(p) * 4];
    const float* m = &metallic.pixels[static_cast<size_t>(p) * 4];
    if (!(r[0] > 1e-3f && r[1] > 1e-3f && r[2] > 1e-3f)) continue;
    ++lit;
    EXPECT_EQ(m[0], r[0]) << "F0 = 1: the red channel is the radiance, pixel " << p;
    EXPECT_GE(m[1], 0.5f * r[1] * 0.999f) << p;
    EXPECT_LE(m[1], r[1] * 1.001f) << p;
    EXPECT_GE(m[2], 0.25f * r[2] * 0.999f) << p;
    EXPECT_GE(m[1] / r[1], m[2] / r[2] * 0.999f) << "F(0.5) >= F(0.25), pixel " << p;
  }
  ASSERT_GT(lit, 500u);
  // Metalness 0: the reflectance, grey, as without the base colour (to rounding).
  in.materialTexture = dielectric;
  ASSERT_TRUE(ctx->dispatch(in, s));
  const Image dielectricOut = readAll(ctx->reflectionTexture(), 4);
  ASSERT_EQ(dielectricOut.pixels.size(), grey.pixels.size());
  for (size_t i = 0; i < grey.pixels.size(); ++i)
    ASSERT_NEAR(dielectricOut.pixels[i], grey.pixels[i], 1e-3f * std::max(1.0f, std::abs(grey.pixels[i]))) << i;
  // Either input alone is refused, with the missing one named.
  FrameInputs noColour = in;
  noColour.baseColorTexture = 0;
  Status st = ctx->dispatch(noColour, s);
  ASSERT_FALSE(st);
  EXPECT_EQ(st.code(), StatusCode::InvalidInput);
  EXPECT_NE(st.message().find("baseColorTexture"), std::string::npos) << st.message();
  FrameInputs noMetalness = in;
  noMetalness.surface.metalnessChannel = -1;
  st = ctx->dispatch(noMetalness, s);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("metalnessChannel"), std::string::npos) << st.message();
  GLuint textures[] = {metal, dielectric, baseColor};
  glDeleteTextures(3, textures);
}

// Roughness and reflectance in a texture of their own (as many engines keep them) give the
// frame of the packed layout; a channel the material texture lacks is refused, naming it.
TEST_F(Api, SeparateMaterialTextureGivesThePackedResult) {
  auto ctx = makeContext();
  Frame f;
  const FrameInputs packedIn = f.gbuffer->frameInputs();  // roughness in B, reflectance in A
  Settings s;
  s.debug.outputs = true;
  ASSERT_TRUE(ctx->dispatch(packedIn, s));
  const Image hitPacked = readAll(ctx->hitTexture(), 4), resolvedPacked = readAll(ctx->resolvedTexture(), 4);
  // RG16 material texture: R = reflectance, G = roughness (the other order on purpose).
  const Image packed = readAll(packedIn.normalTexture, 4);
  std::vector<std::uint16_t> material(static_cast<size_t>(W) * H * 2);
  for (int p = 0; p < W * H; ++p) {
    material[static_cast<size_t>(p) * 2] = static_cast<std::uint16_t>(std::lround(packed.pixels[static_cast<size_t>(p) * 4 + 3] * 65535.0f));
    material[static_cast<size_t>(p) * 2 + 1] = static_cast<std::uint16_t>(std::lround(packed.pixels[static_cast<size_t>(p) * 4 + 2] * 65535.0f));
  }
  const GLuint materialTex = makeTexture(GL_RG16);
  glTextureSubImage2D(materialTex, 0, 0, 0, W, H, GL_RG, GL_UNSIGNED_SHORT, material.data());
  FrameInputs separate = packedIn;
  separate.materialTexture = materialTex;
  separate.surface.reflectanceChannel = 0;
  separate.surface.roughnessChannel = 1;
  ASSERT_TRUE(ctx->dispatch(separate, s));
  // The same 16-bit values reach the same formulas: the same frame, bit for bit.
  EXPECT_EQ(readAll(ctx->hitTexture(), 4).pixels, hitPacked.pixels);
  EXPECT_EQ(readAll(ctx->resolvedTexture(), 4).pixels, resolvedPacked.pixels);
  size_t traced = 0;
  for (int p = 0; p < W * H; ++p) traced += hitPacked.pixels[static_cast<size_t>(p) * 4 + 2] > 0.5f;
  ASSERT_GT(traced, 500u);
  // A channel the material texture does not have.
  separate.surface.roughnessChannel = 2;
  const Status st = ctx->dispatch(separate, s);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("materialTexture"), std::string::npos) << st.message();
  glDeleteTextures(1, &materialTex);
}

// Context::prepare compiles every program a frame with those inputs and settings may use: the
// frames after it (a traced one, an empty one, the one after it that builds level 1 in a pass of
// its own, TraversalPass::Auto switching between inline and deferred, both composites) compile
// nothing more. Counted by the Info messages sslr logs for each program it compiles.
TEST_F(Api, PrepareCompilesEveryProgramFramesUse) {
  for (bool half : {false, true}) {
    int compiled = 0;
    ContextDesc d;
    d.width = W;
    d.height = H;
    d.getProcAddress = HeadlessContext::getProcAddress();
    d.log = [&](LogLevel level, const std::string& text) {
      if (level == LogLevel::Info && text.find("sslr: compiled") != std::string::npos) ++compiled;
    };
    Frame f(DepthMode::Reversed, NormalEncoding::Octahedral, true);
    const FrameInputs in = f.gbuffer->frameInputs();
    {  // TraversalPass::Auto switches passes from frame to frame
      auto ctx = Context::create(d);
      ASSERT_TRUE(ctx) << ctx.error();
      compiled = 0;
      Settings s;
      s.halfResolution = half;
      s.debug.collectStats = true;
      ASSERT_TRUE(ctx.value()->prepare(in, s));
      const int prepared = compiled;
      EXPECT_GT(prepared, 2) << "half " << half;  // classify, pyramid, trace at least
      Settings empty = s;
      empty.selection.minReflectance = 1.0f;  // nothing reflects: no tile is listed
      GLuint target = makeTexture(GL_RGBA16F), fbo = 0;
      glCreateFramebuffers(1, &fbo);
      glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
      bool sawDeferred = false, sawInline = false, sawLevel1Pass = false;
      for (const Settings* frame : {&s, &s, &empty, &s, &s, &s}) {
        ASSERT_TRUE(ctx.value()->dispatch(in, *frame));
        const FrameStats st = ctx.value()->waitForStats();
        if (st.hierarchicalPixels > 0) (st.traversalDeferred ? sawDeferred : sawInline) = true;
        sawLevel1Pass = sawLevel1Pass || st.followedEmptyFrame;
        ASSERT_TRUE(ctx.value()->composite(fbo));
        ASSERT_TRUE(ctx.value()->composite(fbo, {CompositeMode::BlendOverFallback, f.gbuffer->fallbackSpecularTexture()}));
      }
      EXPECT_EQ(compiled, prepared) << "a frame compiled a program prepare() did not (half " << half << ")";
      EXPECT_TRUE(sawLevel1Pass) << "the frame after the empty one builds level 1 in a pass of its own";
      EXPECT_TRUE(sawDeferred || sawInline);
      glDeleteFramebuffers(1, &fbo);
      glDeleteTextures(1, &target);
    }
  }
}

// A loader that records, in order, each program link ('L') and each read of a compile or link
// result ('W': a read waits for a driver that compiles in parallel), and can break one entry's
// source (its body gains an #error).
namespace record {
std::string events;
const char* breakEntry = nullptr;  // the first comment line of the entry to break, or none
PFNGLLINKPROGRAMPROC link = nullptr;
PFNGLGETPROGRAMIVPROC getProgramiv = nullptr;
PFNGLGETSHADERIVPROC getShaderiv = nullptr;
PFNGLSHADERSOURCEPROC shaderSource = nullptr;
void KHRONOS_APIENTRY onLink(GLuint program) {
  events += 'L';
  link(program);
}
void KHRONOS_APIENTRY onGetProgramiv(GLuint program, GLenum pname, GLint* value) {
  if (pname == GL_LINK_STATUS) events += 'W';
  getProgramiv(program, pname, value);
}
void KHRONOS_APIENTRY onGetShaderiv(GLuint shader, GLenum pname, GLint* value) {
  if (pname == GL_COMPILE_STATUS) events += 'W';
  getShaderiv(shader, pname, value);
}
void KHRONOS_APIENTRY onShaderSource(GLuint shader, GLsizei count, const GLchar* const* strings, const GLint* lengths) {
  std::vector<std::string> texts;
  std::vector<const GLchar*> pointers;
  for (GLsizei i = 0; i < count; ++i) {
    texts.emplace_back(lengths != nullptr && lengths[i] >= 0 ? std::string(strings[i], lengths[i]) : std::string(strings[i]));
    if (breakEntry != nullptr && texts.back().find(breakEntry) != std::string::npos) texts.back() += "\n#error broken by the test\n";
  }
  for (const std::string& t : texts) pointers.push_back(t.c_str());
  shaderSource(shader, count, pointers.data(), nullptr);
}
GLProc getProcAddress(const char* name) {
  const GLProc real = HeadlessContext::getProcAddress()(name);
  const std::pair<const char*, GLProc> wrapped[] = {
      {"glLinkProgram", reinterpret_cast<GLProc>(&onLink)},
      {"glGetProgramiv", reinterpret_cast<GLProc>(&onGetProgramiv)},
      {"glGetShaderiv", reinterpret_cast<GLProc>(&onGetShaderiv)},
      {"glShaderSource", reinterpret_cast<GLProc>(&onShaderSource)}};
  if (std::strcmp(name, "glLinkProgram") == 0) link = reinterpret_cast<PFNGLLINKPROGRAMPROC>(real);
  if (std::strcmp(name, "glGetProgramiv") == 0) getProgramiv = reinterpret_cast<PFNGLGETPROGRAMIVPROC>(real);
  if (std::strcmp(name, "glGetShaderiv") == 0) getShaderiv = reinterpret_cast<PFNGLGETSHADERIVPROC>(real);
  if (std::strcmp(name, "glShaderSource") == 0) shaderSource = reinterpret_cast<PFNGLSHADERSOURCEPROC>(real);
  for (const auto& [wrappedName, proc] : wrapped)
    if (std::strcmp(name, wrappedName) == 0) return proc;
  return real;
}
}  // namespace record

// prepare() hands every program of every variant to the driver before it reads any result, so a
// driver that compiles in parallel (GL_KHR_parallel_shader_compile) builds them at once: under the
// software shapes (two traversal variants, the level-1 pass) with both composites, no compile or
// link result is read before the last link. The frames after it link nothing.
TEST_F(Api, PrepareHandsEveryProgramOverBeforeWaitingOnAny) {
  ContextDesc d;
  d.width = W;
  d.height = H;
  d.device = DeviceProfile::Software;
  d.getProcAddress = &record::getProcAddress;
  auto ctx = Context::create(d);
  ASSERT_TRUE(ctx) << ctx.error();
  Frame f;
  const FrameInputs in = f.gbuffer->frameInputs();
  PrepareOptions options;
  options.composite = true;
  options.compositeOptions = {CompositeMode::BlendOverFallback, f.gbuffer->fallbackSpecularTexture()};
  record::events.clear();
  ASSERT_TRUE(ctx.value()->prepare(in, Settings{}, options));
  const std::string prepared = record::events;
  EXPECT_GE(std::count(prepared.begin(), prepared.end(), 'L'), 10) << prepared;
  ASSERT_NE(prepared.find('W'), std::string::npos) << prepared;
  EXPECT_LT(prepared.rfind('L'), prepared.find('W')) << "a result was read before the last link: " << prepared;
  record::events.clear();
  for (int frame = 0; frame < 3; ++frame) ASSERT_TRUE(ctx.value()->dispatch(in, Settings{}));
  EXPECT_EQ(record::events.find('L'), std::string::npos) << "a frame linked a program: " << record::events;
}

// A program that fails to build is named, with the driver's log, by prepare() and by dispatch(),
// which stay usable: nothing crashes, no GL error is left, and a context whose programs build is
// unaffected. The trace's entry is broken by the loader (an #error in its body).
TEST_F(Api, AProgramThatFailsToBuildIsNamed) {
  ContextDesc d;
  d.width = W;
  d.height = H;
  d.getProcAddress = &record::getProcAddress;
  std::vector<std::string> errors;
  d.log = [&](LogLevel level, const std::string& text) {
    if (level == LogLevel::Error) errors.push_back(text);
  };
  auto ctx = Context::create(d);
  ASSERT_TRUE(ctx) << ctx.error();
  Frame f;
  const FrameInputs in = f.gbuffer->frameInputs();
  record::breakEntry = "// Pass 3, the trace";
  const Status prepared = ctx.value()->prepare(in, Settings{});
  const Status dispatched = ctx.value()->dispatch(in, Settings{});
  record::breakEntry = nullptr;
  for (const Status* st : {&prepared, &dispatched}) {
    ASSERT_FALSE(*st);
    EXPECT_EQ(st->code(), StatusCode::ShaderBuild);
    EXPECT_NE(st->message().find("sslr: compiling 3_trace.comp failed"), std::string::npos) << st->message();
    EXPECT_NE(st->message().find("broken by the test"), std::string::npos) << "the driver's log: " << st->message();
  }
  EXPECT_FALSE(errors.empty()) << "logged as an error";
  EXPECT_EQ(sslr::test::glContext()->glErrorCount(), 0);
  sslr::test::glContext()->resetGlErrorCount();  // the driver's own high-severity report of the #error
  auto healthy = makeContext();
  ASSERT_TRUE(healthy->dispatch(in, Settings{}));
}

// The retrace (deferred traversal, half resolution) is the whole tracer's program in its retrace
// role, not a program of its own. TraversalPass::Auto under DeviceProfile::Software keeps the inline
// and the deferred trace ready: two trace programs, the first stage alone and the whole tracer that
// is both the inline trace and the retrace (three before 0.12.1). At half resolution: the quads'
// first stage and whole tracer, the shading and the pixels' retrace (five before). Forced Deferred
// compiles the same; Inline the whole tracer alone (at half resolution the quads', the shading and
// the retrace). Counted by the Info messages sslr logs for each program it compiles.
TEST_F(Api, RetraceIsTheTraceProgramInItsRetraceRole) {
  struct Case {
    TraversalPass pass;
    bool half;
    int programs;  // pass 3's programs (entries 3_*) prepare() compiles
  };
  const Case cases[] = {{TraversalPass::Auto, false, 2},   {TraversalPass::Deferred, false, 2},
                        {TraversalPass::Inline, false, 1}, {TraversalPass::Auto, true, 4},
                        {TraversalPass::Deferred, true, 4}, {TraversalPass::Inline, true, 3}};
  Frame f(DepthMode::Reversed, NormalEncoding::Octahedral, true);
  const FrameInputs in = f.gbuffer->frameInputs();
  for (const Case& c : cases) {
    int programs = 0;
    ContextDesc d;
    d.width = W;
    d.height = H;
    d.device = DeviceProfile::Software;
    d.traversalPass = c.pass;
    d.getProcAddress = HeadlessContext::getProcAddress();
    d.log = [&](LogLevel level, const std::string& text) {
      if (level == LogLevel::Info && text.find("sslr: compiled sslr.program 3_") != std::string::npos) ++programs;
    };
    auto ctx = Context::create(d);
    ASSERT_TRUE(ctx) << ctx.error();
    Settings s;
    s.halfResolution = c.half;
    ASSERT_TRUE(ctx.value()->prepare(in, s));
    const std::string where = "pass " + std::to_string(static_cast<int>(c.pass)) + ", half " + std::to_string(c.half);
    EXPECT_EQ(programs, c.programs) << where;
    ASSERT_TRUE(ctx.value()->dispatch(in, s)) << where;
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << where;
  }
}

// The projection's kind and the depth convention are compiled into the programs
// (shared/projection.h, sslrOrthographic), as the normal encoding is: a frame that changes either
// compiles the programs it has not yet met, a frame with one already met compiles nothing, and each
// gives what a context that met only it gives. Counted by the Info messages sslr logs for each
// program it compiles.
TEST_F(Api, TheProjectionsKindAndDepthConventionAreCompiledIn) {
  struct Shape {
    const char* name;
    DepthMode depth;
    bool orthographic;
  };
  const Shape shapes[] = {{"perspective, reversed", DepthMode::Reversed, false},
                          {"perspective, GL default", DepthMode::GlDefault, false},
                          {"orthographic, reversed", DepthMode::Reversed, true}};
  auto scene = makeBuiltinScene("mirror-box");
  ASSERT_TRUE(scene) << scene.error();
  GpuScene gpu(scene.value());
  std::vector<std::unique_ptr<GBuffer>> gbuffers;
  for (const Shape& shape : shapes) {
    auto g = GBuffer::create({.width = W, .height = H, .depth = shape.depth});
    ASSERT_TRUE(g) << g.error();
    Camera camera = *scene.value().camera;
    camera.orthographic = shape.orthographic;
    camera.orthoHeight = 6.0;
    ASSERT_TRUE(g.value()->render(gpu, camera));
    gbuffers.push_back(std::move(g.value()));
  }
  int compiled = 0;
  auto contextCounting = [&](int* counter) {
    ContextDesc d;
    d.width = W;
    d.height = H;
    d.getProcAddress = HeadlessContext::getProcAddress();
    d.log = [counter](LogLevel level, const std::string& text) {
      if (counter && level == LogLevel::Info && text.find("sslr: compiled sslr.program") != std::string::npos) ++*counter;
    };
    auto ctx = Context::create(d);
    EXPECT_TRUE(ctx) << ctx.error();
    return ctx ? std::move(ctx.value()) : nullptr;
  };
  auto shared = contextCounting(&compiled);
  ASSERT_TRUE(shared);
  Settings s;
  s.debug.outputs = true;
  for (int round = 0; round < 2; ++round)
    for (size_t i = 0; i < std::size(shapes); ++i) {
      SCOPED_TRACE(std::string(shapes[i].name) + ", round " + std::to_string(round));
      const FrameInputs in = gbuffers[i]->frameInputs();
      compiled = 0;
      ASSERT_TRUE(shared->dispatch(in, s));
      if (round == 0)
        EXPECT_GT(compiled, 0) << "a projection or depth convention not met before compiles its programs";
      else
        EXPECT_EQ(compiled, 0) << "met before: nothing to compile";
      const Image hits = readAll(shared->hitTexture(), 4);
      auto alone = contextCounting(nullptr);
      ASSERT_TRUE(alone && alone->dispatch(in, s));
      const Image aloneHits = readAll(alone->hitTexture(), 4);
      size_t found = 0;
      for (size_t p = 2; p < hits.pixels.size(); p += 4) found += hits.pixels[p] > 0.5f;
      EXPECT_GT(found, 200u) << "the mirror box reflects";
      EXPECT_EQ(hits.pixels, aloneHits.pixels);
    }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// FrameStats' ray work is what the iterations image says, regrouped as the trace dispatch's 8x8
// groups run (invocations 0-31 are a group's rows 0-3): lane steps summed, each 32- and 64-lane
// group's largest summed, the largest of all. Recomputed here from the image, exactly, for the
// inline trace, the traversal alone and adaptive L alone; a deferred traversal adds the retrace
// dispatch's work, in groups of 64 listed pixels.
TEST_F(Api, RayWorkIsTheIterationsImageRegroupedAsTheGroupsRun) {
  auto ctx = makeContext(W, H, traversalIn(TraversalPass::Inline));
  Frame f;
  const FrameInputs in = f.gbuffer->frameInputs();
  auto expectRegrouped = [&](const Settings& s, const char* what) {
    SCOPED_TRACE(what);
    ASSERT_TRUE(ctx->dispatch(in, s));
    const FrameStats st = ctx->waitForStats();
    const Image iterations = readAll(ctx->iterationsTexture(), 1);
    std::uint64_t lanes = 0, simt32 = 0, simt64 = 0;
    std::uint32_t chain = 0;
    for (int ty = 0; ty < H; ty += 8)
      for (int tx = 0; tx < W; tx += 8) {
        std::uint32_t half[2] = {0, 0};
        for (int y = ty; y < std::min(ty + 8, H); ++y)
          for (int x = tx; x < std::min(tx + 8, W); ++x) {
            const auto steps = static_cast<std::uint32_t>(iterations.pixels[static_cast<size_t>(y) * W + x]);
            lanes += steps;
            half[(y - ty) / 4] = std::max(half[(y - ty) / 4], steps);
          }
        simt32 += half[0] + half[1];
        simt64 += std::max(half[0], half[1]);
        chain = std::max({chain, half[0], half[1]});
      }
    ASSERT_GT(lanes, 1000u) << "the frame must trace";
    EXPECT_EQ(st.traceWork.laneSteps, lanes);
    EXPECT_EQ(st.traceWork.simt32, simt32);
    EXPECT_EQ(st.traceWork.simt64, simt64);
    EXPECT_EQ(st.traceWork.longestChain, chain);
    EXPECT_EQ(st.retraceWork.groups, 0u);
    EXPECT_EQ(st.totalRayWork().laneSteps, lanes);
    EXPECT_LE(st.traceWork.simt64, st.traceWork.simt32) << "a 64-lane group pays at most its two halves";
    EXPECT_GE(st.traceWork.simt32 * 32, st.traceWork.laneSteps) << "a group pays at least its lanes' mean";
  };
  Settings s;
  s.debug.outputs = true;
  s.debug.collectStats = true;
  expectRegrouped(s, "default, inline");
  Settings hiz = s;
  hiz.method = Method::HierarchicalDepth;
  expectRegrouped(hiz, "the traversal alone");
  Settings alone = s;
  alone.traversal.maxSteps = 0;
  expectRegrouped(alone, "adaptive L alone");
  // Deferred: the trace dispatch counts the traversal's steps, the retrace dispatch the listed
  // pixels' adaptive L; every listed pixel is a lane there, 64 to a group.
  auto deferredCtx = makeContext(W, H, traversalIn(TraversalPass::Deferred));
  ASSERT_TRUE(deferredCtx->dispatch(in, s));
  const FrameStats st = deferredCtx->waitForStats();
  ASSERT_TRUE(st.traversalDeferred);
  EXPECT_GT(st.retraceWork.laneSteps, 0u);
  EXPECT_LE(st.retraceWork.groups, (st.tracedPixels + 63) / 64);
  EXPECT_EQ(st.totalRayWork().longestChain, st.traceWork.longestChain + st.retraceWork.longestChain);
  EXPECT_EQ(st.totalRayWork().simt32, st.traceWork.simt32 + st.retraceWork.simt32);
}

// Settings::radianceClamp on a colour texture at 1,000 (an emitter or a sun in every hit): the
// reflection's luminance stays at most the limit / exposure (Fresnel and coverage only lower it;
// RGBA16F rounds up by at most 2^-10), and a limit no colour reaches changes nothing.
TEST_F(Api, RadianceClampBoundsBrightHits) {
  auto ctx = makeContext();
  Frame f;
  FrameInputs in = f.gbuffer->frameInputs();
  const GLuint bright = makeTexture(GL_RGBA16F);
  const float value[4] = {1000.0f, 800.0f, 600.0f, 1.0f};
  glClearTexImage(bright, 0, GL_RGBA, GL_FLOAT, value);
  in.colorTexture = bright;
  auto maxLuminance = [&](const Settings& s, float exposure) {
    FrameInputs frame = in;
    frame.exposure = exposure;
    EXPECT_TRUE(ctx->dispatch(frame, s));
    const Image r = readAll(ctx->reflectionTexture(), 4);
    float most = 0.0f;
    for (size_t p = 0; p < r.pixels.size(); p += 4)
      most = std::max(most, 0.2126f * r.pixels[p] + 0.7152f * r.pixels[p + 1] + 0.0722f * r.pixels[p + 2]);
    return std::pair{most, r.pixels};
  };
  Settings off, clamped, unreached;
  clamped.radianceClamp.maxLuminance = 4.0f;
  unreached.radianceClamp.maxLuminance = 1e30f;
  const auto [offMost, offPixels] = maxLuminance(off, 1.0f);
  EXPECT_GT(offMost, 100.0f) << "the bright hits must show unclamped";
  EXPECT_LE(maxLuminance(clamped, 1.0f).first, 4.0f * (1.0f + 1.0f / 512.0f));
  EXPECT_GT(maxLuminance(clamped, 1.0f).first, 1.0f) << "clamped, not removed";
  EXPECT_LE(maxLuminance(clamped, 2.0f).first, 2.0f * (1.0f + 1.0f / 512.0f)) << "the limit is in display units";
  EXPECT_EQ(maxLuminance(unreached, 1.0f).second, offPixels);
  glDeleteTextures(1, &bright);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// prepare() runs each program once on the host's inputs (drivers compile at first use) and then
// puts the frame state back: the frames after it are bit for bit those of a context that was never
// prepared (outputs, hits, temporal history, the stats' frame numbers), at full and half resolution.
TEST_F(Api, PrepareLeavesTheFramesAsWithoutIt) {
  for (bool half : {false, true}) {
    SCOPED_TRACE(half ? "half resolution" : "full resolution");
    auto plain = makeContext();
    auto prepared = makeContext();
    Frame f(DepthMode::Reversed, NormalEncoding::Octahedral, true);
    FrameInputs in = f.gbuffer->frameInputs();
    in.previousClipFromView = in.clipFromView;
    Settings s;
    s.halfResolution = half;
    s.temporal.enabled = true;
    s.debug.outputs = true;
    s.debug.collectStats = true;
    ASSERT_TRUE(prepared->prepare(in, s));
    EXPECT_EQ(prepared->lastStats().frame, 0u) << "the warm-up frames are not the host's";
    // An empty frame first (what the warm-up traced must not show), then traced ones.
    Settings empty = s;
    empty.selection.minReflectance = 1.0f;
    for (std::uint64_t frame = 1; frame <= 4; ++frame) {
      const Settings& now = frame == 1 ? empty : s;
      ASSERT_TRUE(plain->dispatch(in, now));
      ASSERT_TRUE(prepared->dispatch(in, now));
      for (auto [tex, channels] : {std::pair{&Context::resolvedTexture, 4}, std::pair{&Context::reflectionTexture, 4},
                                   std::pair{&Context::hitTexture, 4}, std::pair{&Context::iterationsTexture, 1}}) {
        const Image a = readAll(((*plain).*tex)(), channels), b = readAll(((*prepared).*tex)(), channels);
        EXPECT_EQ(a.pixels, b.pixels) << "frame " << frame;
      }
      const FrameStats sa = plain->waitForStats(), sb = prepared->waitForStats();
      EXPECT_EQ(sb.frame, frame);
      EXPECT_EQ(sa.tracedPixels, sb.tracedPixels);
      EXPECT_EQ(sa.fetches, sb.fetches);
    }
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// prepare() validates like dispatch(): bad settings and a bad projection are refused, named.
TEST_F(Api, PrepareRefusesWhatDispatchRefuses) {
  auto ctx = makeContext();
  ASSERT_TRUE(ctx);
  Frame f;
  Settings bad;
  bad.adaptiveL.maxIterations = 0;
  const Status st = ctx->prepare(f.gbuffer->frameInputs(), bad);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("adaptiveL.maxIterations"), std::string::npos) << st.message();
  FrameInputs identity = f.gbuffer->frameInputs();
  identity.clipFromView = glm::dmat4(1.0);
  const Status proj = ctx->prepare(identity, Settings{});
  ASSERT_FALSE(proj);
  EXPECT_NE(proj.message().find("identity"), std::string::npos) << proj.message();
  // Its composite warm-up: a framebuffer that is none, a fallback the mode does not read, radiance
  // output (composite refuses it) are refused, named; nothing is left bound or in error.
  PrepareOptions warm;
  warm.composite = true;
  warm.framebuffer = 4242;
  Status st2 = ctx->prepare(f.gbuffer->frameInputs(), Settings{}, warm);
  ASSERT_FALSE(st2);
  EXPECT_NE(st2.message().find("PrepareOptions::framebuffer 4242 is not a framebuffer name"), std::string::npos)
      << st2.message();
  warm.framebuffer = 0;
  warm.compositeOptions.fallbackSpecularTexture = f.gbuffer->fallbackSpecularTexture();
  st2 = ctx->prepare(f.gbuffer->frameInputs(), Settings{}, warm);
  ASSERT_FALSE(st2);
  EXPECT_NE(st2.message().find("the mode is Add"), std::string::npos) << st2.message();
  warm.compositeOptions = {};
  Settings radiance;
  radiance.output = OutputMode::Radiance;
  st2 = ctx->prepare(f.gbuffer->frameInputs(), radiance, warm);
  ASSERT_FALSE(st2);
  EXPECT_NE(st2.message().find("OutputMode::Radiance"), std::string::npos) << st2.message();
  EXPECT_TRUE(ctx->prepare(f.gbuffer->frameInputs(), Settings{}, warm)) << "the default framebuffer counts as RGBA8";
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// The tools' back-face depth pass: a unit box 4.5 units in front of the camera, seen square on,
// is 1 unit deep at the centre pixel (its back face's view depth 5.5; tolerance: D32F rounding of
// reversed-Z at that distance, ~1e-5 relative); beside it nothing is behind the floorless sky, so
// the back depth keeps the clear value. A mirroring node (negative determinant) turns the winding
// over and measures the same.
TEST_F(Api, BackDepthPassMeasuresABoxsDepth) {
  for (double mirrorX : {1.0, -1.0}) {
    Scene scene;
    scene.materials.push_back(Material{});
    Mesh box = makeBox({0.0, 0.0, -5.0}, {1.0, 1.0, 1.0}, 0);
    box.worldFromModel = glm::scale(box.worldFromModel, glm::dvec3(mirrorX, 1.0, 1.0));
    scene.meshes.push_back(box);
    Camera camera;
    camera.eye = {0.0, 0.0, 0.0};
    camera.target = {0.0, 0.0, -5.0};
    camera.fovyDegrees = 40.0;
    camera.nearPlane = 0.1;
    camera.farPlane = 100.0;
    GBufferOptions o;
    o.width = W;
    o.height = H;
    o.withBackDepth = true;
    auto g = GBuffer::create(o);
    ASSERT_TRUE(g) << g.error();
    GpuScene gpu(scene);
    ASSERT_TRUE(g.value()->render(gpu, camera));
    const Image front = g.value()->readDepth(), back = g.value()->readBackDepth();
    const shared::SslrProjection p = shared::sslrProjectionFromMatrix(g.value()->clipFromView(), true);
    const float frontDist = shared::sslrViewDepthFromDepth(p, front.at(W / 2, H / 2, 0));
    const float backDist = shared::sslrViewDepthFromDepth(p, back.at(W / 2, H / 2, 0));
    EXPECT_NEAR(frontDist, 4.5f, 1e-3f) << "mirrorX " << mirrorX;
    EXPECT_NEAR(backDist, 5.5f, 1e-3f) << "mirrorX " << mirrorX;
    EXPECT_EQ(back.at(1, 1, 0), 0.0f) << "reversed Z clears to 0; nothing lies behind the corner pixel";
  }
}

// A back-face depth that is not the frame's size, not a depth format, or the depth texture itself
// is refused, the message naming it.
TEST_F(Api, BadBackDepthTextureIsNamed) {
  Frame f;
  auto ctx = makeContext();
  ASSERT_TRUE(ctx);
  FrameInputs in = f.gbuffer->frameInputs();
  const GLuint small = makeTexture(GL_DEPTH_COMPONENT32F, W / 2, H / 2), colour = makeTexture(GL_RGBA8);
  const std::pair<GLuint, const char*> cases[] = {
      {small, "32x24 but the context is 64x48"}, {colour, "expected a depth format"}, {in.depthTexture, "itself"}};
  for (const auto& [tex, expected] : cases) {
    in.backDepthTexture = tex;
    const Status st = ctx->dispatch(in, Settings{});
    ASSERT_FALSE(st) << expected;
    EXPECT_NE(st.message().find("backDepthTexture"), std::string::npos) << st.message();
    EXPECT_NE(st.message().find(expected), std::string::npos) << st.message();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  }
  glDeleteTextures(1, &small);
  glDeleteTextures(1, &colour);
}

// A mask limits where rays start: masked-out pixels get nothing (and no tile is listed for them),
// the others get exactly what they get without a mask (hits: the blur is not compared). Its edge
// runs through 2x2 quads and an 8x8 tile, which classification reads a quad at a time.
TEST_F(Api, MaskTextureLimitsWhereRaysStart) {
  auto ctx = makeContext();
  Frame f;
  FrameInputs in = f.gbuffer->frameInputs();
  Settings s;
  s.debug.outputs = true;
  s.debug.collectStats = true;
  ASSERT_TRUE(ctx->dispatch(in, s));
  const Image hitAll = readAll(ctx->hitTexture(), 4);
  const FrameStats statsAll = ctx->waitForStats();
  const int kMaskEdge = W / 2 + 3;  // odd: inside a quad and a tile
  std::vector<std::uint8_t> mask(static_cast<size_t>(W) * H, 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < kMaskEdge; ++x) mask[static_cast<size_t>(y) * W + x] = 255;  // left of x = 35
  const GLuint maskTex = makeTexture(GL_R8);
  glTextureSubImage2D(maskTex, 0, 0, 0, W, H, GL_RED, GL_UNSIGNED_BYTE, mask.data());
  in.maskTexture = maskTex;
  ASSERT_TRUE(ctx->dispatch(in, s));
  const Image hitMasked = readAll(ctx->hitTexture(), 4), resolvedMasked = readAll(ctx->resolvedTexture(), 4);
  const FrameStats statsMasked = ctx->waitForStats();
  size_t leftTraced = 0, leftSame = 0, rightNonZero = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t p = static_cast<size_t>(y) * W + x;
      if (x < kMaskEdge) {
        if (hitAll.pixels[p * 4 + 2] > 0.5f) {
          ++leftTraced;
          leftSame += std::equal(&hitAll.pixels[p * 4], &hitAll.pixels[p * 4] + 4, &hitMasked.pixels[p * 4]);
        }
      } else {
        for (int c = 0; c < 4; ++c) rightNonZero += hitMasked.pixels[p * 4 + c] != 0.0f || resolvedMasked.pixels[p * 4 + c] != 0.0f;
      }
    }
  ASSERT_GT(leftTraced, 300u);
  EXPECT_EQ(leftSame, leftTraced);
  EXPECT_EQ(rightNonZero, 0u);
  EXPECT_LT(statsMasked.tracedPixels, statsAll.tracedPixels);
  EXPECT_LT(statsMasked.tiles, statsAll.tiles);
  // A mask that is not a colour texture is refused, naming it.
  in.maskTexture = in.depthTexture;
  const Status st = ctx->dispatch(in, s);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("maskTexture"), std::string::npos) << st.message();
  glDeleteTextures(1, &maskTex);
}

// Every optional input and pass at once compiles the programs with the most #defines; their
// debug labels (the defines) once ran past GL_MAX_LABEL_LENGTH, a GL error on every first use.
TEST_F(Api, EveryOptionAtOnceLeavesNoGlError) {
  auto ctx = makeContext(W, H, traversalIn(TraversalPass::Deferred));
  Frame f;
  FrameInputs in = f.gbuffer->frameInputs();
  const GLuint maskTex = makeTexture(GL_R8), materialTex = makeTexture(GL_RGBA8);
  const std::vector<std::uint8_t> ones(static_cast<size_t>(W) * H, 255);
  glTextureSubImage2D(maskTex, 0, 0, 0, W, H, GL_RED, GL_UNSIGNED_BYTE, ones.data());
  std::vector<std::uint8_t> mirror(static_cast<size_t>(W) * H * 4, 0);  // roughness (B) 0, reflectance (A) 1
  for (size_t p = 3; p < mirror.size(); p += 4) mirror[p] = 255;
  glTextureSubImage2D(materialTex, 0, 0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, mirror.data());
  in.maskTexture = maskTex;
  in.materialTexture = materialTex;
  in.surface.space = NormalSpace::World;
  in.viewFromWorld = f.gbuffer->viewFromWorld();
  Settings s = Settings::preset(Preset::Ultra);
  s.halfResolution = true;
  s.debug.outputs = true;
  s.debug.collectStats = true;
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  ASSERT_TRUE(ctx->dispatch(in, s));
  EXPECT_GT(ctx->waitForStats().tracedPixels, 0u);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glDeleteTextures(1, &maskTex);
  glDeleteTextures(1, &materialTex);
}

TEST_F(Api, ArticleXyzNormalsGiveTheSameHitsAsOctahedral) {
  auto ctx = makeContext();
  Settings s;
  s.debug.outputs = true;
  Frame oct(DepthMode::Reversed, NormalEncoding::Octahedral);
  ASSERT_TRUE(ctx->dispatch(oct.gbuffer->frameInputs(), s));
  const Image hitOct = readAll(ctx->hitTexture(), 4);
  Frame xyz(DepthMode::Reversed, NormalEncoding::XyzUnorm);
  ASSERT_TRUE(ctx->dispatch(xyz.gbuffer->frameInputs(), s));
  const Image hitXyz = readAll(ctx->hitTexture(), 4);
  size_t both = 0, close = 0;
  for (int p = 0; p < W * H; ++p) {
    if (hitOct.pixels[p * 4 + 2] > 0.5f && hitXyz.pixels[p * 4 + 2] > 0.5f) {
      ++both;
      const float du = (hitOct.pixels[p * 4] - hitXyz.pixels[p * 4]) * W;
      const float dv = (hitOct.pixels[p * 4 + 1] - hitXyz.pixels[p * 4 + 1]) * H;
      close += std::hypot(du, dv) <= 1.0f;
    }
  }
  ASSERT_GT(both, 100u);
  // 8-bit xyz normals err by up to 0.39 deg (0.78 deg reflected): a few hits may move a pixel.
  EXPECT_GE(double(close) / both, 0.95);
}

// Depth pyramids alive in the GL context.
size_t pyramidCount() { return sslr::test::texturesLabelled("sslr.depthPyramid").size(); }

// Memory only for what a frame uses: the depth pyramid (~10.7 B per pixel) is allocated by the
// first dispatch that traces it (a host on adaptive L alone or on the tutorial's method never pays
// for it), the hit record and iteration images (20 B per pixel) by the first with debug.outputs.
// After a resize, again on use.
TEST_F(Api, MemoryIsAllocatedOnlyForWhatAFrameUses) {
  const size_t before = pyramidCount();
  auto ctx = makeContext();
  Frame f;
  Settings alone;
  alone.traversal.maxSteps = 0;
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), alone));
  EXPECT_EQ(pyramidCount(), before) << "adaptive L alone traces no pyramid";
  EXPECT_EQ(ctx->hitTexture(), 0u);
  EXPECT_EQ(ctx->iterationsTexture(), 0u);
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));
  EXPECT_EQ(pyramidCount(), before + 1);
  EXPECT_EQ(ctx->hitTexture(), 0u) << "no debug outputs asked for";
  Settings debug;
  debug.debug.outputs = true;
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), debug));
  EXPECT_NE(ctx->hitTexture(), 0u);
  EXPECT_NE(ctx->iterationsTexture(), 0u);
  const Image hit = readAll(ctx->hitTexture(), 4);
  size_t hits = 0;
  for (size_t i = 2; i < hit.pixels.size(); i += 4) hits += hit.pixels[i] > 0.5f;
  EXPECT_GT(hits, 0u) << "the debug frame wrote its hits";
  ASSERT_TRUE(ctx->resize(W / 2, H / 2));
  EXPECT_EQ(pyramidCount(), before) << "resize frees it";
  EXPECT_EQ(ctx->hitTexture(), 0u);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(Api, ResizeFollowsTheHost) {
  auto ctx = makeContext();
  EXPECT_FALSE(ctx->resize(0, 5));
  ASSERT_TRUE(ctx->resize(32, 16));
  EXPECT_EQ(ctx->width(), 32);
  Frame f;  // 64x48 textures no longer match
  const Status st = ctx->dispatch(f.gbuffer->frameInputs(), Settings{});
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("32x16"), std::string::npos) << st.message();
  ASSERT_TRUE(ctx->resize(W, H));
  EXPECT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));
}

}  // namespace

namespace {

// Composites the context's last frame into a new `format` target cleared to `clear`, with the
// host state `hostState` sets on and `check` run after the call (it also puts the state back):
// the target's pixels, as floats.
std::vector<float> compositeInto(Context& ctx, GLenum format, float clear, const std::function<void()>& hostState,
                                 const std::function<void()>& check) {
  GLuint target = makeTexture(format), fbo = 0;
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
  const float colour[4] = {clear, clear, clear, 1.0f};
  glClearNamedFramebufferfv(fbo, GL_COLOR, 0, colour);
  hostState();
  EXPECT_TRUE(ctx.composite(fbo));
  check();
  std::vector<float> pixels(static_cast<size_t>(W) * H * 4);
  glGetTextureImage(target, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pixels.size() * sizeof(float)), pixels.data());
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &target);
  return pixels;
}

// A host that left a wireframe polygon mode on still gets the filled composite (issue: engine
// integration, item 6), and gets its polygon mode back.
TEST_F(Api, CompositeIsFilledWhateverThePolygonMode) {
  auto ctx = makeContext();
  Frame f;
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));
  auto withPolygonMode = [&](GLenum mode) {
    return compositeInto(*ctx, GL_RGBA16F, 0.0f, [&] { glPolygonMode(GL_FRONT_AND_BACK, mode); }, [&] {
      GLint after[2] = {0, 0};
      glGetIntegerv(GL_POLYGON_MODE, after);
      EXPECT_EQ(after[0], GLint(mode)) << "the host's polygon mode is restored";
      glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    });
  };
  const std::vector<float> filled = withPolygonMode(GL_FILL);
  const std::vector<float> wire = withPolygonMode(GL_LINE);
  double energy = 0.0;
  for (float v : filled) energy += v;
  ASSERT_GT(energy, 1.0) << "the frame must have reflections";
  EXPECT_EQ(wire, filled);
}

// A host drawing with an upper-left clip origin (glClipControl, D3D-style) gets the composite in
// the same texels as a lower-left host: the tiles are placed in the textures' rows, which are the
// framebuffer's. Its clip control comes back as it was.
TEST_F(Api, CompositeIsTheSameUnderEitherClipOrigin) {
  auto ctx = makeContext();
  Frame f;
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));
  auto withOrigin = [&](GLenum origin, GLenum depthMode) {
    return compositeInto(*ctx, GL_RGBA16F, 0.0f, [&] { glClipControl(origin, depthMode); }, [&] {
      GLint after = 0, afterDepth = 0;
      glGetIntegerv(GL_CLIP_ORIGIN, &after);
      glGetIntegerv(GL_CLIP_DEPTH_MODE, &afterDepth);
      EXPECT_EQ(after, GLint(origin)) << "the host's clip origin is restored";
      EXPECT_EQ(afterDepth, GLint(depthMode)) << "the host's clip depth mode is restored";
      glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    });
  };
  const std::vector<float> lowerLeft = withOrigin(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  double energy = 0.0;
  for (float v : lowerLeft) energy += v;
  ASSERT_GT(energy, 1.0) << "the frame must have reflections";
  EXPECT_EQ(withOrigin(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE), lowerLeft);
  EXPECT_EQ(withOrigin(GL_UPPER_LEFT, GL_ZERO_TO_ONE), lowerLeft);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// An upper-left host (glClipControl(GL_UPPER_LEFT, ...)) stores its G-buffer with row 0 at the
// top. Given its projection with the y row negated (what the rows mean to a lower-left reader, as
// integration.md says), dispatch traces the same reflections, stored in the host's rows: here the
// lower-left G-buffer is mirrored row by row into new textures and the output mirrored back.
TEST_F(Api, UpperLeftHostsPassTheirProjectionWithYNegated) {
  auto ctx = makeContext();
  Frame f;
  const FrameInputs lowerLeft = f.gbuffer->frameInputs();
  ASSERT_TRUE(ctx->dispatch(lowerLeft, Settings{}));
  const Image expected = readAll(ctx->resolvedTexture(), 4);
  auto mirrored = [](GLuint tex) -> GLuint {
    if (tex == 0) return 0;
    GLint format = 0;
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    const GLuint copy = makeTexture(static_cast<GLenum>(format));
    for (int row = 0; row < H; ++row)
      glCopyImageSubData(tex, GL_TEXTURE_2D, 0, 0, row, 0, copy, GL_TEXTURE_2D, 0, 0, H - 1 - row, 0, W, 1, 1);
    return copy;
  };
  FrameInputs upperLeft = lowerLeft;
  for (GLName* tex : {&upperLeft.depthTexture, &upperLeft.colorTexture, &upperLeft.normalTexture,
                      &upperLeft.materialTexture, &upperLeft.maskTexture, &upperLeft.backDepthTexture})
    *tex = mirrored(*tex);
  upperLeft.clipFromView = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, -1.0, 1.0)) * lowerLeft.clipFromView;
  ASSERT_TRUE(ctx->dispatch(upperLeft, Settings{}));
  const Image got = readAll(ctx->resolvedTexture(), 4);
  // The pyramid's coarse cells are aligned to the other edge, so a traversal may take other steps:
  // a few pixels may differ; the image may not.
  size_t differing = 0, covered = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t a = (static_cast<size_t>(y) * W + x) * 4, b = (static_cast<size_t>(H - 1 - y) * W + x) * 4;
      covered += expected.pixels[a + 3] > 0.1f;
      float diff = 0.0f;
      for (int c = 0; c < 4; ++c) diff = std::max(diff, std::abs(expected.pixels[a + c] - got.pixels[b + c]));
      differing += diff > 0.02f;
    }
  ASSERT_GT(covered, 300u) << "the frame must have reflections";
  EXPECT_LE(differing, covered / 50) << differing << " of " << covered << " reflective pixels differ";
  // Unflipped, the same projection reads the rows upside down: another image altogether.
  upperLeft.clipFromView = lowerLeft.clipFromView;
  ASSERT_TRUE(ctx->dispatch(upperLeft, Settings{}));
  const Image wrong = readAll(ctx->resolvedTexture(), 4);
  size_t wrongDiffering = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t a = (static_cast<size_t>(y) * W + x) * 4, b = (static_cast<size_t>(H - 1 - y) * W + x) * 4;
      wrongDiffering += std::abs(expected.pixels[a + 3] - wrong.pixels[b + 3]) > 0.02f;
    }
  EXPECT_GT(wrongDiffering, covered / 10) << "the check must see a projection that was not flipped";
  for (GLName tex : {upperLeft.depthTexture, upperLeft.colorTexture, upperLeft.normalTexture, upperLeft.materialTexture,
                     upperLeft.maskTexture, upperLeft.backDepthTexture})
    if (tex != 0) glDeleteTextures(1, &tex);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// A host's per-fragment state that would change what the composite writes (a logic op on a
// fixed-point target, alpha-to-coverage, a clip distance its vertex shader does not write) is
// switched off for its draw and restored after it: the target gets the same pixels.
TEST_F(Api, CompositeIsUnchangedByTheHostsFragmentState) {
  auto ctx = makeContext();
  Frame f;
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));
  auto withCap = [&](GLenum cap) {
    return compositeInto(
        *ctx, GL_RGBA8, 0.25f,
        [&] {
          glLogicOp(GL_XOR);
          if (cap != GL_NONE) glEnable(cap);
        },
        [&] {
          if (cap != GL_NONE) {
            EXPECT_TRUE(glIsEnabled(cap)) << "the host's state is restored";
            glDisable(cap);
          }
          glLogicOp(GL_COPY);
        });
  };
  const std::vector<float> plain = withCap(GL_NONE);
  size_t changed = 0;
  for (size_t i = 0; i < plain.size(); i += 4) changed += plain[i] != 64.0f / 255.0f ? 1 : 0;
  ASSERT_GT(changed, 100u) << "the frame must have reflections";
  for (GLenum cap : {GL_COLOR_LOGIC_OP, GL_SAMPLE_ALPHA_TO_COVERAGE, GL_CLIP_DISTANCE0})
    EXPECT_EQ(withCap(cap), plain) << "with cap 0x" << std::hex << cap << " enabled";
}

TEST_F(Api, CompositeRefusesATargetSmallerThanTheContext) {
  auto ctx = makeContext();
  Frame f;
  ASSERT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));
  GLuint small = makeTexture(GL_RGBA16F, W / 2, H), fbo = 0;
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, small, 0);
  const Status st = ctx->composite(fbo);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("is 32x48, smaller than the context's 64x48"), std::string::npos) << st.message();
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &small);
}

// Host framebuffers as hosts make them: an unsized GL_RGBA texture (glTexImage2D) or renderbuffer
// is prepared and composited into; integer targets (GL leaves a blended draw into them undefined)
// and a texture or renderbuffer deleted while attached are refused by both, named; no call leaves a
// GL error of its own.
TEST_F(Api, PrepareAndCompositeTakeUnsizedTargetsAndRefuseIntegerAndDeletedOnes) {
  auto ctx = makeContext();
  Frame f;
  auto texture = [](GLenum internalFormat, GLenum format, GLenum type) {
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internalFormat), W, H, 0, format, type, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
  };
  auto renderbuffer = [](GLenum internalFormat) {
    GLuint r = 0;
    glCreateRenderbuffers(1, &r);
    glNamedRenderbufferStorage(r, internalFormat, W, H);
    return r;
  };
  auto framebufferOf = [](GLuint image, bool isTexture) {
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    if (isTexture) glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, image, 0);
    else glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, image);
    return fbo;
  };
  auto both = [&](GLuint fbo) {
    PrepareOptions warm;
    warm.composite = true;
    warm.framebuffer = fbo;
    Status prepared = ctx->prepare(f.gbuffer->frameInputs(), Settings{}, warm);
    EXPECT_TRUE(ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));  // prepare() leaves no frame
    return std::pair{prepared, ctx->composite(fbo)};
  };
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  for (bool isTexture : {true, false}) {
    const GLuint image = isTexture ? texture(GL_RGBA, GL_RGBA, GL_UNSIGNED_BYTE) : renderbuffer(GL_RGBA);
    const GLuint fbo = framebufferOf(image, isTexture);
    ASSERT_EQ(glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER), static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));
    const auto [prepared, composited] = both(fbo);
    EXPECT_TRUE(prepared) << (isTexture ? "unsized texture: " : "unsized renderbuffer: ") << prepared.message();
    EXPECT_TRUE(composited) << composited.message();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << (isTexture ? "texture" : "renderbuffer");
    glDeleteFramebuffers(1, &fbo);
    isTexture ? glDeleteTextures(1, &image) : glDeleteRenderbuffers(1, &image);
  }
  for (bool isTexture : {true, false}) {
    const GLuint image = isTexture ? texture(GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT) : renderbuffer(GL_RGBA8I);
    const GLuint fbo = framebufferOf(image, isTexture);
    const auto [prepared, composited] = both(fbo);
    for (const Status* st : {&prepared, &composited}) {
      ASSERT_FALSE(*st) << (isTexture ? "RGBA32UI" : "RGBA8I");
      EXPECT_EQ(st->code(), StatusCode::InvalidInput);
      EXPECT_NE(st->message().find("holds integers"), std::string::npos) << st->message();
    }
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    glDeleteFramebuffers(1, &fbo);
    isTexture ? glDeleteTextures(1, &image) : glDeleteRenderbuffers(1, &image);
  }
  for (bool isTexture : {true, false}) {
    GLuint image = isTexture ? makeTexture(GL_RGBA8, W, H) : renderbuffer(GL_RGBA8);
    const GLuint fbo = framebufferOf(image, isTexture);  // not bound: deleting keeps it attached
    isTexture ? glDeleteTextures(1, &image) : glDeleteRenderbuffers(1, &image);
    const auto [prepared, composited] = both(fbo);
    for (const Status* st : {&prepared, &composited}) {
      if (!*st) EXPECT_NE(st->message().find("was deleted"), std::string::npos) << st->message();
      else ADD_FAILURE() << "a deleted " << (isTexture ? "texture" : "renderbuffer") << " was accepted";
    }
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << (isTexture ? "texture" : "renderbuffer");
    glDeleteFramebuffers(1, &fbo);
  }
}

TEST_F(Api, CallsWithoutACurrentContextSaySo) {
  auto ctx = makeContext();
  Frame f;
  const FrameInputs in = f.gbuffer->frameInputs();
  EGLDisplay display = eglGetCurrentDisplay();
  EGLContext context = eglGetCurrentContext();
  EGLSurface draw = eglGetCurrentSurface(EGL_DRAW), read = eglGetCurrentSurface(EGL_READ);
  ASSERT_TRUE(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
  const Status dispatched = ctx->dispatch(in, Settings{});
  const Status composited = ctx->composite(0);
  const Status prepared = ctx->prepare(in, Settings{});
  const Status resized = ctx->resize(W / 2, H / 2);  // would free and make its targets in no context
  ASSERT_TRUE(eglMakeCurrent(display, draw, read, context));
  for (const Status* st : {&prepared, &resized}) {
    ASSERT_FALSE(*st);
    EXPECT_EQ(st->code(), StatusCode::NoCurrentContext) << st->message();
  }
  EXPECT_NE(resized.message().find("resize(): no OpenGL context is current"), std::string::npos) << resized.message();
  EXPECT_EQ(ctx->width(), W) << "a refused resize keeps the size";
  EXPECT_NE(ctx->resolvedTexture(), 0u) << "a refused resize keeps the targets";
  ASSERT_FALSE(dispatched);
  EXPECT_NE(dispatched.message().find("dispatch(): no OpenGL context is current"), std::string::npos)
      << dispatched.message();
  ASSERT_FALSE(composited);
  EXPECT_NE(composited.message().find("composite(): no OpenGL context is current"), std::string::npos)
      << composited.message();
  EXPECT_EQ(dispatched.code(), StatusCode::NoCurrentContext);
  EXPECT_EQ(composited.code(), StatusCode::NoCurrentContext);
  EXPECT_TRUE(ctx->dispatch(in, Settings{})) << "the same context works once current again";
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  const Image resolved = readAll(ctx->resolvedTexture(), 4);
  double coverage = 0.0;
  for (size_t i = 3; i < resolved.pixels.size(); i += 4) coverage += resolved.pixels[i];
  EXPECT_GT(coverage, 1.0) << "the frame after the refused calls has its reflections";
}

// Every error carries a code of its kind (Status::code), also through Expected (status()), so a
// host can react by kind: settings, inputs, projection, size, GL, the order of calls.
TEST_F(Api, ErrorsCarryTheirKind) {
  ContextDesc zero;
  zero.getProcAddress = HeadlessContext::getProcAddress();
  auto sized = Context::create(zero);
  ASSERT_FALSE(sized);
  EXPECT_EQ(sized.status().code(), StatusCode::InvalidSize) << sized.error();
  ContextDesc noLoader;
  noLoader.width = W;
  noLoader.height = H;
  auto loaderless = Context::create(noLoader);
  ASSERT_FALSE(loaderless);
  EXPECT_EQ(loaderless.status().code(), StatusCode::GlUnavailable) << loaderless.error();
  ContextDesc badPass = noLoader;
  badPass.getProcAddress = HeadlessContext::getProcAddress();
  badPass.traversalPass = static_cast<TraversalPass>(7);
  auto passless = Context::create(badPass);
  ASSERT_FALSE(passless);
  EXPECT_EQ(passless.status().code(), StatusCode::InvalidSettings) << passless.error();
  EXPECT_NE(passless.error().find("traversalPass = 7"), std::string::npos) << passless.error();

  auto ctx = makeContext();
  ASSERT_TRUE(ctx);
  const Status early = ctx->composite(0);
  EXPECT_EQ(early.code(), StatusCode::NoFrame) << early.message();
  Frame f;
  const FrameInputs good = f.gbuffer->frameInputs();
  Settings bad;
  bad.adaptiveL.maxIterations = 0;
  EXPECT_EQ(ctx->dispatch(good, bad).code(), StatusCode::InvalidSettings);
  EXPECT_EQ(ctx->prepare(good, bad).code(), StatusCode::InvalidSettings);
  FrameInputs identity = good;
  identity.clipFromView = glm::dmat4(1.0);
  EXPECT_EQ(ctx->dispatch(identity, Settings{}).code(), StatusCode::InvalidProjection);
  FrameInputs small = good;
  const GLuint tiny = makeTexture(GL_RGBA8, W / 2, H / 2);
  small.colorTexture = tiny;
  const Status wrongSize = ctx->dispatch(small, Settings{});
  EXPECT_EQ(wrongSize.code(), StatusCode::InvalidInput) << wrongSize.message();
  EXPECT_STREQ(toString(wrongSize.code()), "invalid input");
  const Status fine = ctx->dispatch(good, Settings{});
  EXPECT_TRUE(fine);
  EXPECT_EQ(fine.code(), StatusCode::Ok);
  glDeleteTextures(1, &tiny);
}

}  // namespace

namespace {

// NaN in a single texel and in a whole 8x8 tile of each G-buffer texture (it happens in real
// engines; the RGBA16 unorm normal stores it as 0, a zero normal): no output anywhere turns
// NaN/Inf, no GL error (fixture), and the next clean frame is exactly the clean frame (nothing of
// the poisoned one is carried over: pyramid, tile lists, blur stamps).
TEST_F(Api, PoisonedTexelsStayLocalAndLeaveNoTrace) {
  auto ctx = makeContext();
  Frame f;
  const FrameInputs in = f.gbuffer->frameInputs();
  Settings s;
  s.debug.outputs = true;
  ASSERT_TRUE(ctx->dispatch(in, s));
  const Image cleanResolved = readAll(ctx->resolvedTexture(), 4), cleanHit = readAll(ctx->hitTexture(), 4);
  const float nan = NAN;
  struct Target {
    GLuint texture;
    GLenum format;
    int channels;
    const char* name;
  } targets[] = {{in.colorTexture, GL_RGBA, 4, "colour"}, {in.normalTexture, GL_RGBA, 4, "normal"},
                 {in.depthTexture, GL_DEPTH_COMPONENT, 1, "depth"}};
  for (const Target& t : targets)
    for (int size : {1, 8}) {
      const int x0 = W / 2 - size / 2, y0 = H / 3;  // on the mirror floor, where rays start and land
      std::vector<float> saved(static_cast<size_t>(size) * size * t.channels), poison(saved.size(), nan);
      glGetTextureSubImage(t.texture, 0, x0, y0, 0, size, size, 1, t.format, GL_FLOAT,
                           static_cast<GLsizei>(saved.size() * sizeof(float)), saved.data());
      glTextureSubImage2D(t.texture, 0, x0, y0, size, size, t.format, GL_FLOAT, poison.data());
      ASSERT_TRUE(ctx->dispatch(in, s));
      for (GLuint out : {ctx->reflectionTexture(), ctx->resolvedTexture(), ctx->hitTexture()})
        EXPECT_EQ(countNonFinite(readAll(out, 4)), 0u) << t.name << " " << size << "x" << size;
      glTextureSubImage2D(t.texture, 0, x0, y0, size, size, t.format, GL_FLOAT, saved.data());
      ASSERT_TRUE(ctx->dispatch(in, s));
      EXPECT_EQ(readAll(ctx->resolvedTexture(), 4).pixels, cleanResolved.pixels) << t.name << " " << size;
      EXPECT_EQ(readAll(ctx->hitTexture(), 4).pixels, cleanHit.pixels) << t.name << " " << size;
    }
}

}  // namespace
