// FrameInputs::viewport (dynamic resolution): a frame rendered into a rectangle of larger textures
// must give, in that rectangle, what the same frame gives in textures of its own size, whatever
// the rest of the textures holds; sslr writes nothing outside the rectangle; changing the
// rectangle from frame to frame reallocates nothing and leaves nothing of the last frame behind.
#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl_fixture.hpp"
#include "sslr/sslr.hpp"
#include "sslr_host/gbuffer.hpp"
#include "sslr_host/scene.hpp"

using namespace sslr;
using namespace sslr::host;

namespace {

constexpr int kTexW = 203, kTexH = 131;  // the context's (and the textures') size: odd on purpose

// A G-buffer of mirror-room at w x h, and what a context of its own size makes of it in its
// `frames`-th dispatch (half resolution's traced pixel in each quad follows the frame count).
struct Reference {
  std::unique_ptr<GBuffer> gbuffer;
  Image hit, reflection, resolved, composite;
  FrameStats stats;
};

std::unique_ptr<Context> makeContext(int w, int h) { return sslr::test::makeSslrContext(w, h); }

using sslr::test::compositeImage;

Reference makeReference(const Scene& scene, const GpuScene& gpu, int w, int h, const Settings& s, int frames) {
  Reference r;
  GBufferOptions o;
  o.width = w;
  o.height = h;
  auto g = GBuffer::create(o);
  EXPECT_TRUE(g) << g.error();
  r.gbuffer = std::move(g.value());
  EXPECT_TRUE(r.gbuffer->render(gpu, *scene.camera));
  auto ctx = makeContext(w, h);
  for (int k = 0; k < frames; ++k) EXPECT_TRUE(ctx->dispatch(r.gbuffer->frameInputs(), s));
  r.hit = readTexture(ctx->hitTexture(), w, h, 4);
  r.reflection = readTexture(ctx->reflectionTexture(), w, h, 4);
  r.resolved = readTexture(ctx->resolvedTexture(), w, h, 4);
  r.composite = compositeImage(*ctx, w, h);
  r.stats = ctx->waitForStats();
  return r;
}

// A kTexW x kTexH texture of `source`'s format holding copies of its w x h texels at each of
// `places`, in order (the last one on top): the host's other content around the frame.
GLuint largerCopy(GLuint source, int w, int h, const std::vector<glm::ivec2>& places) {
  GLint format = 0;
  glGetTextureLevelParameteriv(source, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, static_cast<GLenum>(format), kTexW, kTexH);
  for (glm::ivec2 p : places) {
    const int cw = std::min(w, kTexW - p.x), ch = std::min(h, kTexH - p.y);
    glCopyImageSubData(source, GL_TEXTURE_2D, 0, 0, 0, 0, t, GL_TEXTURE_2D, 0, p.x, p.y, 0, cw, ch, 1);
  }
  return t;
}

// Texels of `big` inside `rect` against `small` (exactly), and zeros outside it.
struct RegionCheck {
  size_t differing = 0, nonZeroOutside = 0, nonZeroInside = 0;
  float maxDifference = 0.0f;  // |big - small| / max(1, |small|)
};
RegionCheck compareRegion(const Image& big, const Image& small, const Viewport& rect) {
  RegionCheck c;
  const int channels = big.channels;
  for (int y = 0; y < kTexH; ++y)
    for (int x = 0; x < kTexW; ++x)
      for (int k = 0; k < channels; ++k) {
        const float v = big.at(x, y, k);
        const bool inside = x >= rect.x && y >= rect.y && x < rect.x + rect.width && y < rect.y + rect.height;
        if (!inside) {
          c.nonZeroOutside += v != 0.0f;
          continue;
        }
        const float r = small.at(x - rect.x, y - rect.y, k);
        c.differing += v != r;
        c.maxDifference = std::max(c.maxDifference, std::abs(v - r) / std::max(1.0f, std::abs(r)));
        c.nonZeroInside += v != 0.0f;
      }
  return c;
}

class Viewports : public sslr::test::GlTest, public ::testing::WithParamInterface<bool> {};

TEST_P(Viewports, ARectangleOfLargerTexturesTracesAsTexturesOfItsOwnSize) {
  auto scene = makeBuiltinScene("mirror-room");
  ASSERT_TRUE(scene);
  GpuScene gpu(scene.value());
  Settings s;
  s.halfResolution = GetParam();
  s.debug.outputs = true;
  s.debug.collectStats = true;
  // Frames in turn: a rectangle at an odd offset, a smaller one elsewhere (overlapping it), the
  // whole textures, the first again.
  const Viewport rects[] = {{37, 23, 150, 90}, {3, 50, 97, 61}, {0, 0, kTexW, kTexH}, {37, 23, 150, 90}};
  auto big = makeContext(kTexW, kTexH);
  ASSERT_TRUE(big);
  const GLName reflectionName = big->reflectionTexture(), resolvedName = big->resolvedTexture();
  for (int k = 0; k < 4; ++k) {
    const Viewport rect = rects[k];
    SCOPED_TRACE("frame " + std::to_string(k) + ": " + std::to_string(rect.width) + "x" + std::to_string(rect.height) +
                 " at (" + std::to_string(rect.x) + ", " + std::to_string(rect.y) + ")");
    const Reference ref = makeReference(scene.value(), gpu, rect.width, rect.height, s, k + 1);
    ASSERT_GT(ref.stats.tiles, 10u);
    FrameInputs in = ref.gbuffer->frameInputs();
    std::vector<GLuint> made;
    const bool whole = rect.width == kTexW && rect.height == kTexH;
    if (!whole) {
      // The frame's G-buffer at the rectangle, over copies of it elsewhere: plausible geometry all
      // around that a read outside the rectangle would pick up, and just past its right and top
      // edges the frame's middle (other depths than its edges').
      const std::vector<glm::ivec2> places{{0, 0},
                                           {kTexW - rect.width, kTexH - rect.height},
                                           {rect.x + rect.width / 2, rect.y + rect.height / 2},
                                           {rect.x, rect.y}};
      for (GLName* t : {&in.colorTexture, &in.normalTexture, &in.depthTexture}) {
        *t = largerCopy(*t, rect.width, rect.height, places);
        made.push_back(*t);
      }
      in.viewport = rect;
    }
    ASSERT_TRUE(big->dispatch(in, s));
    const FrameStats st = big->waitForStats();
    EXPECT_EQ(st.tiles, ref.stats.tiles);
    EXPECT_EQ(st.tracedPixels, ref.stats.tracedPixels);
    // The same walk through the same pyramid (a cell that took in a texel from outside the
    // rectangle would only widen, and change the fetches, not the hits).
    EXPECT_EQ(st.fetches, ref.stats.fetches);
    EXPECT_EQ(st.hierarchicalPixels, ref.stats.hierarchicalPixels);
    const RegionCheck hit = compareRegion(readTexture(big->hitTexture(), kTexW, kTexH, 4), ref.hit, rect);
    const RegionCheck reflection = compareRegion(readTexture(big->reflectionTexture(), kTexW, kTexH, 4), ref.reflection, rect);
    const RegionCheck resolved = compareRegion(readTexture(big->resolvedTexture(), kTexW, kTexH, 4), ref.resolved, rect);
    const RegionCheck composite = compareRegion(compositeImage(*big, kTexW, kTexH), ref.composite, rect);
    EXPECT_EQ(hit.differing, 0u);
    EXPECT_GT(hit.nonZeroInside, 1000u);
    // The colour is read bilinearly at the hit in both: the same texels, but through uv
    // coordinates of textures of different sizes, so the filter weights may differ in their
    // last bit. GPUs keep 8 fractional bits for them (NVIDIA: 6-7 texels of 13500 differ by up
    // to 2^-9.4), llvmpipe more (2 texels by 2^-14). Bound: one 2^-8 weight step on each axis
    // times a colour step of at most 1 between neighbouring texels, plus one step of a 16-bit
    // float's mantissa (the outputs' format); and such texels stay rare.
    const float weightBits = 2.0f / 256.0f + 1.0f / 1024.0f;
    const size_t rare = static_cast<size_t>(rect.width) * rect.height * 4 / 1000;
    for (const auto& [what, c] : {std::pair{"reflection", reflection}, std::pair{"resolved", resolved},
                                  std::pair{"composite", composite}}) {
      EXPECT_LE(c.maxDifference, weightBits) << what << ": " << c.differing << " texels differ";
      EXPECT_LE(c.differing, rare) << what << ": largest difference " << c.maxDifference;
    }
    EXPECT_GT(resolved.nonZeroInside, 1000u);
    // Nothing outside the rectangle, this frame's or (cleared) the last one's.
    EXPECT_EQ(reflection.nonZeroOutside, 0u);
    EXPECT_EQ(resolved.nonZeroOutside, 0u);
    EXPECT_EQ(composite.nonZeroOutside, 0u);
    EXPECT_EQ(big->reflectionTexture(), reflectionName) << "no reallocation";
    EXPECT_EQ(big->resolvedTexture(), resolvedName) << "no reallocation";
    glDeleteTextures(static_cast<GLsizei>(made.size()), made.data());
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

INSTANTIATE_TEST_SUITE_P(Resolutions, Viewports, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) { return info.param ? "half" : "full"; });

// A rectangle that does not lie inside the textures is refused, named, with no GL error and no
// frame (composite() then has nothing to draw).
TEST_F(Viewports, RectanglesOutsideTheTexturesAreRefused) {
  auto scene = makeBuiltinScene("mirror-room");
  ASSERT_TRUE(scene);
  GpuScene gpu(scene.value());
  GBufferOptions o;
  o.width = 64;
  o.height = 48;
  auto g = GBuffer::create(o);
  ASSERT_TRUE(g) << g.error();
  ASSERT_TRUE(g.value()->render(gpu, *scene.value().camera));
  auto ctx = makeContext(64, 48);
  const Viewport bad[] = {{-1, 0, 10, 10}, {0, -3, 10, 10}, {0, 0, -5, 10},     {0, 0, 10, 0},
                          {55, 0, 10, 10}, {0, 40, 10, 9},  {1, 0, 0, 0},       {0, 0, 65, 48},
                          {0x7fffffff, 0, 0x7fffffff, 1}};
  for (const Viewport& v : bad) {
    FrameInputs in = g.value()->frameInputs();
    in.viewport = v;
    const Status st = ctx->dispatch(in, Settings{});
    ASSERT_FALSE(st) << v.x << "," << v.y << " " << v.width << "x" << v.height;
    EXPECT_EQ(st.code(), StatusCode::InvalidInput);
    EXPECT_NE(st.message().find("FrameInputs::viewport"), std::string::npos) << st.message();
    EXPECT_FALSE(ctx->composite(0)) << "no frame after a refused dispatch";
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace

// Stereo today (integration.md, "Stereo and multiview"): a host whose G-buffer is a 2D array
// (one layer an eye) gives each eye's context texture views of its layer (glTextureView, one
// layer as GL_TEXTURE_2D). Each eye's outputs are then bit for bit those of the same frame in
// textures of its own.
class ArrayLayers : public sslr::test::GlTest {};

TEST_F(ArrayLayers, EachEyeTracesAViewOfItsLayerAsItsOwnTextures) {
  constexpr int kW = 160, kH = 96;
  auto scene = makeBuiltinScene("mirror-room");
  ASSERT_TRUE(scene);
  GpuScene gpu(scene.value());
  Settings s;
  s.debug.outputs = true;
  // The two eyes 0.064 units apart along the camera's right axis, looking the same way.
  Camera eyes[2] = {*scene.value().camera, *scene.value().camera};
  const glm::dvec3 right = glm::normalize(glm::cross(eyes[0].target - eyes[0].eye, eyes[0].up));
  for (int e = 0; e < 2; ++e) {
    const glm::dvec3 shift = right * (e == 0 ? -0.032 : 0.032);
    eyes[e].eye += shift;
    eyes[e].target += shift;
  }
  GBufferOptions o;
  o.width = kW;
  o.height = kH;
  std::unique_ptr<GBuffer> own[2];
  for (int e = 0; e < 2; ++e) {
    auto g = GBuffer::create(o);
    ASSERT_TRUE(g) << g.error();
    own[e] = std::move(g.value());
    ASSERT_TRUE(own[e]->render(gpu, eyes[e]));
  }
  // The host's layered G-buffer: each input a 2-layer array of the eye textures' format.
  const FrameInputs in0 = own[0]->frameInputs(), in1 = own[1]->frameInputs();
  GLName FrameInputs::*const inputs[] = {&FrameInputs::colorTexture, &FrameInputs::normalTexture,
                                         &FrameInputs::depthTexture};
  std::vector<GLuint> arrays, views;
  FrameInputs layered[2] = {in0, in1};
  for (const auto member : inputs) {
    GLint format = 0;
    glGetTextureLevelParameteriv(in0.*member, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    GLuint array = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &array);
    glTextureStorage3D(array, 1, static_cast<GLenum>(format), kW, kH, 2);
    for (int e = 0; e < 2; ++e) {
      const GLuint source = (e == 0 ? in0 : in1).*member;
      glCopyImageSubData(source, GL_TEXTURE_2D, 0, 0, 0, 0, array, GL_TEXTURE_2D_ARRAY, 0, 0, 0, e, kW, kH, 1);
      GLuint view = 0;
      glGenTextures(1, &view);  // a view takes a name that was never bound
      glTextureView(view, GL_TEXTURE_2D, array, static_cast<GLenum>(format), 0, 1, static_cast<GLuint>(e), 1);
      layered[e].*member = view;
      views.push_back(view);
    }
    arrays.push_back(array);
  }
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  size_t hitPixels = 0;
  for (int e = 0; e < 2; ++e) {
    SCOPED_TRACE(e == 0 ? "left eye" : "right eye");
    auto fromLayer = makeContext(kW, kH), fromOwn = makeContext(kW, kH);
    ASSERT_TRUE(fromLayer && fromOwn);
    ASSERT_TRUE(fromLayer->dispatch(layered[e], s));
    ASSERT_TRUE(fromOwn->dispatch(e == 0 ? in0 : in1, s));
    for (auto texture : {&Context::hitTexture, &Context::reflectionTexture, &Context::resolvedTexture}) {
      const Image a = readTexture(((*fromLayer).*texture)(), kW, kH, 4);
      const Image b = readTexture(((*fromOwn).*texture)(), kW, kH, 4);
      size_t differing = 0;
      for (size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i];
      EXPECT_EQ(differing, 0u);
    }
    const Image hit = readTexture(fromLayer->hitTexture(), kW, kH, 4);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) hitPixels += hit.at(x, y, 2) > 0.5f;
  }
  EXPECT_GT(hitPixels, 2000u);  // both eyes see the mirror room's reflections
  glDeleteTextures(static_cast<GLsizei>(views.size()), views.data());
  glDeleteTextures(static_cast<GLsizei>(arrays.size()), arrays.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}
