// sslr/compare.hpp - the parameters of the methods sslr is measured against (Method::
// PositionBuffer, ScreenSpaceDDA, FidelityFxSssr), for sslr-bench, sslr-render and anyone who wants
// the comparison on their own G-buffers. An engine using sslr's method needs none of this:
// sslr.hpp includes it only because Settings holds one of each.
#pragma once

namespace sslr {

// Parameters of Method::PositionBuffer, with the tutorial's demo values.
struct PositionBufferSettings {
  float maxDistance = 8.0f;  // ray length, view units
  float resolution = 0.3f;   // fraction of pixels the coarse march visits (0..1]
  int steps = 5;             // binary refinement steps
  float hitTolerance = 0.5f; // view units: a ray point this close behind the stored position hits
};

// Parameters of Method::ScreenSpaceDDA (McGuire & Mara 2014, JCGT 3(4)).
struct DdaSettings {
  float stride = 2.0f;           // pixels per step (>= 1)
  float objectDepth = 0.5f;      // view units: depth assumed behind every visible surface (the paper's zThickness)
  float maxDistance = 1.0e30f;   // ray length, view units (capped at 1e4 x the origin's distance)
  int maxSteps = 256;            // depth fetches per ray at most, refinement not counted
  bool jitter = true;            // checkerboard offset of half a stride (stride > 1)
  bool refine = true;            // re-march the stride of a hit one pixel at a time (stride > 1)
};

// Parameters of Method::FidelityFxSssr, with FFX SSSR's sample defaults.
struct FfxSssrSettings {
  float depthBufferThickness = 0.015f;  // view units: confidence (1 - smoothstep(0, this, d))^2
  int maxTraversalIntersections = 128;  // steps of the hierarchical raymarch at most
};

}  // namespace sslr
