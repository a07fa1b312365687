// Half resolution (sslr_shared.h, "Half resolution"): the quad record's code, the same-surface
// test and the re-planing of a quad's hit, against exact values and analytic geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "shared_frame.hpp"

using namespace sslr;
using namespace sslr::host;
using namespace sslr::shared;

// Every traced pixel and kind comes back exactly; the confidence to within one float step of w
// (w < 24: 2^-19 ~ 1.9e-6), clamped into [0, 0.999] so it cannot carry into the index.
TEST(HalfResolution, QuadCodeRoundTrips) {
  const float confidences[] = {0.0f, 1e-5f, 0.25f, 0.5f, 0.7f, 0.998f, 0.999f};
  for (int kind : {SSLR_QUAD_HIT, SSLR_QUAD_OWN_RAYS, SSLR_QUAD_MISS})
    for (int index = 0; index < 4; ++index)
      for (float c : confidences) {
        const SslrQuadCode code = sslrUnpackQuadCode(sslrPackQuadCode(c, index, kind));
        EXPECT_EQ(code.kind, kind) << c << " " << index;
        EXPECT_EQ(code.index, index) << c << " " << kind;
        EXPECT_NEAR(code.confidence, c, 2e-6f) << index << " " << kind;
        EXPECT_EQ(code.confidence > 0.0f, c > 0.0f) << "a hit must stay a hit, a miss a miss";
      }
  // Out-of-range confidences are clamped, never spill into the index or kind.
  const SslrQuadCode high = sslrUnpackQuadCode(sslrPackQuadCode(1.0f, 3, SSLR_QUAD_HIT));
  EXPECT_EQ(high.index, 3);
  EXPECT_EQ(high.kind, SSLR_QUAD_HIT);
  EXPECT_NEAR(high.confidence, 0.999f, 2e-6f);
  const SslrQuadCode low = sslrUnpackQuadCode(sslrPackQuadCode(-0.5f, 1, SSLR_QUAD_MISS));
  EXPECT_EQ(low.index, 1);
  EXPECT_EQ(low.kind, SSLR_QUAD_MISS);
  EXPECT_EQ(low.confidence, 0.0f);
  // A record no ray wrote (a quad with nothing to trace) is all zeros: pixel 0, no hit.
  const SslrQuadCode empty = sslrUnpackQuadCode(0.0f);
  EXPECT_EQ(empty.kind, SSLR_QUAD_HIT);
  EXPECT_EQ(empty.index, 0);
  EXPECT_EQ(empty.confidence, 0.0f);
}

TEST(HalfResolution, QuadOffsetsVisitEveryPixelOnce) {
  int seen = 0;
  for (int i = 0; i < 4; ++i) {
    const ivec2 o = sslrQuadOffset(i);
    ASSERT_TRUE(o.x >= 0 && o.x <= 1 && o.y >= 0 && o.y <= 1);
    seen |= 1 << (o.y * 2 + o.x);
  }
  EXPECT_EQ(seen, 0xf);
}

// A pixel's ray re-planed onto the hit surface of its quad's ray meets that plane exactly.
TEST(HalfResolution, ReusedLengthMeetsTheHitPlane) {
  // A mirror floor at y = -2 seen from the origin, reflecting a wall at z = -30 facing the camera.
  const vec3 vsP(0.3f, -2.0f, -8.0f), vsN(0.0f, 1.0f, 0.0f);
  const vec3 vsR = reflect(normalize(vsP), vsN);
  const vec3 vsWallNormal(0.0f, 0.0f, 1.0f);
  const vec3 vsH(-1.0f, 3.0f, -30.0f);  // the neighbouring ray's hit on the wall
  const float L = sslrReusedLength(vsP, vsR, vsH, vsWallNormal);
  ASSERT_GT(L, 0.0f);
  EXPECT_NEAR((vsP + vsR * L).z, -30.0f, 1e-4f);
  // A plane behind the ray: no reuse.
  EXPECT_EQ(sslrReusedLength(vsP, vsR, vec3(0.0f, 0.0f, 5.0f), vsWallNormal), -1.0f);
  // A plane the ray runs along (|R.N| < 0.05): the neighbour's point is kept.
  const vec3 vsAlong = normalize(vec3(1.0f, 0.0f, -0.02f));
  EXPECT_FLOAT_EQ(sslrReusedLength(vsP, vsAlong, vsH, vsWallNormal), length(vsH - vsP));
}

// Neighbouring pixels of one plane are the same surface at any slope, under either projection;
// a step off the plane, or a turned normal, is not.
TEST(HalfResolution, SameSurfaceIsAPlaneTestNotADepthTest) {
  for (bool ortho : {false, true}) {
    const test::SharedFrame f = test::sharedFrameFor(DepthMode::Reversed, ortho);
    // A floor at y = -1 seen nearly edge-on: 30 units away, one pixel up changes depth by percents.
    const vec3 n(0.0f, 1.0f, 0.0f);
    const vec3 a(0.0f, -1.0f, -30.0f), b(0.05f, -1.0f, -33.0f);
    EXPECT_TRUE(sslrSameSurface(f.proj, f.surf, b, n, a, n)) << ortho;
    // The same point half a unit above the floor (the top of a box standing on it): another
    // surface (the tolerance there is 0.2% of the distance plus a quarter pixel, ~0.12 units).
    EXPECT_FALSE(sslrSameSurface(f.proj, f.surf, b + vec3(0.0f, 0.5f, 0.0f), n, a, n)) << ortho;
    // The same point with a normal turned by 3 degrees (a curved surface): no reuse.
    const float t = 3.0f * 3.14159265f / 180.0f;
    EXPECT_FALSE(sslrSameSurface(f.proj, f.surf, b, vec3(std::sin(t), std::cos(t), 0.0f), a, n)) << ortho;
  }
}
