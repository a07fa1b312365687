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
// adaptive L alone; medium adds the traversal (capped at 24 steps) with high's adaptive L, since
// fewer iterations only send more pixels to the traversal (docs/design-notes.md, "Presets").
// Ultra is high's tracer (more steps and iterations measured no lower image error). All but high,
// which keeps the article's look, go without the error fade and with a narrower border fade (the
// fades measured only a higher image error).
TEST(Settings, PresetsGrowInEffort) {
  const Settings low = Settings::preset(Preset::Low), med = Settings::preset(Preset::Medium),
                 high = Settings::preset(Preset::High), ultra = Settings::preset(Preset::Ultra);
  EXPECT_EQ(low.traversal.maxSteps, 0) << "adaptive L alone";
  EXPECT_GT(med.traversal.maxSteps, 0);
  EXPECT_LT(low.adaptiveL.maxIterations, med.adaptiveL.maxIterations);
  EXPECT_LE(med.adaptiveL.maxIterations, high.adaptiveL.maxIterations);
  EXPECT_EQ(high.adaptiveL.maxIterations, ultra.adaptiveL.maxIterations);
  EXPECT_GE(low.adaptiveL.convergenceEps, med.adaptiveL.convergenceEps);
  EXPECT_GE(med.adaptiveL.convergenceEps, high.adaptiveL.convergenceEps);
  EXPECT_EQ(high.adaptiveL.convergenceEps, ultra.adaptiveL.convergenceEps);
  EXPECT_LT(med.traversal.maxSteps, high.traversal.maxSteps);
  EXPECT_EQ(high.traversal.maxSteps, ultra.traversal.maxSteps);
  EXPECT_GT(high.fades.errorK, 0.0f) << "the article's error fade";
  for (const Settings& s : {low, med, ultra}) {
    EXPECT_EQ(s.fades.errorK, 0.0f);
    EXPECT_LT(s.fades.screenEdge, high.fades.screenEdge);
    EXPECT_GT(s.fades.screenEdge, 0.0f) << "a soft border, not a cut";
  }
  for (auto [lower, upper] : {std::pair{low, med}, std::pair{med, high}, std::pair{high, ultra}}) {
    EXPECT_LT(lower.blur.maxRadiusPx, upper.blur.maxRadiusPx);
    EXPECT_LT(lower.selection.roughnessCutoff, upper.selection.roughnessCutoff);
  }
}

TEST(Settings, EveryInvalidFieldIsNamed) {
  struct Bad {
    const char* field;
    void (*apply)(Settings&);
  };
  const Bad cases[] = {
      {"adaptiveL.maxIterations", [](Settings& s) { s.adaptiveL.maxIterations = 0; }},
      {"adaptiveL.maxIterations", [](Settings& s) { s.adaptiveL.maxIterations = 100000; }},
      {"traversal.hiddenGuess", [](Settings& s) { s.traversal.hiddenGuess = 1.5f; }},
      {"traversal.hiddenGuess", [](Settings& s) { s.traversal.hiddenGuess = NAN; }},
      {"ffx.depthBufferThickness", [](Settings& s) { s.ffx.depthBufferThickness = 0.0f; }},
      {"ffx.maxTraversalIntersections", [](Settings& s) { s.ffx.maxTraversalIntersections = 0; }},
      {"traversal.maxSteps", [](Settings& s) { s.traversal.maxSteps = -1; }},
      {"traversal.maxSteps", [](Settings& s) { s.traversal.maxSteps = 1025; }},
      {"traversal.maxSteps = 0 (must be 1..1024 for Method::HierarchicalDepth)",
       [](Settings& s) { s.method = Method::HierarchicalDepth; s.traversal.maxSteps = 0; }},
      {"output", [](Settings& s) { s.output = static_cast<OutputMode>(7); }},
      {"adaptiveL.convergenceEps", [](Settings& s) { s.adaptiveL.convergenceEps = -1.0f; }},
      {"adaptiveL.initialLengthScreen", [](Settings& s) { s.adaptiveL.initialLengthScreen = 0.0f; }},
      {"adaptiveL.initialLengthScreen", [](Settings& s) { s.adaptiveL.initialLengthScreen = 2.0f; }},
      {"fades.errorK", [](Settings& s) { s.fades.errorK = NAN; }},
      {"fades.maxDistance", [](Settings& s) { s.fades.maxDistance = 0.0f; }},
      {"fades.maxDistance", [](Settings& s) { s.fades.maxDistance = NAN; }},
      {"fades.screenEdge", [](Settings& s) { s.fades.screenEdge = 0.7f; }},
      {"fades.cameraStart", [](Settings& s) { s.fades.cameraStart = 0.9f; s.fades.cameraEnd = 0.1f; }},
      {"selection.roughnessCutoff", [](Settings& s) { s.selection.roughnessCutoff = NAN; }},
      {"selection.roughnessCutoff", [](Settings& s) { s.selection.roughnessCutoff = -0.1f; }},
      {"selection.roughnessCutoff", [](Settings& s) { s.selection.roughnessCutoff = 1.5f; }},
      {"selection.minReflectance", [](Settings& s) { s.selection.minReflectance = INFINITY; }},
      {"blur.maxRadiusPx", [](Settings& s) { s.blur.maxRadiusPx = 100.0f; }},
      {"blur.coneScale", [](Settings& s) { s.blur.coneScale = -1.0f; }},
      {"blur.depthSigma", [](Settings& s) { s.blur.depthSigma = 0.0f; }},
      {"blur.normalPower", [](Settings& s) { s.blur.normalPower = NAN; }},
      {"glossy.mode", [](Settings& s) { s.glossy.mode = static_cast<GlossyMode>(9); }},
      {"fresnel = 9 (not a sslr::FresnelMode)", [](Settings& s) { s.fresnel = static_cast<FresnelMode>(9); }},
      {"glossy.stochasticFrom", [](Settings& s) { s.glossy.stochasticFrom = 1.5f; }},
      {"glossy.stochasticFrom", [](Settings& s) { s.glossy.stochasticFrom = NAN; }},
      {"glossy.mode Stochastic", [](Settings& s) { s.glossy.mode = GlossyMode::Stochastic; s.halfResolution = true; }},
      {"temporal.outputConfidence needs temporal.enabled", [](Settings& s) { s.temporal.outputConfidence = true; }},
      {"radianceClamp.maxLuminance", [](Settings& s) { s.radianceClamp.maxLuminance = -1.0f; }},
      {"radianceClamp.maxLuminance", [](Settings& s) { s.radianceClamp.maxLuminance = NAN; }},
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
