#include "gl/gl_fixture.hpp"

#include <cstdlib>
#include <memory>

namespace sslr::test {

namespace {
std::unique_ptr<sslr::host::HeadlessContext> gContext;
std::string gError;
}  // namespace

sslr::host::HeadlessContext* glContext() { return gContext.get(); }
const std::string& glContextError() { return gError; }

std::vector<GLuint> texturesLabelled(const std::string& label) {
  std::vector<GLuint> found;
  for (GLuint name = 1; name < 4096; ++name) {
    if (!glIsTexture(name)) continue;
    char text[64] = {};
    GLsizei length = 0;
    glGetObjectLabel(GL_TEXTURE, name, sizeof text, &length, text);
    if (label == std::string(text, static_cast<size_t>(length))) found.push_back(name);
  }
  return found;
}

void GlTest::SetUp() {
  if (gContext) {
    gContext->resetGlErrorCount();
    return;
  }
  const char* require = std::getenv("SSLR_REQUIRE_GL");
  if (require != nullptr && std::string(require) == "1")
    FAIL() << "no OpenGL 4.5 context (SSLR_REQUIRE_GL=1): " << gError;
  GTEST_SKIP() << "no OpenGL 4.5 context: " << gError;
}

void GlTest::TearDown() {
  if (!gContext) return;
  EXPECT_EQ(gContext->glErrorCount(), 0) << "GL errors were reported during the test";
  EXPECT_EQ(gContext->highSeverityCount(), 0)
      << "HIGH-severity KHR_debug messages were reported during the test (an engine that stops on them would stop)";
}

sslr::host::Image compositeImage(sslr::Context& ctx, int w, int h, const sslr::CompositeOptions& options) {
  GLuint tex = 0, fbo = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  glTextureStorage2D(tex, 1, GL_RGBA32F, w, h);
  const float zero[4] = {0, 0, 0, 0};
  glClearTexImage(tex, 0, GL_RGBA, GL_FLOAT, zero);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
  EXPECT_TRUE(ctx.composite(fbo, options));
  sslr::host::Image out = sslr::host::readTexture(tex, w, h, 4);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &tex);
  return out;
}

std::unique_ptr<sslr::Context> makeSslrContext(int w, int h, const sslr::ContextDesc& shapes) {
  sslr::ContextDesc d = shapes;
  d.width = w;
  d.height = h;
  d.getProcAddress = sslr::host::HeadlessContext::getProcAddress();
  auto c = sslr::Context::create(d);
  EXPECT_TRUE(c) << c.error();
  return c ? std::move(c.value()) : nullptr;
}

}  // namespace sslr::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  sslr::host::EglOptions options;
  options.quiet = true;
  auto ctx = sslr::host::HeadlessContext::create(options);
  if (ctx) {
    sslr::test::gContext = std::move(ctx.value());
    std::printf("GL_RENDERER: %s\n", sslr::test::gContext->renderer().c_str());
  } else {
    sslr::test::gError = ctx.error();
  }
  const int rc = RUN_ALL_TESTS();
  sslr::test::gContext.reset();
  return rc;
}
