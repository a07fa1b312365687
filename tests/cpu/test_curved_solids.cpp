// Curved solids (sslr_shared.h, "Curved solids"): the shared header's float formulas against
// analytic geometry. A sphere and a cylinder give their radius and the chord behind a pixel;
// flat faces, concave surfaces, silhouettes and encoding noise give nothing; the window depth of
// a view depth inverts the reconstruction for every depth convention, and view depths compare
// without converting them (sslrBeyondDepth).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "shared_frame.hpp"

using namespace sslr;
using namespace sslr::host;
using namespace sslr::shared;

namespace {

constexpr float kWidth = test::kFrameWidth, kHeight = test::kFrameHeight;

using Frame = test::SharedFrame;
Frame frameFor(DepthMode mode, bool ortho) {
  Frame s = test::sharedFrameFor(mode, ortho);
  s.trace.objectDepthRelative = 0.075f;
  s.trace.curvedSolids = 1;
  return s;
}

// Two neighbouring points of a sphere (centre c, radius r) seen from the origin, `stepPx` pixels
// apart on screen around the direction `dir`, with their exact normals.
struct Pair {
  vec3 a, na, b, nb;
};
Pair onSphere(vec3 c, float r, vec3 towardsCamera, vec3 along, float angle) {
  const vec3 na = normalize(towardsCamera), nb = normalize(towardsCamera + along * angle);
  return {c + na * r, na, c + nb * r, nb};
}

float footprint(const Frame& s, vec3 p) {
  return sslrPixelFootprint(s.proj, kHeight, sslrViewDistance(s.proj, p));
}

TEST(CurvedSolids, RadiusOfASphereAndACylinder) {
  const Frame s = frameFor(DepthMode::Reversed, false);
  const vec3 centre(0.5f, 0.2f, -8.0f);
  // ~1.2 degrees between neighbours: a radius-1 sphere 8 units away at 320x180 turns ~3 per pixel.
  for (float turn : {0.01f, 0.02f, 0.05f}) {
    const Pair p = onSphere(centre, 1.0f, vec3(0.3f, 0.2f, 1.0f), vec3(1.0f, 0.0f, 0.0f), turn);
    const float r = sslrConvexRadius(s.surf, p.a, p.na, p.b, p.nb, footprint(s, p.a));
    // P_a - P_b = r (N_a - N_b) exactly on a sphere; float rounding of the differences only.
    EXPECT_NEAR(r, 1.0f, 2e-3f) << "turn " << turn;
    // Symmetric in the pair.
    EXPECT_NEAR(sslrConvexRadius(s.surf, p.b, p.nb, p.a, p.na, footprint(s, p.b)), r, 1e-4f);
  }
  // A vertical cylinder (axis y): across the axis its radius, along it nothing turns.
  const vec3 axisPoint(-1.0f, 0.0f, -6.0f);
  const float radius = 0.6f;
  auto onCylinder = [&](float phi, float y) {
    const vec3 n(std::sin(phi), 0.0f, std::cos(phi));
    return std::pair{axisPoint + vec3(0.0f, y, 0.0f) + n * radius, n};
  };
  const auto [a, na] = onCylinder(0.2f, 0.0f);
  const auto [b, nb] = onCylinder(0.23f, 0.0f);
  const auto [c, nc] = onCylinder(0.2f, 0.02f);
  EXPECT_NEAR(sslrConvexRadius(s.surf, a, na, b, nb, footprint(s, a)), radius, 2e-3f);
  EXPECT_EQ(sslrConvexRadius(s.surf, a, na, c, nc, footprint(s, a)), 0.0f) << "along the axis: flat";
}

TEST(CurvedSolids, NothingFromFlatConcaveNoisyOrSeparatedPixels) {
  const Frame s = frameFor(DepthMode::Reversed, false);
  const vec3 n = normalize(vec3(0.2f, 0.3f, 1.0f));
  const vec3 a(0.0f, 0.0f, -5.0f);
  const float fp = footprint(s, a);
  // A flat face: equal normals.
  EXPECT_EQ(sslrConvexRadius(s.surf, a, n, a + vec3(fp, 0.0f, -0.2f * fp), n, fp), 0.0f);
  // The inside of a sphere (a bowl seen from inside): the differences point opposite ways.
  const Pair bowl = onSphere(vec3(0.0f, 0.0f, -5.0f), 2.0f, vec3(0.1f, 0.0f, -1.0f), vec3(1.0f, 0.0f, 0.0f), 0.02f);
  EXPECT_EQ(sslrConvexRadius(s.surf, bowl.a, -bowl.na, bowl.b, -bowl.nb, fp), 0.0f) << "concave";
  // Octahedral noise (< 0.3 degrees) on a flat face is not a curve.
  const vec3 noisy = normalize(n + vec3(0.004f, -0.002f, 0.0f));
  EXPECT_EQ(sslrConvexRadius(s.surf, a, n, a + vec3(fp, 0.0f, 0.0f), noisy, fp), 0.0f);
  // 8-bit xyz normals: up to ~2 degrees of noise is not a curve either, though octahedral would take it.
  SslrSurface xyz = s.surf;
  xyz.normalEncoding = SSLR_NORMALS_XYZ_UNORM;
  const Pair slight = onSphere(vec3(0.0f, 0.0f, -5.0f), 1.0f, vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 0.0f), 0.02f);
  EXPECT_GT(sslrConvexRadius(s.surf, slight.a, slight.na, slight.b, slight.nb, fp), 0.0f);
  EXPECT_EQ(sslrConvexRadius(xyz, slight.a, slight.na, slight.b, slight.nb, fp), 0.0f);
  // An edge (more than ~20 degrees between neighbours) is not a curve.
  const Pair edge = onSphere(vec3(0.0f, 0.0f, -5.0f), 0.01f, vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 0.0f), 0.5f);
  EXPECT_EQ(sslrConvexRadius(s.surf, edge.a, edge.na, edge.b, edge.nb, fp), 0.0f) << "edge";
  // A silhouette: neighbours on two objects, one far behind; normals that happen to differ a little.
  const vec3 far = a + vec3(fp, 0.0f, -3.0f);
  const vec3 nFar = normalize(n + vec3(0.05f, 0.0f, 0.0f));
  EXPECT_EQ(sslrConvexRadius(s.surf, a, n, far, nFar, fp), 0.0f) << "depth jump";
}

// A quad is curved when both its rows (or both its columns) see the same radius: a single pair that
// happens to look like a sphere (a normal map's turn) makes no solid.
TEST(CurvedSolids, OnePairThatLooksCurvedMakesNoSolid) {
  EXPECT_EQ(sslrAgreedRadius(1.0f, 1.5f), 1.0f);
  EXPECT_EQ(sslrAgreedRadius(1.0f, 2.5f), 0.0f) << "disagree by more than 2x";
  EXPECT_EQ(sslrAgreedRadius(1.0f, 0.0f), 0.0f) << "one row flat";
  const Frame s = frameFor(DepthMode::Reversed, false);
  // A flat quad facing the camera 5 units away, one footprint per pixel; its top row's normals
  // turn as on a sphere of radius 0.5, its bottom row's do not.
  const float fp = footprint(s, vec3(0.0f, 0.0f, -5.0f));
  const vec3 p0(0.0f, 0.0f, -5.0f), p1(fp, 0.0f, -5.0f), p2(0.0f, -fp, -5.0f), p3(fp, -fp, -5.0f);
  const vec3 n(0.0f, 0.0f, 1.0f), turned = normalize(n + vec3(fp / 0.5f, 0.0f, 0.0f));
  const bvec4 ok(true);
  const vec4 lonely = sslrQuadCurvedExtraDepth(s.proj, s.surf, s.trace, p0, p1, p2, p3, n, turned, n, n, ok);
  EXPECT_EQ(lonely, vec4(0.0f));
  // Both rows turning alike: a cylinder across the rows, solid behind every pixel of the quad.
  const vec4 both = sslrQuadCurvedExtraDepth(s.proj, s.surf, s.trace, p0, p1, p2, p3, n, turned, n, turned, ok);
  EXPECT_GT(both.x, 0.0f);
  EXPECT_GT(both.w, 0.0f);
}

TEST(CurvedSolids, ExtraDepthIsTheChordBeyondTheSlab) {
  for (bool ortho : {false, true}) {
    const Frame s = frameFor(DepthMode::Reversed, ortho);
    // A pixel facing the camera at distance 8: the chord of a radius-2 sphere is 4 along the view,
    // capped at 4 slabs (4 x 0.6), so the extra is 2.4 - 0.6; a radius-0.2 sphere (chord 0.4) is
    // thinner than the slab: no extra.
    const vec3 p(0.0f, 0.0f, -8.0f);
    const vec3 n(0.0f, 0.0f, 1.0f);
    const float slab = 0.075f * 8.0f;
    EXPECT_NEAR(sslrCurvedExtraDepth(s.proj, s.trace, p, n, 2.0f), 3.0f * slab, 1e-5f) << "ortho " << ortho;
    EXPECT_NEAR(sslrCurvedExtraDepth(s.proj, s.trace, p, n, 0.5f), 1.0f - slab, 1e-5f);
    EXPECT_EQ(sslrCurvedExtraDepth(s.proj, s.trace, p, n, 0.2f), 0.0f);
    EXPECT_EQ(sslrCurvedExtraDepth(s.proj, s.trace, p, n, 0.0f), 0.0f) << "flat: the slab";
    // Near a sphere's rim (normal 80 degrees from the view ray) the chord 2 r cos(a) is short.
    const vec3 rim = normalize(vec3(std::sin(1.4f), 0.0f, std::cos(1.4f)));
    EXPECT_NEAR(sslrCurvedExtraDepth(s.proj, s.trace, p, rim, 1.0f), 0.0f, 1e-6f);
  }
}

TEST(CurvedSolids, Level0TexelHoldsDepthAndExtra) {
  SslrSurface s{};
  s.reversedZ = 1;
  EXPECT_EQ(sslrHiZLevel0Texel(s, 0.25f, 1.5f), vec2(0.25f, 1.5f));
  EXPECT_EQ(sslrHiZLevel0Texel(s, 0.0f, 0.0f), vec2(0.0f, 0.0f)) << "background: the farthest depth";
  EXPECT_EQ(sslrHiZLevel0Texel(s, std::nanf(""), 0.0f), vec2(0.0f, 0.0f)) << "NaN: the farthest depth";
  EXPECT_EQ(sslrHiZMinMax(0, vec2(0.25f, 1.5f)), vec2(0.25f, 0.25f)) << "level 0: one depth, not (min, max)";
  EXPECT_EQ(sslrHiZMinMax(1, vec2(0.25f, 0.5f)), vec2(0.25f, 0.5f));
  EXPECT_TRUE(sslrQuadNormalsTurn(vec4(0.5f), vec4(0.5f), vec4(0.5f), vec4(0.5f, 0.5f, 0.5f, 0.6f)));
  EXPECT_FALSE(sslrQuadNormalsTurn(vec4(0.5f), vec4(0.5f), vec4(0.5f), vec4(0.5f)));
}

// The window depth of a view depth is the inverse of the reconstruction, in every convention.
TEST(CurvedSolids, DepthFromViewDepthInvertsTheReconstruction) {
  for (DepthMode mode : {DepthMode::GlDefault, DepthMode::ZeroToOne, DepthMode::Reversed, DepthMode::ReversedInfinite})
    for (bool ortho : {false, true}) {
      const Frame s = frameFor(mode, ortho);
      for (float dist : {0.2f, 1.0f, 8.0f, 100.0f, 900.0f}) {
        const float depth = sslrDepthFromViewDepth(s.proj, dist);
        EXPECT_GE(depth, 0.0f);
        EXPECT_LE(depth, 1.0f);
        // Float: a few ulp of the distance (perspective, reversed); the depth range's ulps elsewhere.
        const float tolerance = 2e-5f * dist + (mode == DepthMode::GlDefault || mode == DepthMode::ZeroToOne
                                                    ? 1e-6f * dist * dist / 0.1f
                                                    : 0.0f) +
                                (ortho ? 1e-4f : 0.0f);
        EXPECT_NEAR(sslrViewDepthFromDepth(s.proj, depth), dist, tolerance)
            << toString(mode) << (ortho ? " ortho" : " persp") << " dist " << dist;
      }
    }
}

// sslrBeyondDepth compares view depths (distRay > k distFar + e) without converting them: the
// answer must be the view depths' wherever they are 2% from the bound (float depth resolves far
// less than that at these distances), in every convention, and a ray at infinity is beyond.
TEST(CurvedSolids, BeyondDepthComparesViewDepths) {
  for (DepthMode mode : {DepthMode::GlDefault, DepthMode::ZeroToOne, DepthMode::Reversed, DepthMode::ReversedInfinite})
    for (bool ortho : {false, true}) {
      const Frame s = frameFor(mode, ortho);
      for (float distFar : {0.3f, 2.0f, 20.0f, 100.0f})
        for (float k : {1.0f, 1.075f, 1.3f})
          for (float e : {0.0f, 0.05f * distFar, -0.02f * distFar}) {
            const float bound = k * distFar + e;
            const float farDepth = sslrDepthFromViewDepth(s.proj, distFar);
            const float nearerDepth = sslrDepthFromViewDepth(s.proj, 0.98f * bound);
            const float fartherDepth = sslrDepthFromViewDepth(s.proj, 1.02f * bound);
            const std::string where = std::string(toString(mode)) + (ortho ? " ortho" : " persp") + " distFar " +
                                      std::to_string(distFar) + " k " + std::to_string(k) + " e " + std::to_string(e);
            EXPECT_FALSE(sslrBeyondDepth(s.proj, nearerDepth, farDepth, k, e)) << where;
            EXPECT_TRUE(sslrBeyondDepth(s.proj, fartherDepth, farDepth, k, e)) << where;
          }
      if (!ortho && mode == DepthMode::ReversedInfinite) {  // depth 0: infinitely far; below: beyond it
        const float farDepth = sslrDepthFromViewDepth(s.proj, 100.0f);
        EXPECT_TRUE(sslrBeyondDepth(s.proj, 0.0f, farDepth, 1.3f, 5.0f));
        EXPECT_TRUE(sslrBeyondDepth(s.proj, -1e-3f, farDepth, 1.3f, 5.0f));
      }
    }
}

// The level-1 cell of a quad on a sphere reaches the solid's back; without curved solids it is the
// plain min-max of the quad's depths.
TEST(CurvedSolids, Level1CellHoldsTheSolidsBack) {
  Frame s = frameFor(DepthMode::Reversed, false);
  const vec3 centre(0.0f, 0.0f, -8.0f);
  const float radius = 1.5f;
  // Four pixels around the screen centre, each on the sphere: their view rays' front intersections.
  ivec2 px[4] = {ivec2(160, 90), ivec2(161, 90), ivec2(160, 91), ivec2(161, 91)};
  vec4 depths;
  vec4 normals[4];
  for (int k = 0; k < 4; ++k) {
    const vec2 uv = sslrUvFromPixel(px[k], vec2(kWidth, kHeight));
    const vec3 dir = normalize(sslrViewFromUvDepth(s.proj, uv, 0.5f));  // any depth: the ray's direction
    const float b = dot(dir, centre), cc = dot(centre, centre) - radius * radius;
    const float t = b - std::sqrt(b * b - cc);  // the nearer intersection
    const vec3 hit = dir * t;
    depths[k] = sslrDepthFromViewDepth(s.proj, -hit.z);
    const vec2 oct = sslrOctEncode(normalize(hit - centre));
    normals[k] = vec4(oct.x, oct.y, 0.0f, 0.0f);
  }
  vec4 extra;
  const vec2 cell = sslrHiZLevel1Cell(s.proj, s.surf, s.trace, px[0], px[1], px[2], px[3], depths, normals[0],
                                      normals[1], normals[2], normals[3], extra);
  // Seen head-on the sphere is 2r = 3 deep, capped at 4 slabs (4 x 0.0975 x 6.5): 1.95.
  const float front = -centre.z - radius;
  const float slab = s.trace.objectDepthRelative * front;
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(extra[k], 3.0f * slab, 0.02f * slab) << "pixel " << k;
  // Reversed Z: the farther key is the smaller depth; the back lies 3 slabs beyond the front.
  EXPECT_NEAR(sslrViewDepthFromDepth(s.proj, cell.x), front + 3.0f * slab, 0.02f);
  EXPECT_NEAR(sslrViewDepthFromDepth(s.proj, cell.y), front, 0.01f);
  s.trace.curvedSolids = 0;
  const vec2 plain = sslrHiZLevel1Cell(s.proj, s.surf, s.trace, px[0], px[1], px[2], px[3], depths, normals[0],
                                       normals[1], normals[2], normals[3], extra);
  EXPECT_EQ(plain, sslrHiZLevel1Plain(s.surf, depths));
  EXPECT_EQ(extra, vec4(0.0f));
}

}  // namespace
