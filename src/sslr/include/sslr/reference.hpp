// CPU reference runs: the exact uniform block dispatch() uploads, for code that runs the shared
// C++/GLSL headers (sslr_shared.h, sslr_trace.h) on the CPU - tests, benchmarks, debug tools.
#pragma once

#include "sslr/sslr.hpp"
#include "sslr_shared.h"

namespace sslr {

// Validates the projection/convention, the viewport and the settings as dispatch() does (textures
// are not looked at) and returns the SslrFrame block for width x height textures (the frame:
// FrameInputs::viewport inside them, else all of them).
Expected<shared::SslrFrame> frameConstants(const FrameInputs& inputs, const Settings& settings, int width,
                                           int height);
// FrameInputs::viewport resolved (all zeros: the whole width x height), or why it does not fit.
Expected<Viewport> frameViewport(const FrameInputs& inputs, int width, int height);

}  // namespace sslr
