// The production output (resolved rgb = reflection, a = coverage), the blur that produces it and
// both composite modes, checked pixel by pixel against the formulas in sslr.hpp and sslr_shared.h
// on float and fixed-point targets.
#include <algorithm>
#include <cmath>

#include "gl/gl_fixture.hpp"
#include "sslr/reference.hpp"
#include "sslr/sslr.hpp"
#include "sslr_shared.h"
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

// The blur as sslr_shared.h defines it (sslrBlurTapWeight over the pixels sslrShouldTrace accepts,
// each pixel's radius from the trace's blur weight), run on the CPU: one axis of the separable
// filter over `in`, rounded to RGBA16F as the GPU's intermediate and output textures store it.
Image cpuBlurAxis(const Image& in, glm::ivec2 axis, const Image& reflection, const Image& depth, const Image& normals,
                  const shared::SslrFrame& f) {
  auto neighbour = [&](glm::ivec2 q, float& z, glm::vec3& n) {
    if (q.x < 0 || q.y < 0 || q.x >= W || q.y >= H) return false;
    const float d = depth.at(q.x, q.y, 0);
    const glm::vec4 texel(normals.at(q.x, q.y, 0), normals.at(q.x, q.y, 1), normals.at(q.x, q.y, 2), normals.at(q.x, q.y, 3));
    if (!shared::sslrShouldTrace(f.surface, f.trace, d, texel, texel)) return false;
    shared::sslrDecodeNormal(f.surface, texel, n);
    z = std::abs(shared::sslrViewFromUvDepth(f.proj, shared::sslrUvFromPixel(q, glm::vec2(W, H)), d).z);
    return true;
  };
  Image out = in;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float radius = reflection.at(x, y, 3) * f.trace.maxRadiusPx;
      if (!(radius >= 0.5f)) continue;
      float z0 = 0.0f;
      glm::vec3 n0(0.0f);
      neighbour({x, y}, z0, n0);
      glm::vec4 sum(in.at(x, y, 0), in.at(x, y, 1), in.at(x, y, 2), in.at(x, y, 3));
      float weightSum = 1.0f;
      const shared::SslrBlurCentre centre = shared::sslrBlurCentre(f.trace, radius, z0, n0);
      const int taps = static_cast<int>(std::ceil(radius));
      for (int i = -taps; i <= taps; ++i) {
        const glm::ivec2 q = glm::ivec2(x, y) + axis * i;
        float z1 = 0.0f;
        glm::vec3 n1(0.0f);
        if (i == 0 || !neighbour(q, z1, n1)) continue;
        const float w = shared::sslrBlurTapWeight(centre, i, z1, n1);
        sum += w * glm::vec4(in.at(q.x, q.y, 0), in.at(q.x, q.y, 1), in.at(q.x, q.y, 2), in.at(q.x, q.y, 3));
        weightSum += w;
      }
      for (int c = 0; c < 4; ++c) out.at(x, y, c) = sum[c] / weightSum;
    }
  for (float& v : out.pixels) v = glm::unpackHalf2x16(glm::packHalf2x16(glm::vec2(v, 0.0f))).x;
  return out;
}

struct BlurCase {
  float maxRadiusPx, coneScale;
  int widestPx;  // the test requires a pixel with at least this radius
};
void PrintTo(const BlurCase& c, std::ostream* os) {
  *os << "blur.maxRadiusPx " << c.maxRadiusPx << ", blur.coneScale " << c.coneScale;
}
class CompositeBlur : public sslr::test::GlTest, public ::testing::WithParamInterface<BlurCase> {};

// The GPU's blur (work groups staging their tile and its apron in shared memory) against the CPU
// filter above: the same pixels, weights and taps, from the trace's unblurred output (the same
// frame dispatched with the blur off). The default settings (radii up to 5.6 px here), and a cone 16
// times as wide with the largest radius setting, 32 px (radii up to 32: aprons of 32 px on both
// sides of an 8 px tile, reaching past the screen's borders). glossy's panels have radii from 0 up,
// edges in depth and normal, and a bottom row of partial tiles (54 = 6 x 8 + 6).
TEST_P(CompositeBlur, MatchesTheSharedHeadersFilterOnTheCpu) {
  Fixture f("glossy");
  Settings s;
  s.blur.maxRadiusPx = GetParam().maxRadiusPx;
  s.blur.coneScale = GetParam().coneScale;
  Settings raw = s;
  raw.blur.maxRadiusPx = 0.0f;  // no blur
  ASSERT_TRUE(f.ctx->dispatch(f.gbuffer->frameInputs(), raw));
  const Image unblurred = readTexture(f.ctx->resolvedTexture(), W, H, 4);
  ASSERT_TRUE(f.ctx->dispatch(f.gbuffer->frameInputs(), s));
  const Image gpu = readTexture(f.ctx->resolvedTexture(), W, H, 4);
  const Image reflection = readTexture(f.ctx->reflectionTexture(), W, H, 4);
  auto frame = frameConstants(f.gbuffer->frameInputs(), s, W, H);
  ASSERT_TRUE(frame) << frame.error();
  const Image depth = f.gbuffer->readDepth(), normals = f.gbuffer->readNormalPacked();
  const Image horizontal = cpuBlurAxis(unblurred, {1, 0}, reflection, depth, normals, frame.value());
  const Image cpu = cpuBlurAxis(horizontal, {0, 1}, reflection, depth, normals, frame.value());
  int blurred = 0, changed = 0;
  float widest = 0.0f;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      blurred += reflection.at(x, y, 3) * s.blur.maxRadiusPx >= 0.5f;
      widest = std::max(widest, reflection.at(x, y, 3) * s.blur.maxRadiusPx);
      float moved = 0.0f;
      for (int c = 0; c < 4; ++c) {
        const float want = cpu.at(x, y, c);
        // Two RGBA16F roundings (the intermediate, the output) may each land one step (2^-10
        // relative) apart where the GPU's exp and pow differ from the CPU's in the last bits.
        ASSERT_NEAR(gpu.at(x, y, c), want, 2.5e-3f * std::max(std::abs(want), 0.05f))
            << "pixel (" << x << ", " << y << ") channel " << c << ", radius "
            << reflection.at(x, y, 3) * s.blur.maxRadiusPx << " px";
        moved = std::max(moved, std::abs(want - unblurred.at(x, y, c)));
      }
      changed += moved > 0.02f;
    }
  // Not a vacuous match: the blur covers the rough panels and changes what it covers.
  EXPECT_GT(blurred, W * H / 10) << "blurred";
  EXPECT_GE(widest, static_cast<float>(GetParam().widestPx));
  EXPECT_GT(changed, W * H / 40) << "changed by more than 0.02";  // 246 measured
}

INSTANTIATE_TEST_SUITE_P(Radii, CompositeBlur, ::testing::Values(BlurCase{8.0f, 1.0f, 5}, BlurCase{32.0f, 16.0f, 30}),
                         [](const auto& info) { return "upTo" + std::to_string(static_cast<int>(info.param.maxRadiusPx)) + "px"; });

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
