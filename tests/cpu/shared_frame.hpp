// The uniform-block structs of a 320x180 frame seen through a host camera (near 0.1, far 1000,
// orthographic 20 units high): what the CPU tests of the shared header's formulas start from.
#pragma once

#include <gtest/gtest.h>

#include "projection.hpp"
#include "sslr_host/camera.hpp"
#include "sslr_shared.h"

namespace sslr::test {

constexpr float kFrameWidth = 320.0f, kFrameHeight = 180.0f;

struct SharedFrame {
  shared::SslrProjection proj{};
  shared::SslrSurface surf{};
  shared::SslrTraceParams trace{};  // zeroed: each test sets what it reads
};

inline SharedFrame sharedFrameFor(host::DepthMode mode, bool ortho) {
  host::Camera cam;
  cam.nearPlane = 0.1;
  cam.farPlane = 1000.0;
  cam.orthographic = ortho;
  cam.orthoHeight = 20.0;
  auto reduced = sslr::detail::reduceProjection(cam.clipFromView(mode, double(kFrameWidth) / kFrameHeight),
                                                host::depthConvention(mode));
  EXPECT_TRUE(reduced) << reduced.error();
  SharedFrame f;
  if (reduced) f.proj = reduced.value();
  f.surf.normalEncoding = SSLR_NORMALS_OCTAHEDRAL;
  f.surf.width = kFrameWidth;
  f.surf.height = kFrameHeight;
  f.surf.reversedZ = mode == host::DepthMode::Reversed || mode == host::DepthMode::ReversedInfinite ? 1 : 0;
  return f;
}

}  // namespace sslr::test
