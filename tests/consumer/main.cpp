// Compiles and links against the installed library only: no GL loader, no windowing, no tools.
#include <sslr/sslr.hpp>

#include <cstdio>

int main() {
  // Without a GL context the library must refuse cleanly, with a message.
  sslr::ContextDesc desc;
  desc.width = 64;
  desc.height = 64;
  desc.getProcAddress = [](const char*) -> sslr::GLProc { return nullptr; };
  auto ctx = sslr::Context::create(desc);
  if (ctx) return 1;
  std::printf("refused as expected: %s\n", ctx.error().c_str());
  return sslr::validate(sslr::Settings::preset(sslr::Preset::High)).empty() ? 0 : 1;
}
