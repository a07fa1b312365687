// Compiles and links against the installed library only: no GL loader, no windowing, no tools.
#include <sslr/reference.hpp>  // pulls the shared C++/GLSL headers from beside it
#include <sslr/sslr.hpp>

#include <cstdio>
#include <string>

// The quick start of sslr.hpp's comment and README.md, as written there (compiled, not run: it
// needs the host's GL context). If it stops compiling, the documentation is wrong.
[[maybe_unused]] static void quickStart(int width, int height, sslr::GetProcAddress eglGetProcAddress,
                                        sslr::GLName colorTex, sslr::GLName normalTex, sslr::GLName depthTex,
                                        const glm::dmat4& clipFromView, sslr::GLName hostFramebuffer,
                                        sslr::GLName fallbackTex) {
  auto log = [](const std::string& text) { std::fprintf(stderr, "%s\n", text.c_str()); };
  auto ctx = sslr::Context::create({width, height, eglGetProcAddress});   // once
  if (!ctx) log(ctx.error());
  sslr::FrameInputs in;                                                     // per frame
  in.colorTexture = colorTex; in.normalTexture = normalTex; in.depthTexture = depthTex;
  in.clipFromView = clipFromView;  // glm::dmat4, the matrix that rasterized the depth
  if (auto st = ctx.value()->dispatch(in, sslr::Settings::preset(sslr::Preset::High)); !st)
    log(st.message());
  ctx.value()->composite(hostFramebuffer);   // adds the resolved reflection to what is there
  // or, where the host's lighting already added a fallback specular (probes, sky) it keeps:
  ctx.value()->composite(hostFramebuffer, {sslr::CompositeMode::BlendOverFallback, fallbackTex});
}

static_assert(SSLR_VERSION_MAJOR >= 0 && SSLR_VERSION_MINOR >= 0 && SSLR_VERSION_PATCH >= 0,
              "sslr/version.hpp is installed with sslr.hpp");

int main() {
  // The installed headers and the installed library are of one version.
  if (std::string(sslr::libraryVersion()) != SSLR_VERSION_STRING) return 1;
  std::printf("sslr %s\n", sslr::libraryVersion());
  // Without a GL context the library must refuse cleanly, with a message.
  sslr::ContextDesc desc;
  desc.width = 64;
  desc.height = 64;
  desc.getProcAddress = [](const char*) -> sslr::GLProc { return nullptr; };
  auto ctx = sslr::Context::create(desc);
  if (ctx) return 1;
  std::printf("refused as expected: %s\n", ctx.error().c_str());
  // The CPU reference of the shaders' math is usable from the installed headers: a singular
  // projection is refused with a message.
  sslr::FrameInputs singular;
  singular.clipFromView = glm::dmat4(0.0);
  if (sslr::frameConstants(singular, sslr::Settings{}, 64, 64)) return 1;
  std::printf("shared header: SslrFrame is %zu bytes\n", sizeof(sslr::shared::SslrFrame));
  return sslr::validate(sslr::Settings::preset(sslr::Preset::High)).empty() ? 0 : 1;
}
