// Projection and reconstruction: the shared header's float formulas against double precision,
// for every depth convention, perspective and orthographic, centred and off-centre.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "projection.hpp"
#include "sslr/reference.hpp"
#include "sslr_host/camera.hpp"
#include "sslr_shared.h"

using namespace sslr;
using namespace sslr::host;
using namespace sslr::shared;

namespace {

const DepthMode kModes[] = {DepthMode::GlDefault, DepthMode::ZeroToOne, DepthMode::Reversed,
                            DepthMode::ReversedInfinite};

// Window depth as the depth buffer stores it: D24 rounds to 24-bit fixed point, D32F to float.
double quantize(double depth, DepthMode mode) {
  if (mode == DepthMode::GlDefault) {
    const double scale = 16777215.0;
    return std::round(depth * scale) / scale;
  }
  return static_cast<double>(static_cast<float>(depth));
}

double windowDepth(const glm::dmat4& clipFromView, DepthConvention conv, glm::dvec3 vs) {
  const glm::dvec4 clip = clipFromView * glm::dvec4(vs, 1.0);
  const double ndcZ = clip.z / clip.w;
  return conv.range == DepthRange::ZeroToOne ? ndcZ : ndcZ * 0.5 + 0.5;
}

// View depth (along -z) rebuilt in double from a window depth: the reference.
double exactDist(const glm::dmat4& p, DepthConvention conv, double depth) {
  const double ndcZ = conv.range == DepthRange::ZeroToOne ? depth : depth * 2.0 - 1.0;
  if (p[3][3] == 1.0) return -(ndcZ - p[3][2]) / p[2][2];
  return p[3][2] / (ndcZ + p[2][2]);
}

struct Case {
  DepthMode mode;
  bool ortho;
  glm::dvec2 offsetPx;
};
void PrintTo(const Case& c, std::ostream* os) {
  *os << toString(c.mode) << (c.ortho ? " orthographic" : " perspective")
      << (c.offsetPx.x != 0.0 ? " off-centre" : "");
}

class Reconstruction : public ::testing::TestWithParam<Case> {};

TEST_P(Reconstruction, RoundTripWithinTheDepthFormatBound) {
  const Case c = GetParam();
  Camera cam;
  cam.nearPlane = 0.1;
  cam.farPlane = 1000.0;
  cam.orthographic = c.ortho;
  cam.orthoHeight = 20.0;
  const glm::dvec2 size(256.0, 128.0);
  const glm::dmat4 P = cam.clipFromView(c.mode, size.x / size.y, c.offsetPx, size);
  const DepthConvention conv = depthConvention(c.mode);
  auto reduced = sslr::detail::reduceProjection(P, conv);
  ASSERT_TRUE(reduced) << reduced.error();
  const SslrProjection proj = reduced.value();
  for (double dist : {0.101, 0.5, 1.0, 10.0, 100.0, 500.0, 990.0}) {
    for (glm::dvec2 uv : {glm::dvec2(0.5, 0.5), glm::dvec2(0.01, 0.99), glm::dvec2(0.9, 0.2)}) {
      // The view point seen at uv at this distance, built in double.
      const glm::dvec2 ndc = uv * 2.0 - 1.0;
      glm::dvec3 vs;
      if (c.ortho) {
        vs = {(ndc.x - P[3][0]) / P[0][0], (ndc.y - P[3][1]) / P[1][1], -dist};
      } else {
        vs = {dist * (ndc.x + P[2][0]) / P[0][0], dist * (ndc.y + P[2][1]) / P[1][1], -dist};
      }
      const double d = quantize(windowDepth(P, conv, vs), c.mode);
      // Analytic bound: |d(dist)/d(depth)| times half a depth step, plus float arithmetic.
      const double step = c.mode == DepthMode::GlDefault ? 1.0 / 16777215.0 : std::max(std::abs(d), 1e-30) * 0x1p-24;
      const double slope = std::abs(exactDist(P, conv, d + 1e-7 * step) - exactDist(P, conv, d - 1e-7 * step)) /
                           (2e-7 * step);
      const double quantBound = slope * step * 0.5;
      const double reference = exactDist(P, conv, d);  // exact distance for the stored depth
      const vec3 rebuilt = sslrViewFromUvDepth(proj, vec2(uv), static_cast<float>(d));
      // Float arithmetic on the stored depth: a few ulp relative (reversed D32F measures ~1e-7).
      // Float arithmetic: a few ulp of the distance, plus (orthographic) ulps of the depth range.
      const double arith = 6e-7 * dist + (c.ortho ? 4e-7 * cam.farPlane : 0.0);
      EXPECT_NEAR(-rebuilt.z, reference, arith + 1e-12)
          << toString(c.mode) << (c.ortho ? " ortho" : " persp") << " dist " << dist;
      // And against the true distance: within twice the format's analytic bound.
      EXPECT_NEAR(-rebuilt.z, dist, 2.0 * quantBound + arith)
          << toString(c.mode) << (c.ortho ? " ortho" : " persp") << " dist " << dist;
      if (c.mode != DepthMode::GlDefault && !c.ortho && (c.mode == DepthMode::Reversed || c.mode == DepthMode::ReversedInfinite)) {
        EXPECT_LE(std::abs(-rebuilt.z - dist) / dist, 1e-6) << "reversed D32F relative error, dist " << dist;
      }
      // x and y follow z exactly.
      const double scale = c.ortho ? 1.0 : -rebuilt.z / dist;
      EXPECT_NEAR(rebuilt.x, vs.x * scale, 1e-5 * std::max(1.0, std::abs(vs.x)) + 1e-6 * dist);
      EXPECT_NEAR(rebuilt.y, vs.y * scale, 1e-5 * std::max(1.0, std::abs(vs.y)) + 1e-6 * dist);
      // Projecting back lands on the same uv.
      const vec3 ndcBack = sslrNdcFromView(proj, vec3(vs));
      EXPECT_NEAR(ndcBack.x, ndc.x, 1e-5);
      EXPECT_NEAR(ndcBack.y, ndc.y, 1e-5);
    }
  }
}

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (DepthMode m : kModes)
    for (bool ortho : {false, true})
      for (glm::dvec2 off : {glm::dvec2(0.0), glm::dvec2(0.37, -0.25)}) cases.push_back({m, ortho, off});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllConventions, Reconstruction, ::testing::ValuesIn(allCases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = toString(info.param.mode);
                           for (char& ch : name) if (ch == '-') ch = '_';
                           return name + (info.param.ortho ? "_ortho" : "_persp") +
                                  (info.param.offsetPx.x != 0.0 ? "_offcentre" : "");
                         });

TEST(Projection, RejectsNonFiniteSingularAndSkewedMatrices) {
  Camera cam;
  const glm::dmat4 good = cam.clipFromView(DepthMode::Reversed, 1.5);
  ASSERT_TRUE(sslr::detail::reduceProjection(good, DepthConvention::reversed()));

  glm::dmat4 nan = good;
  nan[0][0] = std::nan("");
  auto r = sslr::detail::reduceProjection(nan, DepthConvention::reversed());
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("not finite"), std::string::npos) << r.error();

  glm::dmat4 singular = good;
  singular[1][1] = 0.0;
  r = sslr::detail::reduceProjection(singular, DepthConvention::reversed());
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("singular"), std::string::npos) << r.error();

  // Scales that single precision holds only as subnormals (1e-40) or not at all (1e-300) are
  // refused alike: the shaders would rebuild noise or zeros from them.
  for (double tiny : {1e-40, 1e-300}) {
    glm::dmat4 small = good;
    small[0][0] = tiny;
    r = sslr::detail::reduceProjection(small, DepthConvention::reversed());
    ASSERT_FALSE(r) << tiny;
    EXPECT_NE(r.error().find("underflow"), std::string::npos) << r.error();
  }

  glm::dmat4 skew = good;
  skew[1][0] = 0.2;
  r = sslr::detail::reduceProjection(skew, DepthConvention::reversed());
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("skew"), std::string::npos) << r.error();

  // The identity is FrameInputs' default: a host that forgot its projection is told so, whatever
  // the convention (it would pass as a reversed orthographic unit cube).
  for (const DepthConvention c : {DepthConvention::reversed(), DepthConvention::glDefault()}) {
    r = sslr::detail::reduceProjection(glm::dmat4(1.0), c);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find("identity"), std::string::npos) << r.error();
  }
  // An orthographic unit cube that is not exactly the identity is fine.
  glm::dmat4 cube(1.0);
  cube[2][2] = -1.0;
  EXPECT_TRUE(sslr::detail::reduceProjection(cube, DepthConvention::glDefault()));

  r = sslr::detail::reduceProjection(glm::dmat4(0.0), DepthConvention::reversed());
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("neither"), std::string::npos) << r.error();
}

// FrameInputs' enumerations out of range (a host's cast, uninitialised memory) are refused by name,
// not read as one of the valid values.
TEST(Projection, UnknownEnumerationsAndBadExposuresAreRefused) {
  Camera cam;
  FrameInputs good;
  good.clipFromView = cam.clipFromView(DepthMode::Reversed, 1.5);
  good.depth = DepthConvention::reversed();
  ASSERT_TRUE(frameConstants(good, Settings{}, 64, 64));
  struct Bad {
    const char* expected;
    void (*apply)(FrameInputs&);
  };
  const Bad cases[] = {
      {"surface.normals = 5 (not a sslr::NormalEncoding)",
       [](FrameInputs& in) { in.surface.normals = static_cast<NormalEncoding>(5); }},
      {"surface.space = 5 (not a sslr::NormalSpace)", [](FrameInputs& in) { in.surface.space = static_cast<NormalSpace>(5); }},
      {"depth.range = 7 (not a sslr::DepthRange)", [](FrameInputs& in) { in.depth.range = static_cast<DepthRange>(7); }},
      {"FrameInputs::exposure = 0", [](FrameInputs& in) { in.exposure = 0.0f; }},
      {"FrameInputs::exposure = inf", [](FrameInputs& in) { in.exposure = INFINITY; }},
  };
  for (const Bad& b : cases) {
    FrameInputs in = good;
    b.apply(in);
    auto r = frameConstants(in, Settings{}, 64, 64);
    ASSERT_FALSE(r) << b.expected;
    EXPECT_EQ(r.status().code(), StatusCode::InvalidInput);
    EXPECT_NE(r.error().find(b.expected), std::string::npos) << r.error();
  }
}

// The radiance clamp's limit is divided by the exposure: a tiny limit over a huge exposure is still
// a limit (the smallest normal float), never 0, which reads as "off"; off stays 0.
TEST(Projection, ARadianceClampThatUnderflowsStaysOn) {
  Camera cam;
  FrameInputs in;
  in.clipFromView = cam.clipFromView(DepthMode::Reversed, 1.5);
  in.depth = DepthConvention::reversed();
  in.exposure = 1e30f;
  Settings s;
  s.radianceClamp.maxLuminance = 1e-30f;
  auto r = frameConstants(in, s, 64, 64);
  ASSERT_TRUE(r) << r.error();
  EXPECT_EQ(r.value().trace.maxLuminance, std::numeric_limits<float>::min());
  s.radianceClamp.maxLuminance = 0.0f;
  r = frameConstants(in, s, 64, 64);
  ASSERT_TRUE(r) << r.error();
  EXPECT_EQ(r.value().trace.maxLuminance, 0.0f);
}

TEST(Projection, RejectsNearEqualsFarAndConventionMismatch) {
  Camera cam;
  cam.nearPlane = cam.farPlane = 5.0;
  // n == f: the standard matrix divides by zero (inf entries), the reversed one has zero slope.
  EXPECT_FALSE(sslr::detail::reduceProjection(cam.clipFromView(DepthMode::ZeroToOne, 1.0), DepthConvention::zeroToOne()));
  Camera ok;
  auto r = sslr::detail::reduceProjection(ok.clipFromView(DepthMode::ZeroToOne, 1.0), DepthConvention::reversed());
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("mismatch"), std::string::npos) << r.error();
  r = sslr::detail::reduceProjection(ok.clipFromView(DepthMode::Reversed, 1.0), DepthConvention::glDefault());
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("mismatch"), std::string::npos) << r.error();
}

// What the matrix can tell about the declared range: every matching pair passes (also covered by
// the reconstruction cases above); a reversed matrix declared with GL's -1..1 range puts the far
// end of the depth range behind the camera and is refused with the fix. A standard matrix built
// for one range and declared with the other cannot be told apart from a matrix with other planes
// (docs/conventions.md, "What sslr cannot check").
TEST(Projection, RangeMismatchesThatTheMatrixRevealsAreRefused) {
  Camera cam;
  const struct {
    DepthMode mode;
    DepthConvention declared;
    bool ok;
  } cases[] = {
      {DepthMode::Reversed, DepthConvention::reversed(), true},
      {DepthMode::ReversedInfinite, DepthConvention::reversed(), true},
      {DepthMode::ZeroToOne, DepthConvention::zeroToOne(), true},
      {DepthMode::GlDefault, DepthConvention::glDefault(), true},
      {DepthMode::Reversed, DepthConvention{DepthRange::NegativeOneToOne, true}, false},
      {DepthMode::ReversedInfinite, DepthConvention{DepthRange::NegativeOneToOne, true}, false},
  };
  for (const auto& c : cases) {
    auto r = sslr::detail::reduceProjection(cam.clipFromView(c.mode, 1.5), c.declared);
    EXPECT_EQ(bool(r), c.ok) << static_cast<int>(c.mode) << (r ? "" : ": " + r.error());
    if (!r && !c.ok) EXPECT_NE(r.error().find("GL_ZERO_TO_ONE"), std::string::npos) << r.error();
  }
  // A perspective matrix whose near end lies behind the camera under the declared convention.
  glm::dmat4 bad = cam.clipFromView(DepthMode::Reversed, 1.5);
  bad[2][2] = -2.0;  // ndc z = 2 + zOffset / dist: depth 1 (the near end) at dist = -zOffset
  auto r = sslr::detail::reduceProjection(bad, DepthConvention::reversed());
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("near end"), std::string::npos) << r.error();
}

TEST(Projection, DepthFromNdcInvertsNdcFromDepth) {
  for (int zeroToOne : {0, 1}) {
    SslrProjection p{};
    p.ndcZeroToOne = zeroToOne;
    for (float d : {0.0f, 0.25f, 0.5f, 1.0f})
      EXPECT_FLOAT_EQ(sslrDepthFromNdcZ(p, sslrNdcZFromDepth(p, d)), d);
  }
}

TEST(Projection, BackgroundDepthIsNotGeometry) {
  SslrSurface standard{}, reversed{};
  reversed.reversedZ = 1;
  EXPECT_FALSE(sslrIsGeometryDepth(standard, 1.0f));
  EXPECT_TRUE(sslrIsGeometryDepth(standard, 0.5f));
  EXPECT_FALSE(sslrIsGeometryDepth(reversed, 0.0f));
  EXPECT_TRUE(sslrIsGeometryDepth(reversed, 1e-30f));  // denormal-ish depth: far but real
  EXPECT_FALSE(sslrIsGeometryDepth(reversed, std::nanf("")));
  EXPECT_FALSE(sslrIsGeometryDepth(standard, std::nanf("")));
  EXPECT_FALSE(sslrIsGeometryDepth(standard, -0.5f));
  EXPECT_FALSE(sslrIsGeometryDepth(reversed, 1.5f));
  EXPECT_FALSE(sslrIsGeometryDepth(reversed, INFINITY));
}

// The traversal skips a cell whose nearest key (keySign x depth) is the background key; the
// pyramid's passes ask sslrHiZCellHoldsGeometry. Both must agree on every cell the pyramid can
// hold: any mix of geometry and of what the pyramid stores as background (the clear value, NaN,
// depths outside [0, 1]).
TEST(Projection, PyramidCellsOfBackgroundAloneHaveTheBackgroundKey) {
  const float samples[] = {0.0f, 1e-30f, 0.25f, 0.999f, 1.0f, -0.5f, 1.5f, std::nanf(""), INFINITY};
  for (int reversedZ : {0, 1}) {
    SslrSurface s{};
    s.reversedZ = reversedZ;
    const float keySign = reversedZ ? -1.0f : 1.0f;
    int background = 0, geometry = 0;
    for (float a : samples)
      for (float b : samples) {
        const vec2 cell = sslrHiZReduce(sslrHiZTexel(s, a), sslrHiZTexel(s, b));
        const float keyNear = std::min(keySign * cell.x, keySign * cell.y);
        const bool holds = sslrIsGeometryDepth(s, a) || sslrIsGeometryDepth(s, b);
        EXPECT_EQ(sslrHiZCellHoldsGeometry(s, cell), holds) << a << ", " << b << " reversed " << reversedZ;
        EXPECT_EQ(keyNear >= sslrHiZBackgroundKey(s), !holds) << a << ", " << b << " reversed " << reversedZ;
        ++(holds ? geometry : background);
      }
    EXPECT_GT(background, 0);
    EXPECT_GT(geometry, 0);
  }
}

}  // namespace

namespace {

// The classic error term must not depend on the scene's unit: scaling the reflecting point and
// the reflection length together leaves it unchanged (the article's k in world units did not:
// x100 kept 31% of the energy, x1e4 none).
TEST(Weights, ClassicErrorTermIsScaleFree) {
  using namespace sslr::shared;
  for (bool ortho : {false, true}) {
    SslrProjection p{};
    p.orthographic = ortho ? 1 : 0;
    const glm::vec3 vsP(1.2f, -0.7f, -6.0f);
    for (float L : {0.1f, 2.0f, 9.0f}) {
      const float reference = sslrErrorWeight(p, vsP, L, 0.15f);
      EXPECT_GT(reference, 0.0f);
      EXPECT_LT(reference, 1.0f);
      for (float scale : {1e-3f, 1e-1f, 1e2f, 1e4f})
        EXPECT_NEAR(sslrErrorWeight(p, vsP * scale, L * scale, 0.15f), reference, 1e-6f)
            << (ortho ? "ortho" : "perspective") << " L " << L << " scale " << scale;
    }
  }
}

}  // namespace

namespace {

// Temporal reuse's reprojection: a static point seen from a camera that has since moved sat
// elsewhere in the previous view; its previous uv follows from the previous projection, and the key is the previous view depth (perspective) or 2 + NDC z (orthographic), matching what
// sslrHistoryKey stores for the same point seen from there.
TEST(Temporal, ReprojectionFollowsTheCamera) {
  for (bool ortho : {false, true}) {
    Camera cam;
    cam.orthographic = ortho;
    cam.nearPlane = 0.1;
    cam.farPlane = 100.0;
    const glm::dmat4 clipFromView = cam.clipFromView(DepthMode::Reversed, 16.0 / 9.0);
    auto reduced = detail::reduceProjection(clipFromView, depthConvention(DepthMode::Reversed));
    ASSERT_TRUE(reduced);
    const SslrProjection p = reduced.value();
    const glm::dvec3 vsNow(0.4, -0.3, -6.0), moved(0.25, 0.0, 0.5);
    // previousViewFromView = a translation by `moved`: the static point sat at vsNow + moved.
    const glm::dmat4 previousClipFromView = clipFromView * glm::dmat4(1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0,
                                                                      moved.x, moved.y, moved.z, 1.0);
    glm::vec2 uv;
    float key = 0.0f;
    ASSERT_TRUE(sslrReproject(p, glm::mat4(previousClipFromView), glm::vec3(vsNow), uv, key));
    const glm::dvec3 vsThen = vsNow + moved;
    const glm::dvec4 clip = clipFromView * glm::dvec4(vsThen, 1.0);
    EXPECT_NEAR(uv.x, clip.x / clip.w * 0.5 + 0.5, 1e-6);
    EXPECT_NEAR(uv.y, clip.y / clip.w * 0.5 + 0.5, 1e-6);
    EXPECT_NEAR(key, sslrHistoryKey(p, glm::vec3(vsThen)), 1e-5f * key);
    if (!ortho) EXPECT_NEAR(key, -vsThen.z, 1e-5);
    EXPECT_TRUE(sslrHistoryKeyMatches(sslrHistoryKey(p, glm::vec3(vsThen)), key, 0.02f));
    // A surface 5% nearer (what hid the point) does not match; nothing stored (0) never does.
    const float nearer = sslrHistoryKey(p, glm::vec3(vsThen * 0.95));
    if (!ortho) EXPECT_FALSE(sslrHistoryKeyMatches(nearer, key, 0.02f));
    EXPECT_FALSE(sslrHistoryKeyMatches(0.0f, key, 0.02f));
    // Behind the previous camera or off its screen: no history.
    const glm::dmat4 behind = clipFromView * glm::dmat4(1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 10.0, 1.0);
    if (!ortho) EXPECT_FALSE(sslrReproject(p, glm::mat4(behind), glm::vec3(vsNow), uv, key));
    const glm::dmat4 aside = clipFromView * glm::dmat4(1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 50.0, 0, 0, 1.0);
    EXPECT_FALSE(sslrReproject(p, glm::mat4(aside), glm::vec3(vsNow), uv, key));
  }
}

}  // namespace

namespace {

// The virtual-point lookup for mirrors: the point X where the previous camera saw the reflection
// of Q in a plane mirror lies on the mirror, and the previous camera's ray reflected at X passes
// through Q (the law of reflection, checked against Q directly).
TEST(Temporal, VirtualPointObeysTheLawOfReflection) {
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  const glm::vec3 vsQ(-0.8f, 0.7f, -9.0f);  // a point above the floor plane y = -1
  // The current camera (at the origin) sees Q's mirror image through the point P of the floor on
  // the line to that image; then the reflected length is L = |Q - P|.
  const glm::vec3 mirrored(vsQ.x, -2.0f - vsQ.y, vsQ.z);
  const glm::vec3 p = mirrored * (-1.0f / mirrored.y);
  ASSERT_NEAR(p.y, -1.0f, 1e-5f);
  const float L = glm::length(vsQ - p);
  for (glm::vec3 eye : {glm::vec3(0.0f), glm::vec3(0.4f, 0.1f, 0.3f), glm::vec3(-1.0f, 0.5f, -0.5f)}) {
    glm::vec3 x;
    ASSERT_TRUE(sslrVirtualPointOnMirror(glm::vec4(eye, 1.0f), p, n, L, x));
    EXPECT_NEAR(x.y, -1.0f, 1e-4f) << "X lies on the mirror";
    const glm::vec3 reflected = glm::reflect(glm::normalize(x - eye), n);
    const glm::vec3 toQ = glm::normalize(vsQ - x);
    EXPECT_GT(glm::dot(reflected, toQ), 1.0f - 1e-5f) << "the reflected ray from the previous eye meets Q";
  }
  // Unknown eye (orthographic) or an eye below the mirror: no lookup.
  glm::vec3 x;
  EXPECT_FALSE(sslrVirtualPointOnMirror(glm::vec4(0.0f), p, n, L, x));
  EXPECT_FALSE(sslrVirtualPointOnMirror(glm::vec4(0.0f, -3.0f, 0.0f, 1.0f), p, n, L, x));
}

}  // namespace

namespace {

// Settings::radianceClamp's rule (sslr_shared.h, sslrClampLuminance): off (0) and below the limit
// the colour passes unchanged; above it the Rec. 709 luminance becomes the limit and the hue (the
// channels' ratios) stays.
TEST(RadianceClamp, ScalesBrightColoursDownToTheLimitKeepingTheirHue) {
  const vec3 sun(3000.0f, 2000.0f, 1000.0f);
  EXPECT_EQ(sslrClampLuminance(sun, 0.0f), sun) << "0: off";
  EXPECT_EQ(sslrClampLuminance(vec3(0.5f, 0.4f, 0.3f), 4.0f), vec3(0.5f, 0.4f, 0.3f)) << "below the limit";
  const vec3 clamped = sslrClampLuminance(sun, 4.0f);
  EXPECT_NEAR(glm::dot(clamped, vec3(0.2126f, 0.7152f, 0.0722f)), 4.0f, 1e-5f);
  EXPECT_NEAR(clamped.x / clamped.z, 3.0f, 1e-5f);
  EXPECT_NEAR(clamped.y / clamped.z, 2.0f, 1e-5f);
}

}  // namespace
