// The hit model (sslr_hit_model.h) on a synthetic depth buffer. Its verdict at a pixel
// (sslrJudgePixel: in front, near, inside, behind, a hit) and its answer inside a solid
// (sslrJudgeInside), then its rules one by one. Where a ray inside a solid went in (sslrEntryHit),
// first on a box whose front face ends at a pixel boundary, seen against a far wall: a ray from the
// right that crosses the outline a little behind the front face meets the box's side there,
// exactly where a right-angled corner puts it (sslrCornerHit). Every condition of the side has a
// case that must refuse the hit: a hidden side, a side seen nearly edge-on, a hit the outer pixel
// would have shown, a hit deeper than the slab, no outline, and a ray that did not cross the
// outline there. On the same buffer, with the far surface moved close behind the front one and
// level 0 holding curved solids' extra depth: a crease between two samples of one curved surface,
// and the cases it must refuse. With the box's samples receding and its normals turning towards
// the edge and no extra depth: the rim and a crease of a curved surface near its outline
// (sslrRimHit), and the flat faces and box edges that meet their side instead. And
// sslrPlaneHit's contact line, whose plane must come from a pixel touching the mirror pixel, and
// whose colour comes from the pixel beside it (sslrColorUv); a hit beside an outline lies off the
// nearer face's plane (sslrGapToTexelPlane, which lobe rays read their colour by). The walk's
// thickness test at a cell (sslrPassesBehindCell) against its view-depth bound, where its hidden
// guess reads its colour (sslrWalkGuess) and where it ends at the screen's edge. Its own executable:
// it defines the loaders the tracer headers call, which sslr_host also defines for its CPU run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "projection.hpp"
#include "shared_frame.hpp"
#include "sslr_host/camera.hpp"
#include "sslr_shared.h"

namespace sslr::shared {
namespace {
constexpr int kWidth = 320, kHeight = 180;
constexpr float kFrontZ = -10.0f, kWallZ = -50.0f;
float gWallZ = kWallZ;
float gCurvedExtra = 0.0f;  // level 0's extra depth on every pixel (0: flat surfaces)

SslrProjection gProj{};
SslrSurface gSurf{};
// The box's front face covers window x < gEdgePx (boxOnLeft) or x >= gEdgePx (the box to the right
// of its edge), at view depth 10; the far wall covers the rest.
float gEdgePx = 130.0f;
bool gBoxOnLeft = true;
float gBarWidthPx = 0.0f;  // > 0: the box is a bar this many columns wide, ending at its edge

bool showsBox(ivec2 px) {
  const float xc = float(px.x) + 0.5f;
  if (gBarWidthPx > 0.0f && std::abs(xc - gEdgePx) > gBarWidthPx) return false;
  return gBoxOnLeft ? xc < gEdgePx : xc >= gEdgePx;
}
// The box's surface recedes towards its edge by gRimRecede view units a pixel column (the outline
// column at depth 10), and the shading normals turn towards +x by gNormalTurn radians a column.
float gRimRecede = 0.0f, gNormalTurn = 0.0f;
float columnsFromEdge(ivec2 px) { return (gEdgePx - 0.5f) - (float(px.x) + 0.5f); }
float viewZAt(ivec2 px) { return showsBox(px) ? kFrontZ + gRimRecede * columnsFromEdge(px) : gWallZ; }
}  // namespace

// The window depth a pixel's surface writes (the inverse of the reconstruction).
float sslrLoadDepth(ivec2 px) { return sslrDepthFromViewDepth(gProj, -viewZAt(px)); }
vec4 sslrLoadNormal(ivec2 px) {
  // Facing the camera at the box's outline column, turned by gNormalTurn a column towards +x.
  const float a = -gNormalTurn * columnsFromEdge(px);
  const vec2 e = sslrOctEncode(vec3(std::sin(a), 0.0f, std::cos(a)));
  return vec4(e.x, e.y, 0.0f, 0.0f);
}
bool sslrLoadSurface(ivec2 px, vec3& vsPos) { return sslrSurfaceFromDepth(gProj, gSurf, px, sslrLoadDepth(px), vsPos); }
// sslrEntryHit reads level 0 alone; sslrSlabNearOutline (gCoarseLevels) reads the levels above
// it, each cell the (min, max) of its pixels' depths.
bool gCoarseLevels = false;
int gFetchesOutside = 0;  // pyramid texels read outside their level's cells (none may be)
vec2 sslrLoadPyramidTexel(int level, ivec2 cell) {
  const int side = 1 << level;
  if (cell.x < 0 || cell.y < 0 || cell.x >= (int(gSurf.width) + side - 1) / side ||
      cell.y >= (int(gSurf.height) + side - 1) / side)
    ++gFetchesOutside;
  if (level == 0) return sslrHiZLevel0Texel(gSurf, sslrLoadDepth(cell), gCurvedExtra);
  EXPECT_TRUE(gCoarseLevels) << "level " << level;
  vec2 minMax(1.0f, 0.0f);
  for (int y = cell.y << level; y < std::min((cell.y + 1) << level, int(gSurf.height)); ++y)
    for (int x = cell.x << level; x < std::min((cell.x + 1) << level, int(gSurf.width)); ++x)
      minMax = sslrHiZReduce(minMax, sslrHiZTexel(gSurf, sslrLoadDepth(ivec2(x, y))));
  return minMax;
}
}  // namespace sslr::shared

#include "sslr_trace_hiz.h"
#include "sslr_trace_ffx.h"

using namespace sslr;
using namespace sslr::shared;

namespace {

class CornerHit : public ::testing::Test {
 protected:
  void SetUp() override {
    host::Camera cam;
    cam.nearPlane = 0.1;
    cam.farPlane = 1000.0;
    auto reduced = sslr::detail::reduceProjection(cam.clipFromView(host::DepthMode::Reversed, double(kWidth) / kHeight),
                                                  depthConvention(host::DepthMode::Reversed));
    ASSERT_TRUE(reduced) << reduced.error();
    gProj = reduced.value();
    gSurf = SslrSurface{};
    gSurf.normalEncoding = SSLR_NORMALS_OCTAHEDRAL;
    gSurf.width = kWidth;
    gSurf.height = kHeight;
    gSurf.reversedZ = 1;
    gEdgePx = 130.0f;
    gBoxOnLeft = true;
    gBarWidthPx = 0.0f;
    gCoarseLevels = false;
    gFetchesOutside = 0;
    gWallZ = kWallZ;
    gCurvedExtra = 0.0f;
    gRimRecede = 0.0f;
    gNormalTurn = 0.0f;
  }

  // The view point at window (x, y) on the plane z = viewZ.
  static vec3 viewAt(float x, float y, float viewZ) {
    const vec3 onRay = sslrViewFromUvDepth(gProj, vec2(x / kWidth, y / kHeight), 0.5f);
    return onRay * (viewZ / onRay.z);
  }

  // The ray's length where a ray from vsP along vsR crosses window x = xPx (bisection).
  static float lengthAtColumn(vec3 vsP, vec3 vsR, float xPx) {
    float lo = 0.0f, hi = 100.0f;
    const float sideP = sslrWindowFromView(gProj, vec2(kWidth, kHeight), -1.0f, vsP).x - xPx;
    for (int i = 0; i < 80; ++i) {
      const float mid = 0.5f * (lo + hi);
      const float side = sslrWindowFromView(gProj, vec2(kWidth, kHeight), -1.0f, vsP + vsR * mid).x - xPx;
      ((side > 0.0f) == (sideP > 0.0f) ? lo : hi) = mid;
    }
    return hi;
  }
  // Where that ray crosses window x = xPx.
  static vec3 windowCrossing(vec3 vsP, vec3 vsR, float xPx) {
    return sslrWindowFromView(gProj, vec2(kWidth, kHeight), -1.0f, vsP + vsR * lengthAtColumn(vsP, vsR, xPx));
  }

  // Where the ray crosses window x = xPx, moved on by `nudge` pixels as the traversal's nudge
  // leaves it, and its window-space direction (major axis 1), as the traversal's loop holds them.
  struct Entry {
    vec3 wEntry, d;
  };
  static Entry entryAt(vec3 vsP, vec3 vsR, float xPx, float nudge) {
    const vec3 wCross = windowCrossing(vsP, vsR, xPx);
    vec3 d = wCross - sslrWindowFromView(gProj, vec2(kWidth, kHeight), -1.0f, vsP);
    d /= std::max(std::abs(d.x), std::abs(d.y));
    return {wCross + d * nudge, d};
  }

  // The corner rule for a ray aimed at `vsTarget` from `vsP`, entering the box's outline pixel
  // (the box's last pixel column before the edge) through the edge.
  // `slab`: the assumed depth of what the screen shows, in view units at the box's distance 10.
  static bool corner(vec3 vsP, vec3 vsTarget, float slab, float& L) {
    const vec3 vsR = normalize(vsTarget - vsP);
    const Entry e = entryAt(vsP, vsR, gEdgePx, 1.0f / 256.0f);
    EXPECT_EQ(int(std::floor(e.wEntry.x)), gBoxOnLeft ? int(gEdgePx) - 1 : int(gEdgePx)) << "the box's outline pixel";
    return sslrEntryHit(gProj, gSurf, params(slab), e.wEntry, e.d, vsP, vsR, L);
  }

  static SslrTraceParams params(float slab) {
    SslrTraceParams t{};
    t.objectDepthRelative = slab / -kFrontZ;
    return t;
  }
};

TEST_F(CornerHit, MeetsTheSideOfABoxWhereARightAngledCornerPutsIt) {
  // The side x = edge, 0.1 behind the front face: 30 px left of the centre it projects 0.29 px
  // outside the outline, before the outer pixel's centre. The ray comes from the right, towards
  // the side, going away from the camera.
  const vec3 vsEdge = viewAt(gEdgePx, 90.5f, kFrontZ);
  const vec3 vsQ = vec3(vsEdge.x, vsEdge.y, kFrontZ - 0.1f);
  const vec3 vsP = vsQ + vec3(4.0f, 0.3f, 1.5f);
  float L = 0.0f;
  ASSERT_TRUE(corner(vsP, vsQ, 0.75f, L));
  // The rule's edge is the pixel boundary on the front plane: here the true edge (float rounding
  // of the unprojection: 1e-4 relative).
  EXPECT_NEAR(L, length(vsQ - vsP), 1e-4f * length(vsQ - vsP));
}

TEST_F(CornerHit, RefusesAHiddenSide) {
  // The box lies to the right of its edge, left of the screen centre: its left side faces away.
  gBoxOnLeft = false;
  const vec3 vsEdge = viewAt(gEdgePx, 90.5f, kFrontZ);
  const vec3 vsQ = vec3(vsEdge.x, vsEdge.y, kFrontZ - 0.1f);
  float L = 0.0f;
  EXPECT_FALSE(corner(vsQ + vec3(-4.0f, 0.3f, 1.5f), vsQ, 0.75f, L));
}

TEST_F(CornerHit, RefusesAHitTheOuterPixelWouldShow) {
  // 0.5 behind the front face the side projects ~1.5 px outside the outline: past the outer
  // pixel's centre, which shows the wall, so the side cannot reach that deep there.
  const vec3 vsEdge = viewAt(gEdgePx, 90.5f, kFrontZ);
  const vec3 vsQ = vec3(vsEdge.x, vsEdge.y, kFrontZ - 0.5f);
  float L = 0.0f;
  EXPECT_FALSE(corner(vsQ + vec3(4.0f, 0.3f, 1.5f), vsQ, 0.75f, L));
}

TEST_F(CornerHit, RefusesAHitDeeperThanTheSlab) {
  const vec3 vsEdge = viewAt(gEdgePx, 90.5f, kFrontZ);
  const vec3 vsQ = vec3(vsEdge.x, vsEdge.y, kFrontZ - 0.1f);
  float L = 0.0f;
  EXPECT_FALSE(corner(vsQ + vec3(4.0f, 0.3f, 1.5f), vsQ, 0.05f, L));
  EXPECT_TRUE(corner(vsQ + vec3(4.0f, 0.3f, 1.5f), vsQ, 0.15f, L));
}

TEST_F(CornerHit, RefusesWithoutAnOutline) {
  // The outer pixel shows the box too (its edge moved two pixels right): no outline to cross.
  const vec3 vsEdge = viewAt(gEdgePx, 90.5f, kFrontZ);
  const vec3 vsQ = vec3(vsEdge.x, vsEdge.y, kFrontZ - 0.1f);
  const vec3 vsP = vsQ + vec3(4.0f, 0.3f, 1.5f);
  gEdgePx = 132.0f;
  const vec3 vsR = normalize(vsQ - vsP);
  const Entry e = entryAt(vsP, vsR, 130.0f, 1.0f / 256.0f);
  ASSERT_EQ(int(std::floor(e.wEntry.x)), 129);
  float L = 0.0f;
  EXPECT_FALSE(sslrEntryHit(gProj, gSurf, params(0.75f), e.wEntry, e.d, vsP, vsR, L));
}

TEST_F(CornerHit, RefusesARayThatDidNotEnterThroughTheOutline) {
  // Moved on inside the pixel (as after descending to where the ray reaches the cell's depth).
  const vec3 vsEdge = viewAt(gEdgePx, 90.5f, kFrontZ);
  const vec3 vsQ = vec3(vsEdge.x, vsEdge.y, kFrontZ - 0.1f);
  const vec3 vsP = vsQ + vec3(4.0f, 0.3f, 1.5f);
  const vec3 vsR = normalize(vsQ - vsP);
  const Entry e = entryAt(vsP, vsR, gEdgePx - 0.5f, 0.0f);
  ASSERT_EQ(int(std::floor(e.wEntry.x)), int(gEdgePx) - 1);
  float L = 0.0f;
  EXPECT_FALSE(sslrEntryHit(gProj, gSurf, params(0.75f), e.wEntry, e.d, vsP, vsR, L));
}

TEST_F(CornerHit, RefusesASideSeenNearlyEdgeOn) {
  // 2 px left of the centre the side is within ~1 degree of the view ray.
  gEdgePx = 158.0f;
  const vec3 vsEdge = viewAt(gEdgePx, 90.5f, kFrontZ);
  const vec3 vsQ = vec3(vsEdge.x, vsEdge.y, kFrontZ - 0.1f);
  float L = 0.0f;
  EXPECT_FALSE(corner(vsQ + vec3(4.0f, 0.3f, 1.5f), vsQ, 0.75f, L));
}

}  // namespace

namespace {

// Thin objects (sslrMetThinObject): a ray that went into the assumed slab of what a pixel shows met
// the object's hidden side when the object is at most 16 px and a 30th of the screen height (here
// 6 px) across around that pixel, and the ray went in less deep than its width and than 6 pixel
// footprints. The width is counted in steps of 1, 2, 4, 8 and 16 px each way from the pixel. A
// 4-column bar seen square on: 3 footprints deep is a hit, 5 is not (deeper than the bar is wide),
// nor 7 (past 6), and neither is 3 behind a 12-column bar (counted 10 wide from its second column)
// or the wide box.
TEST_F(CornerHit, ThinObjectsAreAsDeepAsTheyAreWide) {
  const ivec2 px(int(gEdgePx) - 2, 90);
  const vec3 vsN(0.0f, 0.0f, 1.0f);
  auto met = [&](float footprintsBehind) {
    vec3 vsSurface;
    EXPECT_TRUE(sslrLoadSurface(px, vsSurface));
    const float footprint = sslrPixelFootprint(gProj, gSurf.height, sslrClipW(gProj, vsSurface));
    const float tolerance = sslrHitTolerance(gProj, gSurf, -vsSurface.z, 0.0f);
    return sslrMetThinObject(gProj, gSurf, px, vsSurface, vsN, tolerance, footprintsBehind * footprint);
  };
  gBarWidthPx = 4.0f;
  EXPECT_TRUE(met(3.0f));
  EXPECT_FALSE(met(5.0f));
  EXPECT_FALSE(met(7.0f));
  gBarWidthPx = 12.0f;
  EXPECT_FALSE(met(3.0f));
  gBarWidthPx = 0.0f;
  EXPECT_FALSE(met(3.0f));
}

// Outline thinning (sslrSlabNearOutline): near an object's outline the slab is no deeper than a
// right-angled corner of the shown face allows, d (cot a + tan a) at d pixels from the outline (a
// the face's angle to the view ray), d bounded by 1.5 cells of the smallest pyramid level whose
// cell around the pixel holds a surface beyond the ray (here the wall past the box's edge at
// x = 130). The face at 45 degrees: 2 footprints of depth a pixel. At the edge column (129) the
// level-1 cell (128-129) is all box, the level-2 cell (128-131) holds the wall: 1.5 x 4 x 2 = 12
// footprints. 60 columns in, no cell below the slab's bound reaches the wall: the slab.
TEST_F(CornerHit, TheSlabThinsNearTheOutline) {
  gCoarseLevels = true;
  SslrTraceParams t{};
  t.hizLevels = sslrHiZLevelCount(kWidth, kHeight);
  const float footprint = sslrPixelFootprint(gProj, gSurf.height, -kFrontZ);
  const float slab = 40.0f * footprint;
  const float keyBehindBox = -sslrDepthFromViewDepth(gProj, -kFrontZ + 1.0f);  // reversed Z: key = -depth
  // A face at 45 degrees to the view ray at each pixel.
  auto thinned = [&](int x) {
    const vec3 vsSurface = viewAt(float(x) + 0.5f, 90.5f, kFrontZ);
    const vec3 view = sslrViewDirection(gProj, vsSurface);
    const vec3 n45 = normalize(-view + normalize(cross(view, vec3(0.0f, 1.0f, 0.0f))));
    return sslrSlabNearOutline(gProj, gSurf, t, ivec2(x, 90), vsSurface, n45, keyBehindBox, -1.0f, slab);
  };
  EXPECT_NEAR(thinned(129), 12.0f * footprint, 1e-3f * footprint);
  EXPECT_EQ(thinned(70), slab);  // levels 1-3 all box; level 4's bound (48) is past the slab
}

// FidelityFX SSSR's depth hierarchy as AMD ships it: mip sizes max(1, size >> level) from the
// render size, rounded down; a cell past a mip's size reads as background (its loads return 0)
// without a fetch. 320x180: level 3 is 40x22 (180 / 8 = 22.5), so row 22 is no cell of FFX's,
// though sslr's padded pyramid holds one there (whose fetch this test's loader refuses).
TEST_F(CornerHit, FfxMipsRoundDownAndReadBackgroundPastTheirSize) {
  EXPECT_EQ(sslrFfxMipSize(gSurf, 3).x, 40.0f);
  EXPECT_EQ(sslrFfxMipSize(gSurf, 3).y, 22.0f);
  EXPECT_EQ(sslrFfxMipSize(gSurf, 9).y, 1.0f) << "never below one texel";
  const float keySign = -1.0f;  // reversed Z
  const float farKey = sslrFfxNearKey(gSurf, 3, vec2(0.0f, 22.0f), keySign, 5);
  EXPECT_EQ(farKey, 0.0f) << "row 22 of level 3 lies past FFX's mip: background";
  EXPECT_EQ(sslrFfxNearKey(gSurf, 3, vec2(40.0f, 0.0f), keySign, 5), 0.0f);
  // FFX walks up to level 6 where sslr's pyramid stops at 5 (320x180): its mip 6 is 5x2, so the
  // top 52 rows (row 2 and up) are background there.
  EXPECT_EQ(sslrFfxMipSize(gSurf, 6).y, 2.0f);
  EXPECT_EQ(sslrFfxNearKey(gSurf, 6, vec2(0.0f, 2.0f), keySign, 5), 0.0f);
  // Level 0 is the depth buffer itself: every pixel is in range.
  EXPECT_EQ(sslrFfxNearKey(gSurf, 0, vec2(319.0f, 179.0f), keySign, 5), keySign * sslrLoadDepth(ivec2(319, 179)));
}

// A faceted curved surface seen at an angle steps in depth from pixel to pixel: here the pixels
// left of the edge at view depth 10, those right of it at 10.05, both on a curved solid (level 0's
// extra depth). A ray from the right, in front of the farther samples, crosses the edge at depth
// 10.02, behind the nearer ones: it crossed the surface between the two samples, at the edge.
class CurvedEntryHit : public CornerHit {
 protected:
  void SetUp() override {
    CornerHit::SetUp();
    gWallZ = kFrontZ - 0.05f;
    gCurvedExtra = 0.5f;
  }
  // Whether vsHit lies on the box's side: the plane x = the edge's x on the front face. A point at
  // the edge's window x 0.02-0.03 behind the front face lies 0.004-0.006 view units off it (the
  // answer across the two samples); the tolerance is a tenth of that and ~50x the unprojection's
  // float rounding here.
  static bool onTheSide(vec3 vsHit) {
    const vec3 wHit = sslrWindowFromView(gProj, vec2(kWidth, kHeight), -1.0f, vsHit);
    return std::abs(vsHit.x - viewAt(gEdgePx, wHit.y, kFrontZ).x) <= 5e-4f;
  }
  static SslrTraceParams curvedParams() {
    SslrTraceParams t = params(0.75f);
    t.curvedSolids = 1;
    return t;
  }
  // The rule for a ray from vsP towards vsTarget, entering the edge's pixel column through the edge
  // (or, with inside > 0, moved on that far into it).
  static bool entryHit(vec3 vsP, vec3 vsTarget, float& L, float inside = 0.0f) {
    const vec3 vsR = normalize(vsTarget - vsP);
    const Entry e = entryAt(vsP, vsR, gEdgePx - inside, 1.0f / 256.0f);
    EXPECT_EQ(int(std::floor(e.wEntry.x)), int(gEdgePx) - 1);
    return sslrEntryHit(gProj, gSurf, curvedParams(), e.wEntry, e.d, vsP, vsR, L);
  }
};

TEST_F(CurvedEntryHit, HitsACreaseBetweenTwoSamplesOfOneSurfaceAtTheEdge) {
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.02f);
  const vec3 vsP = vsQ + vec3(4.0f, 0.3f, 1.5f);
  float L = 0.0f;
  ASSERT_TRUE(entryHit(vsP, vsQ, L));
  // At the edge, moved on by the traversal's nudge (1/256 px: ~1e-4 of the ray's length here).
  EXPECT_NEAR(L, length(vsQ - vsP), 2e-3f * length(vsQ - vsP));
}

TEST_F(CurvedEntryHit, RefusesAnOutline) {
  // The far samples 40 units behind: no one surface, the ray passes behind the near ones' outline.
  gWallZ = kWallZ;
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.02f);
  float L = 0.0f;
  EXPECT_FALSE(entryHit(vsQ + vec3(4.0f, 0.3f, 1.5f), vsQ, L));
}

// Without extra depth and with one normal, the pixel shows a flat face: a ray that crosses its
// outline just behind it meets the face's side (the corner's right angle: the plane through the
// edge along the view depth), not the surface between the two samples.
TEST_F(CurvedEntryHit, AFlatPixelMeetsItsFacesSide) {
  gCurvedExtra = 0.0f;
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.02f);
  const vec3 vsP = vsQ + vec3(4.0f, 0.3f, 1.5f);
  float L = 0.0f;
  ASSERT_TRUE(entryHit(vsP, vsQ, L));
  EXPECT_TRUE(onTheSide(vsP + normalize(vsQ - vsP) * L));
}

TEST_F(CurvedEntryHit, RefusesARayBehindBothSamples) {
  // At depth 10.3 the ray is behind the far samples too: it did not come from in front of them.
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.3f);
  float L = 0.0f;
  EXPECT_FALSE(entryHit(vsQ + vec3(4.0f, 0.3f, 1.5f), vsQ, L));
}

TEST_F(CurvedEntryHit, InsideAPixelHitsOnlyOnItsSurface) {
  // Moved on 0.3 px into the pixel: a hit if the ray there lies on the pixel's surface within the
  // hit tolerance (0.02 + 1.5 footprints, ~0.1 at depth 10), not 0.5 behind it.
  const vec3 vsNear = viewAt(gEdgePx - 0.3f, 90.5f, kFrontZ - 0.01f);
  float L = 0.0f;
  EXPECT_TRUE(entryHit(vsNear + vec3(4.0f, 0.3f, 1.5f), vsNear, L, 0.3f));
  const vec3 vsFar = viewAt(gEdgePx - 0.3f, 90.5f, kFrontZ - 0.5f);
  EXPECT_FALSE(entryHit(vsFar + vec3(4.0f, 0.3f, 1.5f), vsFar, L, 0.3f));
}

// Without curved extra depth (sslrRimHit): the box is a curved surface near its outline, and level
// 0 holds no extra depth. Its columns recede by 0.05 a column towards the edge and the normals
// turn by 3 degrees a column. A ray from the right crosses the edge from the far wall (the rim)
// or, with the wall moved close behind, from a sample of the same surface (a crease).
class RimEntryHit : public CurvedEntryHit {
 protected:
  void SetUp() override {
    CurvedEntryHit::SetUp();
    gCurvedExtra = 0.0f;
    gWallZ = kWallZ;
    gRimRecede = 0.05f;
    gNormalTurn = 3.0f * 3.14159265f / 180.0f;
  }
  static bool rimHit(vec3 vsP, vec3 vsTarget, float& L, vec3& wHit) {
    const vec3 vsR = normalize(vsTarget - vsP);
    const Entry e = entryAt(vsP, vsR, gEdgePx, 1.0f / 256.0f);
    EXPECT_EQ(int(std::floor(e.wEntry.x)), int(gEdgePx) - 1);
    const bool hit = sslrEntryHit(gProj, gSurf, curvedParams(), e.wEntry, e.d, vsP, vsR, L);
    wHit = sslrWindowFromView(gProj, vec2(kWidth, kHeight), -1.0f, vsP + vsR * L);
    return hit;
  }
  static vec3 rayFrom(vec3 vsQ) { return vsQ + vec3(4.0f, 0.3f, 1.5f); }
};

TEST_F(RimEntryHit, HitsARayBehindTheRimsSampleByLessThanTheSurfaceRecedes) {
  // Across the edge 0.03 behind the rim's sample (the column inwards is 0.05 nearer).
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.03f);
  float L = 0.0f;
  vec3 wHit;
  ASSERT_TRUE(rimHit(rayFrom(vsQ), vsQ, L, wHit));
  // Reported halfway across the rim pixel (its colour, not the wall's): x = edge - 0.5.
  EXPECT_NEAR(wHit.x, gEdgePx - 0.5f, 0.02f);
  EXPECT_GT(L, length(vsQ - rayFrom(vsQ)));
}

TEST_F(RimEntryHit, RefusesARayBehindTheRimByMoreThanItRecedes) {
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.08f);
  float L = 0.0f;
  vec3 wHit;
  EXPECT_FALSE(rimHit(rayFrom(vsQ), vsQ, L, wHit));
}

TEST_F(RimEntryHit, AFlatFaceEndsInItsSideNotARim) {
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.03f);
  float L = 0.0f;
  vec3 wHit;
  gNormalTurn = 0.0f;  // one normal: a flat face, whose side meets it at its outline
  ASSERT_TRUE(rimHit(rayFrom(vsQ), vsQ, L, wHit));
  EXPECT_TRUE(onTheSide(rayFrom(vsQ) + normalize(vsQ - rayFrom(vsQ)) * L));
  EXPECT_GT(wHit.x, gEdgePx - 0.1f) << "not halfway across the rim pixel";
}

TEST_F(RimEntryHit, RefusesASurfaceNotReceding) {
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.03f);
  float L = 0.0f;
  vec3 wHit;
  gRimRecede = -0.05f;  // nearer towards the edge: no rim turning away
  EXPECT_FALSE(rimHit(rayFrom(vsQ), vsQ, L, wHit));
}

// With extra depth the pixel takes the curved branch, where an outline is no crossing of one surface.
TEST_F(RimEntryHit, LeavesCurvedPixelsToTheCurvedEntryRule) {
  gCurvedExtra = 0.5f;
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.03f);
  float L = 0.0f;
  vec3 wHit;
  EXPECT_FALSE(rimHit(rayFrom(vsQ), vsQ, L, wHit));
}

TEST_F(RimEntryHit, HitsACreaseOfOneCurvedSurfaceAndABoxsEdgeAtItsSide) {
  // The wall 0.05 behind the rim's sample: the same surface, its normal turned 3 degrees further.
  gWallZ = kFrontZ - 0.05f;
  const vec3 vsQ = viewAt(gEdgePx, 90.5f, kFrontZ - 0.02f);
  float L = 0.0f;
  vec3 wHit;
  ASSERT_TRUE(rimHit(rayFrom(vsQ), vsQ, L, wHit));
  EXPECT_NEAR(L, length(vsQ - rayFrom(vsQ)), 2e-3f * length(vsQ - rayFrom(vsQ)));  // at the edge
  // Normals 60 degrees apart: two faces meeting at an edge, not one curved surface. The ray meets
  // the side of the face the outline pixel shows.
  gNormalTurn = 60.0f * 3.14159265f / 180.0f;
  ASSERT_TRUE(rimHit(rayFrom(vsQ), vsQ, L, wHit));
  EXPECT_TRUE(onTheSide(rayFrom(vsQ) + normalize(vsQ - rayFrom(vsQ)) * L));
}

// sslrPlaneHit's contact line: a ray from a mirror pixel meets the plane of the surface standing on
// the mirror inside the mirror pixel itself. That holds when the plane's pixel touches the mirror
// pixel; from four pixels away the plane reaches the mirror pixel only by extension (the pixels
// between show something else: a thin leg's tangent plane, not a foot); and when the surface rises
// from the mirror rather than facing it.
TEST_F(CornerHit, AContactLinesPlaneMustComeFromANeighbouringPixel) {
  const ivec2 pxOrigin(200, 90);
  const vec3 vsP = viewAt(200.5f, 90.5f, kFrontZ);
  const float footprint = sslrPixelFootprint(gProj, float(kHeight), -kFrontZ);
  // A wall standing on the mirror (perpendicular to it, facing the ray) that the ray meets 0.3
  // footprints to the right of vsP, inside the mirror pixel. The mirror's normal is the one that
  // reflects the view into vsR. The same wall point is given as the plane's surface sample for
  // either pixel, so only where the plane comes from differs.
  const vec3 vsR = normalize(vec3(1.0f, 0.0f, -1.0f));
  const vec3 vsMirrorNormal = normalize(vsR - normalize(vsP));
  const vec3 vsWallNormal = -normalize(vsR - dot(vsR, vsMirrorNormal) * vsMirrorNormal);
  const vec3 vsWall = vsP + vsR * (0.3f * footprint * std::sqrt(2.0f));
  float L = 0.0f;
  EXPECT_GE(sslrPlaneHit(gProj, gSurf, pxOrigin, vsP, vsR, ivec2(201, 90), vsWall, vsWallNormal, L), 0.5f);
  EXPECT_NEAR(L, 0.3f * footprint * std::sqrt(2.0f), 0.01f * footprint);
  EXPECT_EQ(sslrPlaneHit(gProj, gSurf, pxOrigin, vsP, vsR, ivec2(204, 90), vsWall, vsWallNormal, L), 0.0f);
  // The same point on a surface that faces the mirror (160 degrees from its normal: a sphere's
  // underside beside where it rests) is no contact: its plane reaches the mirror across a gap.
  const vec3 vsFacing = normalize(-vsMirrorNormal + 0.35f * vsWallNormal);
  ASSERT_LT(dot(vsR, vsFacing), -0.05f);
  EXPECT_EQ(sslrPlaneHit(gProj, gSurf, pxOrigin, vsP, vsR, ivec2(201, 90), vsWall, vsFacing, L), 0.0f);
}

// A contact line's hit lies inside the mirror pixel, which shows the mirror: its colour comes from
// the pixel the ray heads into on screen (sslrColorUv). Any other hit's colour is read where it is.
TEST_F(CornerHit, AContactLinesColourComesFromThePixelTheRayHeadsInto) {
  const vec3 vsP = viewAt(200.5f, 90.5f, kFrontZ);
  const vec2 size{float(kWidth), float(kHeight)};
  const float footprint = sslrPixelFootprint(gProj, float(kHeight), -kFrontZ);
  struct Case {
    vec3 vsR;
    ivec2 pxColor;
  };
  // Rays leaning mostly right, left, up and down on screen (and a little away from the camera).
  for (const Case& c : {Case{normalize(vec3(1.0f, 0.3f, -1.0f)), ivec2(201, 90)},
                        Case{normalize(vec3(-1.0f, 0.3f, -1.0f)), ivec2(199, 90)},
                        Case{normalize(vec3(0.3f, 1.0f, -1.0f)), ivec2(200, 91)},
                        Case{normalize(vec3(-0.3f, -1.0f, -1.0f)), ivec2(200, 89)}}) {
    // The hit 0.3 footprints along the ray: still inside the mirror pixel.
    const vec3 wHit = sslrWindowFromView(gProj, size, 1.0f, vsP + c.vsR * (0.3f * footprint));
    const vec2 uvHit = vec2(wHit.x, wHit.y) / size;
    ASSERT_EQ(ivec2(floor(uvHit * size)), ivec2(200, 90));
    const vec2 uvColor = sslrColorUv(gProj, gSurf, vsP, c.vsR, uvHit);
    EXPECT_EQ(ivec2(floor(uvColor * size)), c.pxColor);
    EXPECT_NEAR(uvColor.x * size.x - std::floor(uvColor.x * size.x), 0.5f, 1e-3f) << "at the pixel's centre";
    EXPECT_NEAR(uvColor.y * size.y - std::floor(uvColor.y * size.y), 0.5f, 1e-3f);
    // Three footprints along: a hit in another pixel, read where it is.
    const vec3 wFar = sslrWindowFromView(gProj, size, 1.0f, vsP + c.vsR * (3.0f * footprint));
    const vec2 uvFar = vec2(wFar.x, wFar.y) / size;
    EXPECT_EQ(sslrColorUv(gProj, gSurf, vsP, c.vsR, uvFar), uvFar);
  }
}

// sslrGapToTexelPlane: how far a hit lies from a texel's tangent plane, in hit tolerances there. A
// ray drawn from a rough pixel's lobe reads its colour from the texels whose plane holds its hit
// (sslrSurfaceColor in passes/shade_pixel.glsl), not across an outline as a bilinear read does. A
// hit on the far wall next to the box's outline is on the wall texels' plane wherever along it,
// and many tolerances off the box's front face.
TEST_F(CornerHit, AHitBesideTheOutlineIsOffTheBoxFacesPlane) {
  const vec3 towardsCamera(0.0f, 0.0f, 1.0f);
  const vec3 wallTexel = viewAt(130.5f, 90.5f, kWallZ), boxTexel = viewAt(129.5f, 90.5f, kFrontZ);
  const vec3 vsHit = viewAt(130.2f, 90.7f, kWallZ);  // on the wall, 0.3 px from the outline
  EXPECT_NEAR(sslrGapToTexelPlane(gProj, gSurf, vsHit, wallTexel, towardsCamera), 0.0f, 1e-3f);
  EXPECT_GT(sslrGapToTexelPlane(gProj, gSurf, vsHit, boxTexel, towardsCamera), 6.0f) << "40 units behind the box";
  // Off the wall by a fraction of its tolerance: that fraction (in front of it or behind).
  const float tolerance = sslrHitTolerance(gProj, gSurf, sslrViewDistance(gProj, wallTexel),
                                           sslrSlopeTan(gProj, wallTexel, towardsCamera));
  ASSERT_GT(tolerance, 0.0f);
  EXPECT_NEAR(sslrGapToTexelPlane(gProj, gSurf, vsHit + towardsCamera * (0.5f * tolerance), wallTexel, towardsCamera),
              0.5f, 1e-3f);
  EXPECT_NEAR(sslrGapToTexelPlane(gProj, gSurf, vsHit - towardsCamera * (3.0f * tolerance), wallTexel, towardsCamera),
              3.0f, 1e-3f);
  // A plane seen at a slant has a wider tolerance (its depth steps more from pixel to pixel).
  const vec3 slanted = normalize(vec3(0.9f, 0.0f, 0.3f));
  EXPECT_LT(sslrGapToTexelPlane(gProj, gSurf, wallTexel + slanted * tolerance, wallTexel, slanted), 1.0f);
}

}  // namespace

// The hit model's verdict (sslr_hit_model.h, sslrJudgePixel) at pixel (60, 90) of the box's flat
// front face (view depth 10, facing along the view axis, 70 columns from its outline), for rays that run
// parallel to it (no tangent-plane hit) at a given depth behind it: in front; behind by at most
// the hit tolerance tau (on: pixel snapping); inside the slab of 0.75 (the walk ends); deeper
// (passes behind). A measured solid (back-face depth) or a curved one's extra depth moves where
// inside ends; a ray on the reflecting pixel itself is not judged behind it. A ray that meets the
// face inside the pixel hits it there.
class HitModel : public CornerHit {
 protected:
  void SetUp() override {
    CornerHit::SetUp();
    gCoarseLevels = true;  // outline thinning looks for the outline in the levels above
  }
  static constexpr float kSlab = 0.75f;
  static SslrTraceParams modelParams() {
    SslrTraceParams t = params(kSlab);
    t.hizLevels = sslrHiZLevelCount(kWidth, kHeight);
    t.thinObjectHits = 1;
    t.maxDistance = 1e30f;
    return t;
  }
  // The verdict for a ray along +x `behind` view units behind the face at pixel px.
  static SslrVerdict verdict(float behind, float extra = 0.0f, bool hidden = false, ivec2 px = ivec2(60, 90),
                             ivec2 pxOrigin = ivec2(20, 90)) {
    const float zRay = kFrontZ - behind;
    const vec3 vsP = viewAt(20.5f, 90.5f, zRay);
    SslrCrossing c;
    c.px = px;
    c.depth = sslrLoadDepth(px);
    c.keySign = -1.0f;  // reversed Z
    c.segNear = c.segFar = -sslrDepthFromViewDepth(gProj, -zRay);
    c.extra = extra;
    c.hidden = hidden;
    return sslrJudgePixel(gProj, gSurf, modelParams(), pxOrigin, vsP, vec3(1.0f, 0.0f, 0.0f), c);
  }
  // The hit tolerance and pixel footprint at pixel (60, 90) of the face.
  static float tau() {
    vec3 vsSurface, vsN;
    EXPECT_TRUE(sslrLoadSurface(ivec2(60, 90), vsSurface));
    EXPECT_TRUE(sslrDecodeNormal(gSurf, sslrLoadNormal(ivec2(60, 90)), vsN));
    return sslrHitTolerance(gProj, gSurf, -vsSurface.z, sslrSlopeTan(gProj, vsSurface, vsN));
  }
  static float footprint() { return sslrPixelFootprint(gProj, gSurf.height, -kFrontZ); }
};

TEST_F(HitModel, TheVerdictFollowsHowDeepTheRayGoesBehindTheSurface) {
  ASSERT_LT(2.0f * tau(), kSlab) << "the cases below need the tolerance well inside the slab";
  EXPECT_EQ(verdict(-0.5f).kind, SSLR_VERDICT_IN_FRONT);
  EXPECT_EQ(verdict(0.5f * tau()).kind, SSLR_VERDICT_NEAR);
  const SslrVerdict inside = verdict(0.5f * kSlab);
  EXPECT_EQ(inside.kind, SSLR_VERDICT_INSIDE);
  EXPECT_FALSE(inside.measured);
  EXPECT_NEAR(inside.behind, 0.5f * kSlab, 1e-3f);
  EXPECT_NEAR(inside.tolerance, tau(), 1e-6f);
  EXPECT_EQ(verdict(2.0f * kSlab).kind, SSLR_VERDICT_BEHIND);
  // 70 columns from its outline the face's slab is not thinned: just inside it still holds.
  EXPECT_EQ(verdict(0.95f * kSlab).kind, SSLR_VERDICT_INSIDE);
  EXPECT_EQ(verdict(1.05f * kSlab).kind, SSLR_VERDICT_BEHIND);
}

TEST_F(HitModel, ExtraDepthMovesWhereInsideEnds) {
  // A curved solid 0.5 deeper than the slab holds a ray 1.0 behind; it is no thin object's side.
  const SslrVerdict curved = verdict(1.0f, 0.5f);
  EXPECT_EQ(curved.kind, SSLR_VERDICT_INSIDE);
  EXPECT_FALSE(curved.thinCandidate);
  // Measured (back-face depth): 0.5 thicker holds it and says it is known hidden; 0.6 thinner (a
  // solid of 0.15) lets a ray 0.4 behind pass.
  gSurf.hasBackDepth = 1;
  const SslrVerdict thick = verdict(1.0f, 0.5f);
  EXPECT_EQ(thick.kind, SSLR_VERDICT_INSIDE);
  EXPECT_TRUE(thick.measured);
  EXPECT_EQ(verdict(0.4f, -0.6f).kind, SSLR_VERDICT_BEHIND);
  EXPECT_EQ(verdict(1.0f).kind, SSLR_VERDICT_BEHIND) << "nothing measured there: the slab";
}

TEST_F(HitModel, OnlyAShallowRayThatWasInSightMayHaveMetAThinObject) {
  const float shallow = 0.5f * (tau() + SSLR_THIN_MAX_DEPTH_FOOTPRINTS * footprint());
  ASSERT_GT(shallow, tau());
  ASSERT_LT(SSLR_THIN_MAX_DEPTH_FOOTPRINTS * footprint(), kSlab);
  EXPECT_TRUE(verdict(shallow).thinCandidate);
  EXPECT_FALSE(verdict(shallow, 0.0f, true).thinCandidate) << "already out of sight: the hidden guess's";
  const SslrVerdict deep = verdict(0.5f * (SSLR_THIN_MAX_DEPTH_FOOTPRINTS * footprint() + kSlab));
  EXPECT_EQ(deep.kind, SSLR_VERDICT_INSIDE);
  EXPECT_FALSE(deep.thinCandidate);
}

TEST_F(HitModel, TheReflectingPixelIsNeverBehindItself) {
  EXPECT_EQ(verdict(0.5f * kSlab, 0.0f, false, ivec2(60, 90), ivec2(60, 90)).kind, SSLR_VERDICT_NONE);
  EXPECT_EQ(verdict(-0.5f, 0.0f, false, ivec2(60, 90), ivec2(60, 90)).kind, SSLR_VERDICT_IN_FRONT);
}

TEST_F(HitModel, ARayThatMeetsTheFaceInsideThePixelHitsIt) {
  const vec3 vsP = viewAt(20.5f, 90.5f, kFrontZ + 1.0f);
  const vec3 vsTarget = viewAt(60.5f, 90.5f, kFrontZ);
  const vec3 vsR = normalize(vsTarget - vsP);
  SslrCrossing c;
  c.px = ivec2(60, 90);
  c.depth = sslrLoadDepth(c.px);
  c.keySign = -1.0f;
  c.segNear = -sslrDepthFromViewDepth(gProj, -kFrontZ + 0.01f);
  c.segFar = -sslrDepthFromViewDepth(gProj, -kFrontZ - 0.01f);
  c.extra = 0.0f;
  c.hidden = false;
  const SslrVerdict v = sslrJudgePixel(gProj, gSurf, modelParams(), ivec2(20, 90), vsP, vsR, c);
  EXPECT_EQ(v.kind, SSLR_VERDICT_HIT);
  EXPECT_NEAR(v.L, length(vsTarget - vsP), 1e-4f * length(vsTarget - vsP));
  EXPECT_GT(v.valid, 0.99f);
}

// sslrJudgeInside for a ray that ended inside the solid at a pixel's centre (no outline crossed,
// no curved solid): a measured solid's ray is hidden from where it went in; an assumed slab's gets
// the slab guess's length there; a thin bar's (4 columns) hidden side is hit there, as a guess.
TEST_F(HitModel, InsideASolidTheAnswerIsWhereTheRayWentIn) {
  auto inside = [&](ivec2 px, float behind, SslrVerdict v) {
    const float zRay = kFrontZ - behind;
    const vec3 vsQ = viewAt(float(px.x) + 0.5f, float(px.y) + 0.5f, zRay);
    const vec3 vsR(1.0f, 0.0f, 0.0f);
    const vec3 vsP = vsQ - vsR * 2.0f;
    const vec2 size(kWidth, kHeight);
    SslrInside entered;
    entered.wEntry = sslrWindowFromView(gProj, size, -1.0f, vsQ);
    vec3 d = entered.wEntry - sslrWindowFromView(gProj, size, -1.0f, vsP);
    entered.d = d / std::max(std::abs(d.x), std::abs(d.y));
    entered.LEntry = 2.0f;
    entered.px = px;
    entered.verdict = v;
    return sslrJudgeInside(gProj, gSurf, modelParams(), vsP, vsR, sslrNoHit(SSLR_STATUS_MISS), entered);
  };
  const SslrHit slab = inside(ivec2(60, 90), 0.5f * kSlab, verdict(0.5f * kSlab));
  EXPECT_EQ(slab.status, SSLR_STATUS_MISS);
  EXPECT_EQ(slab.LSlab, 2.0f);
  gSurf.hasBackDepth = 1;
  const SslrHit measured = inside(ivec2(60, 90), 1.0f, verdict(1.0f, 0.5f));
  EXPECT_EQ(measured.status, SSLR_STATUS_HIDDEN);
  EXPECT_EQ(measured.L, 2.0f);
  gSurf.hasBackDepth = 0;
  gBarWidthPx = 4.0f;
  const float shallow = 3.0f * footprint();
  const SslrVerdict bar = verdict(shallow, 0.0f, false, ivec2(128, 90));
  ASSERT_EQ(bar.kind, SSLR_VERDICT_INSIDE);
  ASSERT_TRUE(bar.thinCandidate);
  const SslrHit met = inside(ivec2(128, 90), shallow, bar);
  EXPECT_EQ(met.status, SSLR_STATUS_HIT);
  EXPECT_EQ(met.guessed, 1);
  EXPECT_EQ(met.L, 2.0f);
}

// The walk keeps where the ray last went out of sight (tHidden) and makes it the hidden guess's
// uv and length after the walk (sslrWalkGuess). A ray from the far wall that runs left, a little
// in front of the wall and far behind the box, goes out of sight at the box's outline (x = 130)
// and leaves the screen still hidden: the guess is there. Behind a bar of 10 columns it comes out
// in front of the wall again: no guess. With the guess off, none either.
TEST_F(HitModel, TheHiddenGuessIsWhereTheRayLastWentOutOfSight) {
  SslrTraceParams t = modelParams();
  t.maxSteps = 200;
  t.hiddenGuess = 0.5f;
  const vec3 vsP = viewAt(250.5f, 90.5f, kWallZ);
  const vec3 vsR = normalize(vec3(-1.0f, 0.0f, 0.02f));
  const SslrHit hidden = sslrTraceHierarchical(gProj, gSurf, t, ivec2(250, 90), vsP, vsR);
  EXPECT_EQ(hidden.status, SSLR_STATUS_OFF_SCREEN);
  // It goes behind in the box's last column, [129, 130): its pixel's entry or centre.
  EXPECT_GE(hidden.uvGuess.x * kWidth, 129.0f);
  EXPECT_LE(hidden.uvGuess.x * kWidth, 130.0f);
  EXPECT_NEAR(hidden.uvGuess.y * kHeight, 90.5f, 0.5f);
  // Its length there lies between where the ray crosses x = 130 and x = 129 (it runs left).
  EXPECT_GE(hidden.LGuess, 0.999f * lengthAtColumn(vsP, vsR, 130.0f));
  EXPECT_LE(hidden.LGuess, 1.001f * lengthAtColumn(vsP, vsR, 129.0f));
  const SslrHit guess = sslrHiddenGuess(t, hidden);
  EXPECT_EQ(guess.status, SSLR_STATUS_HIT);
  EXPECT_EQ(guess.guessed, 1);
  EXPECT_EQ(guess.confidence, 0.5f);

  t.hiddenGuess = 0.0f;
  EXPECT_EQ(sslrTraceHierarchical(gProj, gSurf, t, ivec2(250, 90), vsP, vsR).LGuess, 0.0f) << "no guess asked for";
  t.hiddenGuess = 0.5f;
  gBarWidthPx = 10.0f;
  const SslrHit past = sslrTraceHierarchical(gProj, gSurf, t, ivec2(250, 90), vsP, vsR);
  EXPECT_EQ(past.status, SSLR_STATUS_OFF_SCREEN);
  EXPECT_EQ(past.LGuess, 0.0f) << "in front of the wall again past the bar";
}

// A ray in front of the box's face that runs nearly along the image plane (the traversal's answer
// is final for it: sslrTraversalOnly) and grazes into the face, too flat for the tangent plane's
// hit (dot(R, N) > -0.05), ends inside the face's slab. The walk alone answers it, with the
// guesses the second stage gives: the slab's colour where it went in, at the guesses' confidence.
TEST_F(HitModel, ARayTheWalkAloneAnswersGetsTheSlabGuess) {
  SslrTraceParams t = modelParams();
  t.hizMode = SSLR_HIZ_TRAVERSAL_FIRST;
  t.maxSteps = 200;
  t.hiddenGuess = 0.5f;
  const vec3 vsP = viewAt(128.5f, 90.5f, kFrontZ + 0.05f);
  const vec3 vsR = normalize(vec3(-1.0f, 0.0f, -0.045f));
  ASSERT_TRUE(sslrTraversalOnly(gProj, vsP, vsR));
  const SslrHit walked = sslrTraceHierarchical(gProj, gSurf, t, ivec2(128, 90), vsP, vsR);
  ASSERT_EQ(walked.endedInside, 1);
  ASSERT_NE(walked.status, SSLR_STATUS_HIT);
  ASSERT_GT(walked.LSlab, 0.0f);
  ASSERT_EQ(walked.LGuess, 0.0f) << "never out of sight: no hidden guess";
  bool needsTraversal = true;
  const SslrHit answer = sslrTraceFirstStage(gProj, gSurf, t, ivec2(128, 90), vsP, vsR, needsTraversal);
  EXPECT_FALSE(needsTraversal);
  EXPECT_EQ(answer.status, SSLR_STATUS_HIT);
  EXPECT_EQ(answer.guessed, 1);
  EXPECT_EQ(answer.confidence, 0.5f);
  EXPECT_FLOAT_EQ(answer.L, walked.LSlab);
}

// A ray the walk follows to the screen's edge, or out of the depth range (towards the camera),
// ends there off the screen without reading a pyramid texel past the
// screen: from next to each edge and from the middle, along the edge and across it, in front of
// the wall all the way.
TEST_F(HitModel, AWalkEndsAtTheScreensEdgeAndReadsNothingPastIt) {
  SslrTraceParams t = modelParams();
  t.maxSteps = 400;
  gBoxOnLeft = false;
  gEdgePx = 1e4f;  // the wall alone
  const vec2 starts[] = {{2.5f, 2.5f}, {317.5f, 177.5f}, {160.5f, 90.5f}, {1.5f, 120.5f}, {300.5f, 0.5f}};
  const vec3 dirs[] = {{-1.0f, 0.0f, 0.05f}, {1.0f, 0.0f, 0.05f},  {0.0f, -1.0f, 0.05f}, {0.0f, 1.0f, 0.05f},
                       {1.0f, 0.3f, 0.05f},  {-0.7f, 1.0f, 0.05f}, {0.02f, 0.01f, 1.0f}};
  for (vec2 start : starts)
    for (vec3 dir : dirs) {
      const vec3 vsP = viewAt(start.x, start.y, kWallZ);
      const SslrHit hit = sslrTraceHierarchical(gProj, gSurf, t, ivec2(floor(start)), vsP, normalize(dir));
      EXPECT_EQ(hit.status, SSLR_STATUS_OFF_SCREEN)
          << "from (" << start.x << ", " << start.y << ") along (" << dir.x << ", " << dir.y << ", " << dir.z << ")";
    }
  EXPECT_EQ(gFetchesOutside, 0);
}

// The walk's thickness test at a cell (sslrPassesBehindCell) is the view-depth bound
// distRay - distFar > max(tolerance at tan 16, slab) (+ a curved extra depth; a measured one
// inside the max), in every convention: decided right wherever the ray is 2% from the bound.
TEST(PassesBehindCell, IsTheViewDepthBound) {
  using host::DepthMode;
  for (DepthMode mode : {DepthMode::GlDefault, DepthMode::ZeroToOne, DepthMode::Reversed, DepthMode::ReversedInfinite})
    for (bool ortho : {false, true})
      for (int backDepth : {0, 1}) {
        test::SharedFrame f = test::sharedFrameFor(mode, ortho);
        f.surf.hasBackDepth = backDepth;
        f.trace.objectDepthRelative = 0.075f;
        const float keySign = f.surf.reversedZ ? -1.0f : 1.0f;
        for (float distFar : {0.3f, 2.0f, 20.0f, 100.0f})
          for (float extra : {0.0f, 0.2f * distFar, backDepth ? -0.05f * distFar : 0.01f * distFar}) {
            const float tolerance16 = sslrHitTolerance(f.proj, f.surf, distFar, 16.0f);
            const float slab = f.trace.objectDepthRelative * distFar;
            const float behind = backDepth ? std::max(tolerance16, slab + extra) : std::max(tolerance16, slab) + extra;
            const float keyFar = keySign * sslrDepthFromViewDepth(f.proj, distFar);
            auto passes = [&](float distRay) {
              const float segNear = keySign * sslrDepthFromViewDepth(f.proj, distRay);
              return sslrPassesBehindCell(f.proj, f.surf, f.trace, keySign, segNear, keyFar, extra);
            };
            const std::string where = std::string(toString(mode)) + (ortho ? " ortho" : " persp") +
                                      (backDepth ? " back depth" : "") + " distFar " + std::to_string(distFar) +
                                      " extra " + std::to_string(extra);
            EXPECT_FALSE(passes(distFar + 0.98f * behind)) << where;
            EXPECT_TRUE(passes(distFar + 1.02f * behind)) << where;
            EXPECT_FALSE(passes(0.9f * distFar)) << where << ": in front of the cell";
          }
        // Nothing lies behind a cell whose far key is background: a ray inside the key range (as
        // the walk's are) is never beyond it.
        const float background = f.surf.reversedZ ? 0.0f : 1.0f;
        EXPECT_FALSE(sslrPassesBehindCell(f.proj, f.surf, f.trace, keySign, keySign * background,
                                          keySign * background, 0.0f));
      }
}

// After a skip the walk rises a level exactly when the ray enters a new parent cell
// (sslrHiZNextLevel): checked against the parent of the cell the ray is in just past its exit,
// found in double precision, on rays in every direction (axis-aligned ones too) at levels 0-4.
// Exits within 1e-3 px of a cell's corner are left out: there rounding may decide either way.
TEST(WalkLevel, RisesExactlyWhenTheRayEntersANewParentCell) {
  const float dirs[][2] = {{1.0f, 0.37f}, {-1.0f, 0.61f}, {0.23f, -1.0f}, {-0.8f, -1.0f}, {1.0f, 0.0f},
                           {0.0f, -1.0f}, {-1.0f, 1.0f},  {1.0f, -0.999f}};
  int rises = 0, stays = 0;
  for (const auto& dir : dirs)
    for (int level = 0; level <= 4; ++level)
      for (int k = 0; k < 40; ++k) {
        SslrWalk w{};
        w.o = vec3(117.3f + 3.71f * float(k), 63.9f + 2.13f * float(k), 0.5f);
        w.d = vec3(dir[0], dir[1], 0.0f);
        w.invD = vec3(w.d.x != 0.0f ? 1.0f / w.d.x : 1e12f, w.d.y != 0.0f ? 1.0f / w.d.y : 1e12f, 0.0f);
        w.boundaryStep = vec2(w.d.x >= 0.0f ? 1.0f : 0.0f, w.d.y >= 0.0f ? 1.0f : 0.0f);
        w.level = level;
        w.topLevel = 6;
        const float size = float(1 << level), tRay = 0.77f * float(k);
        w.cell = floor(vec2(w.o.x + w.d.x * tRay, w.o.y + w.d.y * tRay) / size);
        const vec2 tBound = ((w.cell + w.boundaryStep) * size - vec2(w.o.x, w.o.y)) * vec2(w.invD.x, w.invD.y);
        w.tExit = std::min(tBound.x, tBound.y);
        if (std::abs(tBound.x - tBound.y) < 1e-3f) continue;
        w.tRay = w.tExit + SSLR_HIZ_NUDGE;
        const double tPast = double(w.tRay);
        const double nextX = std::floor((double(w.o.x) + double(w.d.x) * tPast) / size);
        const double nextY = std::floor((double(w.o.y) + double(w.d.y) * tPast) / size);
        const bool newParent = std::floor(nextX / 2.0) != std::floor(double(w.cell.x) / 2.0) ||
                               std::floor(nextY / 2.0) != std::floor(double(w.cell.y) / 2.0);
        EXPECT_EQ(sslrHiZNextLevel(w), newParent ? level + 1 : level)
            << "d (" << dir[0] << ", " << dir[1] << ") level " << level << " cell (" << w.cell.x << ", " << w.cell.y
            << ")";
        ++(newParent ? rises : stays);
        w.topLevel = level;
        EXPECT_EQ(sslrHiZNextLevel(w), level) << "at the top level the walk stays there";
      }
  EXPECT_GT(rises, 100);
  EXPECT_GT(stays, 100);
}
