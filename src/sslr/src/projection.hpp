// Host projection -> the reduced form the shaders use (SslrProjection), with validation.
#pragma once

#include <string>

#include "sslr/sslr.hpp"
#include "sslr_shared.h"

namespace sslr::detail {

// Checks that clipFromView is a finite perspective or orthographic matrix without skew (the form
// documented at SslrProjection), non-singular, and that its depth direction agrees with the
// convention (reversed-Z maps nearer points to larger depth). Entries are extracted in double.
Expected<shared::SslrProjection> reduceProjection(const glm::dmat4& clipFromView,
                                                  const DepthConvention& depth);

}  // namespace sslr::detail
