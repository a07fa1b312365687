// Normal packing: octahedral 2x16 (sslr's default) and the article's xyz*0.5+0.5 in 8 bits,
// over 1M uniformly distributed directions, with the quantization the textures apply.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sslr_shared.h"

using namespace sslr::shared;

namespace {

// In double, with atan2: acos of a float dot product alone has ~0.03 deg of noise near 0.
double angleDeg(glm::vec3 a, glm::vec3 b) {
  const glm::dvec3 x(a), y(b);
  return glm::degrees(std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y)));
}

float quantize(float v, float levels) { return std::round(std::clamp(v, 0.0f, 1.0f) * levels) / levels; }

struct Stats {
  double mean = 0, max = 0;
};

template <typename Fn>
Stats measure(Fn roundTrip) {
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> g;
  const int n = 1 << 20;
  Stats s;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 d(g(rng), g(rng), g(rng));
    if (glm::length(d) < 1e-9) continue;
    const glm::vec3 v = glm::vec3(glm::normalize(d));
    const double e = angleDeg(v, roundTrip(v));
    s.mean += e / n;
    s.max = std::max(s.max, e);
  }
  return s;
}

TEST(Normals, OctahedralRg16MaxErrorBelowFourThousandthsOfADegree) {
  SslrSurface surf{};
  surf.normalEncoding = SSLR_NORMALS_OCTAHEDRAL;
  const Stats s = measure([&](glm::vec3 v) {
    const vec2 e = sslrOctEncode(v);
    vec3 n;
    EXPECT_TRUE(sslrDecodeNormal(surf, vec4(quantize(e.x, 65535.0f), quantize(e.y, 65535.0f), 0, 0), n));
    return n;
  });
  RecordProperty("mean_deg", std::to_string(s.mean));
  RecordProperty("max_deg", std::to_string(s.max));
  std::printf("octahedral RG16: mean %.5f deg, max %.5f deg over 1M directions\n", s.mean, s.max);
  // measuring.md: 0.0013 mean / 0.0037 max for 2x16; a 10% margin for the sample set.
  EXPECT_LT(s.max, 0.0041);
  EXPECT_LT(s.mean, 0.0015);
}

TEST(Normals, ArticleXyzRgb8MaxErrorBelowFourTenthsOfADegree) {
  SslrSurface surf{};
  surf.normalEncoding = SSLR_NORMALS_XYZ_UNORM;
  const Stats s = measure([&](glm::vec3 v) {
    const glm::vec3 e = v * 0.5f + 0.5f;
    vec3 n;
    EXPECT_TRUE(sslrDecodeNormal(surf, vec4(quantize(e.x, 255.0f), quantize(e.y, 255.0f), quantize(e.z, 255.0f), 0), n));
    return n;
  });
  std::printf("xyz RGB8: mean %.4f deg, max %.4f deg over 1M directions\n", s.mean, s.max);
  EXPECT_LT(s.max, 0.43);  // measuring.md: 0.387 max
  EXPECT_LT(s.mean, 0.19);
}

TEST(Normals, OctahedralIsExactWithoutQuantization) {
  for (glm::vec3 v : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0),
                      glm::normalize(glm::vec3(1, -2, -3)), glm::normalize(glm::vec3(-1, 1, 1e-4f))})
    EXPECT_LT(angleDeg(v, sslrOctDecode(sslrOctEncode(v))), 1e-3);
}

TEST(Normals, PoisonedNormalsAreRejected) {
  SslrSurface xyz{};
  xyz.normalEncoding = SSLR_NORMALS_XYZ_UNORM;
  vec3 n;
  EXPECT_FALSE(sslrDecodeNormal(xyz, vec4(0.5f, 0.5f, 0.5f, 1.0f), n)) << "zero vector";
  EXPECT_FALSE(sslrDecodeNormal(xyz, vec4(NAN, 0.5f, 1.0f, 1.0f), n)) << "NaN";
  EXPECT_FALSE(sslrDecodeNormal(xyz, vec4(1.0f, 1.0f, 1.0f, 1.0f), n)) << "length sqrt(3)";
  EXPECT_FALSE(sslrDecodeNormal(xyz, vec4(INFINITY, 0.5f, 0.5f, 1.0f), n)) << "Inf";
  SslrSurface oct{};
  oct.normalEncoding = SSLR_NORMALS_OCTAHEDRAL;
  // Octahedral decodes every finite pair to a unit vector; out-of-range values are clamped.
  EXPECT_TRUE(sslrDecodeNormal(oct, vec4(7.0f, -3.0f, 0, 0), n));
  EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  EXPECT_FALSE(sslrDecodeNormal(oct, vec4(NAN, 0.5f, 0, 0), n));
}

// The signed unpack (SurfaceLayout::normalScale 1, normalBias 0) decodes a signed value to the
// normal the unsigned default decodes from (value + 1) / 2, for both encodings; a surface whose
// unpack is not set unpacks as unsigned.
TEST(Normals, SignedUnpackMatchesTheUnsignedOne) {
  for (int encoding : {SSLR_NORMALS_OCTAHEDRAL, SSLR_NORMALS_XYZ_UNORM}) {
    SslrSurface unsignedSurface{}, signedSurface{}, unset{};
    unsignedSurface.normalEncoding = signedSurface.normalEncoding = unset.normalEncoding = encoding;
    unsignedSurface.normalScale = 2.0f;
    unsignedSurface.normalBias = -1.0f;
    signedSurface.normalScale = 1.0f;
    signedSurface.normalBias = 0.0f;
    for (glm::vec3 v : {glm::vec3(0, 0, 1), glm::vec3(0, -1, 0), glm::normalize(glm::vec3(1, -2, -3)),
                        glm::normalize(glm::vec3(-0.3f, 0.7f, 0.2f))}) {
      const vec4 stored = encoding == SSLR_NORMALS_OCTAHEDRAL ? vec4(sslrOctEncode(v), 0.0f, 0.0f)
                                                              : vec4(v * 0.5f + 0.5f, 0.0f);
      const vec4 signedStored = vec4(vec3(stored) * 2.0f - 1.0f, 0.0f);
      vec3 a, b, c;
      ASSERT_TRUE(sslrDecodeNormal(unsignedSurface, stored, a));
      ASSERT_TRUE(sslrDecodeNormal(signedSurface, signedStored, b));
      ASSERT_TRUE(sslrDecodeNormal(unset, stored, c));
      EXPECT_LT(angleDeg(a, v), 1e-3);
      EXPECT_LT(angleDeg(b, v), 1e-3);
      EXPECT_EQ(a, c) << "unset is the unsigned default, bit for bit";
    }
    vec3 n;
    EXPECT_FALSE(signedSurface.normalEncoding == SSLR_NORMALS_XYZ_UNORM &&
                 sslrDecodeNormal(signedSurface, vec4(0.0f, 0.0f, 0.0f, 0.0f), n))
        << "a zero signed vector is no normal";
  }
}

// Classification lists tiles by sslrTraceCandidate (no normal decode); the trace asks
// sslrShouldTrace of each pixel. No pixel the trace would trace may be missed by classification,
// and the two agree wherever the normal decodes: over every depth, material and normal class,
// both depth directions and both encodings.
TEST(TraceTest, ClassificationListsEveryPixelTheTraceTraces) {
  SslrTraceParams t{};
  t.minReflectance = 0.02f;
  t.roughnessCutoff = 0.6f;
  const float depths[] = {0.0f, 1e-7f, 0.3f, 1.0f - 1e-7f, 1.0f, -0.1f, 1.5f, NAN, INFINITY};
  const float materials[] = {0.0f, 0.02f, 0.021f, 0.5f, 0.6f, 0.61f, 1.0f, NAN, -INFINITY};
  const vec4 normals[] = {vec4(0.5f, 0.5f, 1.0f, 0.0f), vec4(0.2f, 0.9f, 0.7f, 0.0f), vec4(NAN, 0.5f, 0.5f, 0.0f),
                          vec4(0.5f, 0.5f, 0.5f, 0.0f), vec4(INFINITY, 0.0f, 0.0f, 0.0f)};
  int traced = 0, candidates = 0;
  for (int encoding : {SSLR_NORMALS_OCTAHEDRAL, SSLR_NORMALS_XYZ_UNORM})
    for (int reversed : {0, 1}) {
      SslrSurface s{};
      s.normalEncoding = encoding;
      s.reversedZ = reversed;
      s.roughnessChannel = 2;
      s.reflectanceChannel = 3;
      for (float depth : depths)
        for (float reflectance : materials)
          for (float roughness : materials)
            for (vec4 n : normals) {
              const vec4 texel(n.x, n.y, roughness, reflectance);
              const bool candidate = sslrTraceCandidate(s, t, depth, reflectance, roughness);
              const bool trace = sslrShouldTrace(s, t, depth, texel, texel);
              vec3 decoded;
              const bool decodes = sslrDecodeNormal(s, texel, decoded);
              ASSERT_EQ(trace, candidate && decodes)
                  << "depth " << depth << " reflectance " << reflectance << " roughness " << roughness;
              traced += trace;
              candidates += candidate;
            }
    }
  // Both outcomes occur (the loops are not vacuous) and poisoned normals make them differ.
  EXPECT_GT(traced, 0);
  EXPECT_GT(candidates, traced);
}

}  // namespace
