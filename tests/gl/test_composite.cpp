// The production output (resolved rgb = reflection, a = coverage) and both composite modes, checked
// pixel by pixel against the formulas in sslr.hpp on float and fixed-point targets.
#include <algorithm>
#include <cmath>

#include "gl/gl_fixture.hpp"
#include "sslr/sslr.hpp"
#include "sslr_host/gbuffer.hpp"

using namespace sslr;
using namespace sslr::host;

namespace {

constexpr int W = 96, H = 54;

struct Fixture {
  std::unique_ptr<GBuffer> gbuffer;
  std::unique_ptr<Context> ctx;
  explicit Fixture(const std::string& sceneName) {
    GBufferOptions o;
    o.width = W;
    o.height = H;
    auto g = GBuffer::create(o);
    EXPECT_TRUE(g) << g.error();
    gbuffer = std::move(g.value());
    auto s = makeBuiltinScene(sceneName);
    EXPECT_TRUE(s) << s.error();
    GpuScene gpu(s.value());
    EXPECT_TRUE(gbuffer->render(gpu, *s.value().camera));
    ContextDesc d{W, H, HeadlessContext::getProcAddress(), {}};
    auto c = Context::create(d);
    EXPECT_TRUE(c) << c.error();
    ctx = std::move(c.value());
  }
};

GLuint makeTexture(GLenum format, glm::vec4 value) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, W, H);
  glClearTexImage(t, 0, GL_RGBA, GL_FLOAT, &value.x);
  return t;
}

float maxChannel(const Image& img) { return *std::max_element(img.pixels.begin(), img.pixels.end()); }

class Composite : public sslr::test::GlTest {};
class CompositeCoverage : public sslr::test::GlTest, public ::testing::WithParamInterface<const char*> {};

// Coverage is a fraction, the reflection never exceeds coverage x the brightest reflected colour
// (Fresnel <= 1), and the blur keeps that (both are blurred with the same weights). glossy has
// blurred panels, mirror-room sharp ones.
TEST_P(CompositeCoverage, CoverageIsAFractionAndBoundsTheReflection) {
  Fixture f(GetParam());
  ASSERT_TRUE(f.ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));
  const Image resolved = readTexture(f.ctx->resolvedTexture(), W, H, 4);
  const float brightest = maxChannel(f.gbuffer->readColor());
  int covered = 0;
  for (size_t i = 0; i < resolved.pixels.size(); i += 4) {
    const float coverage = resolved.pixels[i + 3];
    ASSERT_GE(coverage, 0.0f);
    ASSERT_LE(coverage, 1.0f);
    covered += coverage > 0.5f;
    for (int c = 0; c < 3; ++c) {
      const float rgb = resolved.pixels[i + c];
      ASSERT_GE(rgb, 0.0f);
      // RGBA16F rounding: 2^-10 relative on each stored value.
      ASSERT_LE(rgb, coverage * brightest * 1.002f + 1e-4f) << "pixel " << i / 4 << " coverage " << coverage;
    }
  }
  EXPECT_GT(covered, W * H / 20) << "the scene's mirrors should be mostly answered";
}

INSTANTIATE_TEST_SUITE_P(Scenes, CompositeCoverage, ::testing::Values("mirror-room", "glossy"),
                         [](const auto& info) {
                           std::string n = info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

// final = existing - coverage x fallback + reflection (BlendOverFallback), existing + reflection
// (Add), alpha kept, on RGBA16F and RGBA8 targets; a NaN fallback texel counts as 0.
TEST_F(Composite, ModesFollowTheirFormulas) {
  Fixture f("glossy");
  ASSERT_TRUE(f.ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));
  const Image resolved = readTexture(f.ctx->resolvedTexture(), W, H, 4);
  const glm::vec4 existing(0.55f, 0.5f, 0.45f, 0.7f), fallbackValue(0.3f, 0.2f, 0.1f, 1.0f);
  GLuint fallback = makeTexture(GL_RGBA16F, fallbackValue);
  // A poisoned texel where the trace answers.
  size_t poisoned = 0;
  for (size_t i = 0; i < resolved.pixels.size(); i += 4)
    if (resolved.pixels[i + 3] > 0.5f) poisoned = i / 4;
  ASSERT_GT(poisoned, 0u);
  const float nan4[4] = {NAN, NAN, NAN, NAN};
  glTextureSubImage2D(fallback, 0, int(poisoned % W), int(poisoned / W), 1, 1, GL_RGBA, GL_FLOAT, nan4);

  for (GLenum format : {GLenum(GL_RGBA16F), GLenum(GL_RGBA8)}) {
    for (CompositeMode mode : {CompositeMode::BlendOverFallback, CompositeMode::Add}) {
      GLuint target = makeTexture(format, existing);
      GLuint fbo = 0;
      glCreateFramebuffers(1, &fbo);
      glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
      const bool blend = mode == CompositeMode::BlendOverFallback;
      ASSERT_TRUE(f.ctx->composite(fbo, {mode, blend ? fallback : 0}));
      const Image out = readTexture(target, W, H, 4);
      const bool unorm = format == GL_RGBA8;
      // RGBA8 stores 1/255 steps (the clear, the subtraction and the sum each round once);
      // RGBA16F 2^-11 relative on values below 2.
      const float tolerance = unorm ? 1.6f / 255.0f : 2e-3f;
      int changed = 0;
      for (size_t p = 0; p < size_t(W) * H; ++p) {
        const float coverage = resolved.pixels[p * 4 + 3];
        for (int c = 0; c < 4; ++c) {
          float want = existing[c];
          if (c < 3) {
            const float fb = p == poisoned ? 0.0f : fallbackValue[c];
            float subtracted = blend ? want - coverage * fb : want;
            if (unorm) subtracted = std::clamp(subtracted, 0.0f, 1.0f);
            want = subtracted + resolved.pixels[p * 4 + c];
            if (unorm) want = std::clamp(want, 0.0f, 1.0f);
          }
          const float got = out.pixels[p * 4 + c];
          ASSERT_TRUE(std::isfinite(got)) << "pixel " << p;
          ASSERT_NEAR(got, want, tolerance) << "pixel " << p << " channel " << c << (blend ? " blend" : " add")
                                            << (unorm ? " RGBA8" : " RGBA16F");
        }
        changed += std::abs(out.pixels[p * 4] - existing.x) > 0.02f;
      }
      EXPECT_GT(changed, W * H / 50) << "the composite should change the reflective pixels";
      glDeleteFramebuffers(1, &fbo);
      glDeleteTextures(1, &target);
    }
  }
  glDeleteTextures(1, &fallback);
}

TEST_F(Composite, BadOptionsAreRefusedWithTheirName) {
  Fixture f("mirror-room");
  ASSERT_TRUE(f.ctx->dispatch(f.gbuffer->frameInputs(), Settings{}));
  GLuint target = makeTexture(GL_RGBA16F, glm::vec4(0.0f)), fbo = 0;
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
  GLuint wrongSize = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &wrongSize);
  glTextureStorage2D(wrongSize, 1, GL_RGBA16F, W / 2, H);
  GLuint twoChannels = makeTexture(GL_RG16F, glm::vec4(0.0f));
  struct Bad {
    CompositeOptions options;
    const char* expect;
  };
  const Bad cases[] = {
      {{CompositeMode::BlendOverFallback, 0}, "fallbackSpecularTexture (texture 0) is 0"},
      {{CompositeMode::BlendOverFallback, 987654}, "not a texture name"},
      {{CompositeMode::BlendOverFallback, wrongSize}, "is 48x54 but the context is 96x54"},
      {{CompositeMode::BlendOverFallback, twoChannels}, "needs 3"},
      {{CompositeMode::Add, twoChannels}, "the mode is Add, which does not read it"},
      {{static_cast<CompositeMode>(7), 0}, "mode 7 is not a CompositeMode"},
  };
  const Image before = readTexture(target, W, H, 4);
  for (const Bad& b : cases) {
    const Status st = f.ctx->composite(fbo, b.options);
    ASSERT_FALSE(st) << b.expect;
    EXPECT_NE(st.message().find(b.expect), std::string::npos) << "got: " << st.message();
    EXPECT_EQ(sslr::test::glContext()->glErrorCount(), 0) << "after: " << b.expect;
  }
  EXPECT_EQ(readTexture(target, W, H, 4).pixels, before.pixels) << "a refused composite drew";
  glDeleteFramebuffers(1, &fbo);
  const GLuint textures[] = {target, wrongSize, twoChannels};
  glDeleteTextures(3, textures);
}

}  // namespace
