#include "projection.hpp"

#include <cmath>
#include <sstream>

namespace sslr::detail {

namespace {
std::string entry(int col, int row, double v) {
  std::ostringstream s;
  s << "clipFromView[" << col << "][" << row << "] = " << v;
  return s.str();
}

// Where the declared convention puts the two ends of a perspective matrix's depth range, as view
// distances: dist(ndcZ) = zOffset / (ndcZ + zScale). The near end must lie in front of the camera
// and the far end beyond it (or at infinity). A reversed matrix declared with GL's -1..1 range
// puts the far end behind the camera: half the depth range would be unused and the depth read
// back would be misread.
Status checkPerspectiveDepthRange(double zScale, double zOffset, const DepthConvention& depth) {
  const bool zeroToOne = depth.range == DepthRange::ZeroToOne;
  const double ndcNear = depth.reversedZ ? 1.0 : (zeroToOne ? 0.0 : -1.0);
  const double ndcFar = depth.reversedZ ? (zeroToOne ? 0.0 : -1.0) : 1.0;
  const double nearDist = zOffset / (ndcNear + zScale);
  const double farDen = ndcFar + zScale;
  const double farDist = farDen == 0.0 ? INFINITY : zOffset / farDen;
  const char* range = zeroToOne ? "DepthRange::ZeroToOne" : "DepthRange::NegativeOneToOne";
  if (!(nearDist > 0.0) || !std::isfinite(nearDist)) {
    std::ostringstream why;
    why << "sslr: depth convention mismatch: with " << range << " and reversedZ = "
        << (depth.reversedZ ? "true" : "false") << ", clipFromView puts the near end of the depth range at view "
        << "distance " << nearDist << " (it must be in front of the camera): the matrix was built for another "
        << "depth range or convention";
    return Status::error(StatusCode::InvalidProjection, why.str());
  }
  if (farDist < nearDist * (1.0 + 1e-9) && !(farDist == INFINITY)) {
    std::ostringstream why;
    why << "sslr: depth convention mismatch: with " << range << " and reversedZ = "
        << (depth.reversedZ ? "true" : "false") << ", clipFromView puts the far end of the depth range at view "
        << "distance " << farDist << ", not beyond the near end (" << nearDist << ")"
        << (depth.reversedZ && !zeroToOne ? ": a reversed-Z projection needs glClipControl(..., GL_ZERO_TO_ONE) "
                                            "and DepthRange::ZeroToOne"
                                          : ": the matrix was built for another depth range or convention");
    return Status::error(StatusCode::InvalidProjection, why.str());
  }
  return {};
}

}  // namespace

Expected<shared::SslrProjection> reduceProjection(const glm::dmat4& m, const DepthConvention& depth) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r]))
        return Status::error(StatusCode::InvalidProjection, "sslr: projection is not finite: " + entry(c, r, m[c][r]));

  // FrameInputs' default: the host forgot to set its projection (the identity would otherwise
  // pass as a reversed orthographic unit cube and reconstruct nonsense).
  if (m == glm::dmat4(1.0))
    return Status::error(StatusCode::InvalidProjection, 
        "sslr: clipFromView is the identity (FrameInputs' default): set it to the projection matrix "
        "that rasterized the depth buffer");
  const bool ortho = m[2][3] == 0.0 && m[3][3] == 1.0;
  const bool persp = m[2][3] == -1.0 && m[3][3] == 0.0;
  if (!ortho && !persp)
    return Status::error(StatusCode::InvalidProjection, 
        "sslr: clipFromView is neither a GL perspective (column 2 row 3 = -1, [3][3] = 0) nor an "
        "orthographic ([2][3] = 0, [3][3] = 1) projection: " + entry(2, 3, m[2][3]) + ", " +
        entry(3, 3, m[3][3]));
  // Entries that must be zero for the reduced form (no skew, no rotation, no oblique clipping).
  const int zeroEntries[][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 0}, {1, 2}, {1, 3}, {2, 0}, {2, 1},
                                {3, 0}, {3, 1}, {3, 3}};
  for (const auto& ij : zeroEntries) {
    const int c = ij[0], r = ij[1];
    const bool offsetSlot = (c == 2 && r < 2 && persp) || (c == 3 && r < 2 && ortho);
    const bool wSlot = (c == 3 && r == 3);
    if (offsetSlot || wSlot) continue;  // off-centre / jitter offsets, or w handled above
    if (m[c][r] != 0.0)
      return Status::error(StatusCode::InvalidProjection, "sslr: clipFromView has skew or oblique terms sslr does not support: " +
                           entry(c, r, m[c][r]));
  }
  const double xScale = m[0][0], yScale = m[1][1], zScale = m[2][2], zOffset = m[3][2];
  if (xScale == 0.0 || yScale == 0.0)
    return Status::error(StatusCode::InvalidProjection, "sslr: clipFromView is singular (x or y scale is 0)");
  // Depth direction: d(ndc z)/d(view distance). Perspective: ndcZ = -zScale + zOffset / dist,
  // so it falls with distance iff zOffset > 0. Orthographic: ndcZ = -zScale * dist + zOffset.
  double slope = persp ? -zOffset : -zScale;
  if (slope == 0.0 || (ortho && zScale == 0.0))
    return Status::error(StatusCode::InvalidProjection, "sslr: clipFromView maps every distance to the same depth (singular: "
                         "near == far or zero depth scale)");
  const bool reversedMatrix = slope < 0.0;
  if (reversedMatrix != depth.reversedZ)
    return Status::error(StatusCode::InvalidProjection, std::string("sslr: depth convention mismatch: DepthConvention::reversedZ = ") +
                         (depth.reversedZ ? "true" : "false") + " but clipFromView maps nearer points to " +
                         (reversedMatrix ? "larger" : "smaller") + " depth");

  if (persp) {
    if (Status st = checkPerspectiveDepthRange(zScale, zOffset, depth); !st) return st;
  }

  const shared::SslrProjection p =
      shared::sslrProjectionFromMatrix(m, depth.range == DepthRange::ZeroToOne);
  // A subnormal (or flushed) entry has lost its precision: the shaders' reconstruction would be
  // noise or zeros. Zero depth terms are legitimate (an infinite far plane).
  auto representable = [](float v) { return std::isfinite(v) && (v == 0.0f || std::isnormal(v)); };
  if (!representable(p.xScale) || !representable(p.yScale) || !representable(p.zScale) ||
      !representable(p.zOffset) || p.xScale == 0.0f || p.yScale == 0.0f)
    return Status::error(StatusCode::InvalidProjection, "sslr: clipFromView entries overflow or underflow single precision");
  return p;
}

}  // namespace sslr::detail
