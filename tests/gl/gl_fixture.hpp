// Shared GL test setup: one headless context for the whole executable. Without a context the
// tests skip with the reason, unless SSLR_REQUIRE_GL=1 (CI) makes that a failure. Every test
// ends by checking that no GL error was reported through KHR_debug.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "sslr/sslr.hpp"
#include "sslr_host/egl_context.hpp"
#include "sslr_host/gbuffer.hpp"
#include "sslr_host/gl.hpp"

namespace sslr::test {

sslr::host::HeadlessContext* glContext();     // nullptr if none could be created
const std::string& glContextError();
// The textures of the current GL context whose debug label is `label` (sslr labels its own).
std::vector<GLuint> texturesLabelled(const std::string& label);
// An sslr context of w x h on the headless context (a failed test and nullptr if none).
// `shapes`: the pass shapes (ContextDesc's device, traversalPass, oneBodyTraversal, occupancyExit).
std::unique_ptr<sslr::Context> makeSslrContext(int w, int h, const sslr::ContextDesc& shapes = {});
// `ctx`'s composite (by `options`) into a w x h RGBA32F framebuffer cleared to zero, read back
// (RGBA). DSA calls only: nothing of the host's GL state is bound or changed.
sslr::host::Image compositeImage(sslr::Context& ctx, int w, int h, const sslr::CompositeOptions& options = {});

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
};

}  // namespace sslr::test
