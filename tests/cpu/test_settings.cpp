// Settings: presets are valid and ordered by effort; every invalid field is named.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "sslr/sslr.hpp"

using namespace sslr;

TEST(Settings, DefaultsAndPresetsAreValid) {
  EXPECT_EQ(validate(Settings{}), "");
  for (Preset p : {Preset::Low, Preset::Medium, Preset::High, Preset::Ultra}) EXPECT_EQ(validate(Settings::preset(p)), "");
}

// Each preset spends at least what the one below spends on every knob, and more on some: low is
// adaptive L alone; medium adds the traversal (capped at 96 steps) with high's adaptive L, since
// fewer iterations only send more pixels to the traversal (docs/algorithm.md, "Presets").
TEST(Settings, PresetsGrowInEffort) {
  const Settings low = Settings::preset(Preset::Low), med = Settings::preset(Preset::Medium),
                 high = Settings::preset(Preset::High), ultra = Settings::preset(Preset::Ultra);
  EXPECT_FALSE(low.hierarchicalFallback);
  EXPECT_TRUE(med.hierarchicalFallback && high.hierarchicalFallback && ultra.hierarchicalFallback);
  EXPECT_FALSE(low.hierarchicalVerify || med.hierarchicalVerify);
  EXPECT_TRUE(high.hierarchicalVerify);
  EXPECT_TRUE(ultra.hierarchicalVerify);
  EXPECT_LT(low.maxIterations, med.maxIterations);
  EXPECT_LE(med.maxIterations, high.maxIterations);
  EXPECT_LT(high.maxIterations, ultra.maxIterations);
  EXPECT_GE(low.convergenceEps, med.convergenceEps);
  EXPECT_GE(med.convergenceEps, high.convergenceEps);
  EXPECT_GT(high.convergenceEps, ultra.convergenceEps);
  EXPECT_LT(med.hierarchicalMaxSteps, high.hierarchicalMaxSteps);
  EXPECT_LT(high.hierarchicalMaxSteps, ultra.hierarchicalMaxSteps);
  for (auto [lower, upper] : {std::pair{low, med}, std::pair{med, high}, std::pair{high, ultra}}) {
    EXPECT_LT(lower.blurMaxRadiusPx, upper.blurMaxRadiusPx);
    EXPECT_LT(lower.roughnessCutoff, upper.roughnessCutoff);
  }
}

TEST(Settings, EveryInvalidFieldIsNamed) {
  struct Bad {
    const char* field;
    void (*apply)(Settings&);
  };
  const Bad cases[] = {
      {"maxIterations", [](Settings& s) { s.maxIterations = 0; }},
      {"maxIterations", [](Settings& s) { s.maxIterations = 100000; }},
      {"hierarchicalVerify", [](Settings& s) { s.hierarchicalVerify = true; s.hierarchicalFallback = false; }},
      {"hiddenPassageLimitPx", [](Settings& s) { s.hiddenPassageLimitPx = -1.0f; }},
      {"ffx.depthBufferThickness", [](Settings& s) { s.ffx.depthBufferThickness = 0.0f; }},
      {"ffx.maxTraversalIntersections", [](Settings& s) { s.ffx.maxTraversalIntersections = 0; }},
      {"hiddenPassageLimitPx", [](Settings& s) { s.hiddenPassageLimitPx = NAN; }},
      {"traversalPass", [](Settings& s) { s.traversalPass = static_cast<TraversalPass>(7); }},
      {"convergenceEps", [](Settings& s) { s.convergenceEps = -1.0f; }},
      {"initialLengthScreen", [](Settings& s) { s.initialLengthScreen = 0.0f; }},
      {"initialLengthScreen", [](Settings& s) { s.initialLengthScreen = 2.0f; }},
      {"errorK", [](Settings& s) { s.errorK = NAN; }},
      {"maxDistance", [](Settings& s) { s.maxDistance = 0.0f; }},
      {"maxDistance", [](Settings& s) { s.maxDistance = NAN; }},
      {"thicknessRelative", [](Settings& s) { s.thicknessRelative = -0.1f; }},
      {"thicknessPixels", [](Settings& s) { s.thicknessPixels = INFINITY; }},
      {"both 0", [](Settings& s) { s.thicknessPixels = 0.0f; s.thicknessRelative = 0.0f; }},
      {"edgeFade", [](Settings& s) { s.edgeFade = 0.7f; }},
      {"cameraFadeStart", [](Settings& s) { s.cameraFadeStart = 0.9f; s.cameraFadeEnd = 0.1f; }},
      {"roughnessCutoff", [](Settings& s) { s.roughnessCutoff = NAN; }},
      {"roughnessCutoff", [](Settings& s) { s.roughnessCutoff = -0.1f; }},
      {"roughnessCutoff", [](Settings& s) { s.roughnessCutoff = 1.5f; }},
      {"minReflectance", [](Settings& s) { s.minReflectance = INFINITY; }},
      {"blurMaxRadiusPx", [](Settings& s) { s.blurMaxRadiusPx = 100.0f; }},
      {"blurConeScale", [](Settings& s) { s.blurConeScale = -1.0f; }},
      {"blurDepthSigma", [](Settings& s) { s.blurDepthSigma = 0.0f; }},
      {"blurNormalPower", [](Settings& s) { s.blurNormalPower = NAN; }},
  };
  for (const Bad& b : cases) {
    Settings s;
    b.apply(s);
    const std::string why = validate(s);
    EXPECT_NE(why.find(b.field), std::string::npos) << b.field << " -> '" << why << "'";
  }
}

// Expected's operator-> reaches a value's members, and through a pointer-like value its pointee's
// (what `ctx->dispatch(...)` on Context::create's result needs); operator* is the value.
TEST(ExpectedAccess, ArrowReachesTheValueOrThePointee) {
  sslr::Expected<std::string> text(std::string("abc"));
  EXPECT_EQ(text->size(), 3u);
  EXPECT_EQ(*text, "abc");
  sslr::Expected<std::unique_ptr<std::string>> pointer(std::make_unique<std::string>("hello"));
  EXPECT_EQ(pointer->size(), 5u) << "through the unique_ptr to the string";
  const auto& constPointer = pointer;
  EXPECT_EQ(constPointer->size(), 5u);
  sslr::Expected<std::string> failed(sslr::Status::error("no"));
  EXPECT_FALSE(failed);
  EXPECT_EQ(failed.error(), "no");
}

// The version macros come from CMake's project() line, and the library reports the same.
TEST(Version, MacrosAndLibraryAgree) {
  const std::string fromMacros = std::to_string(SSLR_VERSION_MAJOR) + "." + std::to_string(SSLR_VERSION_MINOR) + "." +
                                 std::to_string(SSLR_VERSION_PATCH);
  EXPECT_EQ(fromMacros, SSLR_VERSION_STRING);
  EXPECT_EQ(std::string(sslr::libraryVersion()), SSLR_VERSION_STRING);
}
