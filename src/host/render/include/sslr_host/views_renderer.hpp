// The tools' pipeline for several views (ContextDesc::views): each view's G-buffer -> the layers
// of 2D-array inputs -> one sslr dispatch for every view -> each view's composite into its own
// final image. A host renders its views straight into the array layers; the tools copy their
// per-view G-buffers in (glCopyImageSubData), which sslr's timings do not include.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "sslr/sslr.hpp"
#include "sslr_host/gbuffer.hpp"

namespace sslr::host {

// `views` cameras side by side: the camera moved along its right axis, `separation` view units
// apart, centred on it (two eyes: -separation / 2 and +separation / 2).
std::vector<Camera> sideBySideCameras(const Camera& camera, int views, double separation);

class ViewsRenderer {
 public:
  // `views`: 2..kMaxViews (one view is FrameRenderer's); `shapes`: sslr's pass shapes, as
  // FrameRenderer::create takes them.
  static Expected<std::unique_ptr<ViewsRenderer>> create(const GBufferOptions& options, int views,
                                                         GetProcAddress getProcAddress = nullptr,
                                                         const ContextDesc& shapes = {});
  ~ViewsRenderer();
  ViewsRenderer(const ViewsRenderer&) = delete;
  ViewsRenderer& operator=(const ViewsRenderer&) = delete;

  // Each camera's G-buffer, copied into the layers; with `settings` one dispatch traces every view
  // and each composites into its final image (else final = colour). cameras.size() == views().
  Status render(const GpuScene& scene, std::span<const Camera> cameras, const Settings* settings);
  // The G-buffers rasterized and copied, then sslr's prepare() on the layered inputs.
  Status prepare(const GpuScene& scene, std::span<const Camera> cameras, const Settings& settings);

  int views() const { return static_cast<int>(eyes_.size()); }
  GBuffer& gbuffer(int view) { return *eyes_[static_cast<size_t>(view)]; }
  // View v's FrameInputs naming its own 2D textures (what a one-view context would be given).
  FrameInputs viewInputs(int view) const;
  // What the last render handed sslr: every view's FrameInputs over the 2D arrays.
  std::span<const FrameInputs> layeredInputs() const { return layered_; }
  Context& sslr() { return *sslr_; }
  // How each view's reflection enters its final image (default: over its fallback specular).
  void setCompositeMode(CompositeMode mode) { compositeMode_ = mode; }
  GLuint finalTexture(int view) const { return finals_[static_cast<size_t>(view)]; }  // RGBA16F
  Image readFinal(int view) const;  // RGB, linear

 private:
  ViewsRenderer() = default;
  Status rasterize(const GpuScene& scene, std::span<const Camera> cameras);
  std::vector<std::unique_ptr<GBuffer>> eyes_;
  std::vector<GLuint> arrays_;  // one per input the G-buffers have
  std::vector<FrameInputs> layered_;
  std::vector<glm::dmat4> previousClipFromWorld_;
  std::unique_ptr<Context> sslr_;
  std::vector<GLuint> finals_, finalFbos_;
  CompositeMode compositeMode_ = CompositeMode::BlendOverFallback;
};

}  // namespace sslr::host
