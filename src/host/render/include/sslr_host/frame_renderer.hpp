// One frame of the tools' pipeline: G-buffer -> sslr dispatch -> composite into a final image.
// This is the integration a host renderer does, written once for sslr-render, tests and bench.
#pragma once

#include <memory>

#include "sslr/sslr.hpp"
#include "sslr_host/gbuffer.hpp"

namespace sslr::host {

class FrameRenderer {
 public:
  // `getProcAddress`: the current context's (default: the headless EGL context's); `shapes`:
  // sslr's pass shapes (ContextDesc's device, traversalPass, oneBodyTraversal and occupancyExit; its size,
  // loader and views are set here).
  static Expected<std::unique_ptr<FrameRenderer>> create(const GBufferOptions& options,
                                                         GetProcAddress getProcAddress = nullptr,
                                                         const ContextDesc& shapes = {});
  ~FrameRenderer();

  // Rasterizes the G-buffer; with `settings` also traces and composites (else final = colour).
  // FrameInputs::previousClipFromView comes from the previous render (temporal reuse).
  Status render(const GpuScene& scene, const Camera& camera, const Settings* settings,
                glm::dvec2 jitterPx = {0.0, 0.0});

  // Rasterizes the G-buffer, then sslr's prepare() on the inputs render() hands it: every program
  // compiled and run once, as an engine does at load time.
  Status prepare(const GpuScene& scene, const Camera& camera, const Settings& settings);
  // final = the G-buffer's colour with `ctx`'s last dispatch composited (the renderer's composite
  // mode): for a context other than the renderer's own, over the same G-buffer.
  Status compositeFrom(Context& ctx);
  // How the reflection enters the final image (default: over the G-buffer pass's fallback specular).
  void setCompositeMode(CompositeMode mode) { compositeMode_ = mode; }
  CompositeMode compositeMode() const { return compositeMode_; }

  GBuffer& gbuffer() { return *gbuffer_; }
  // What the last render handed (or, without settings, would have handed) to sslr's dispatch.
  const FrameInputs& inputs() const { return inputs_; }
  Context& sslr() { return *sslr_; }
  GLuint finalTexture() const { return final_; }
  Image readFinal() const;                  // RGB, linear
  Image readReflection() const;             // RGBA16F as RGBA float
  Image readResolved() const;
  Image readHit() const;                    // needs Settings::debug.outputs
  Image readIterations() const;             // needs Settings::debug.outputs

 private:
  FrameRenderer() = default;
  std::unique_ptr<GBuffer> gbuffer_;
  std::unique_ptr<Context> sslr_;
  void copyColorToFinal();
  GLuint final_ = 0, finalFbo_ = 0;
  CompositeMode compositeMode_ = CompositeMode::BlendOverFallback;
  glm::dmat4 previousClipFromWorld_{0.0};  // the last render's, for temporal reuse
  FrameInputs inputs_;
};

}  // namespace sslr::host
