#include "sslr_host/frame_renderer.hpp"

#include "sslr_host/egl_context.hpp"

namespace sslr::host {

Expected<std::unique_ptr<FrameRenderer>> FrameRenderer::create(const GBufferOptions& options,
                                                              GetProcAddress getProcAddress, const ContextDesc& shapes) {
  auto gbuffer = GBuffer::create(options);
  if (!gbuffer) return Status::error(gbuffer.error());
  auto r = std::unique_ptr<FrameRenderer>(new FrameRenderer());
  r->gbuffer_ = std::move(gbuffer.value());
  ContextDesc desc = shapes;
  desc.width = options.width;
  desc.height = options.height;
  desc.views = 1;
  desc.getProcAddress = getProcAddress != nullptr ? getProcAddress : HeadlessContext::getProcAddress();
  auto ctx = Context::create(desc);
  if (!ctx) return Status::error(ctx.error());
  r->sslr_ = std::move(ctx.value());
  glCreateTextures(GL_TEXTURE_2D, 1, &r->final_);
  glTextureStorage2D(r->final_, 1, GL_RGBA16F, options.width, options.height);
  glObjectLabel(GL_TEXTURE, r->final_, -1, "host.final");
  glCreateFramebuffers(1, &r->finalFbo_);
  glNamedFramebufferTexture(r->finalFbo_, GL_COLOR_ATTACHMENT0, r->final_, 0);
  return r;
}

FrameRenderer::~FrameRenderer() {
  glDeleteFramebuffers(1, &finalFbo_);
  glDeleteTextures(1, &final_);
}

Status FrameRenderer::render(const GpuScene& scene, const Camera& camera, const Settings* settings,
                             glm::dvec2 jitterPx) {
  if (Status s = gbuffer_->render(scene, camera, jitterPx); !s) return s;
  // The previous frame's matrices, as a host keeps them for temporal reuse (the first frame has
  // none: its own stand in, and sslr has no history then anyway).
  FrameInputs& inputs = inputs_;
  inputs = gbuffer_->frameInputs();
  const glm::dmat4 clipFromWorld = gbuffer_->clipFromView() * gbuffer_->viewFromWorld();
  inputs.previousClipFromView = previousClipFromWorld_ == glm::dmat4(0.0)
                                    ? gbuffer_->clipFromView()
                                    : previousClipFromWorld_ * glm::inverse(gbuffer_->viewFromWorld());
  previousClipFromWorld_ = clipFromWorld;
  if (settings == nullptr) {
    copyColorToFinal();
    return {};
  }
  if (Status s = sslr_->dispatch(inputs, *settings); !s) return s;
  return compositeFrom(*sslr_);
}

void FrameRenderer::copyColorToFinal() {
  const int w = gbuffer_->width(), h = gbuffer_->height();
  glNamedFramebufferReadBuffer(gbuffer_->framebuffer(), GL_COLOR_ATTACHMENT0);
  glBlitNamedFramebuffer(gbuffer_->framebuffer(), finalFbo_, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT,
                         GL_NEAREST);
}

// final = lit colour (which includes the fallback specular), then sslr's reflection replaces the
// fallback where it has coverage (BlendOverFallback), or is added on top (Add).
Status FrameRenderer::compositeFrom(Context& ctx) {
  copyColorToFinal();
  CompositeOptions composite;
  composite.mode = compositeMode_;
  if (compositeMode_ == CompositeMode::BlendOverFallback)
    composite.fallbackSpecularTexture = gbuffer_->fallbackSpecularTexture();
  return ctx.composite(finalFbo_, composite);
}

Status FrameRenderer::prepare(const GpuScene& scene, const Camera& camera, const Settings& settings) {
  if (Status s = gbuffer_->render(scene, camera); !s) return s;
  FrameInputs inputs = gbuffer_->frameInputs();
  inputs.previousClipFromView = inputs.clipFromView;
  PrepareOptions options;
  options.composite = settings.output == OutputMode::Weighted;
  options.framebuffer = finalFbo_;
  options.compositeOptions.mode = compositeMode_;
  if (compositeMode_ == CompositeMode::BlendOverFallback)
    options.compositeOptions.fallbackSpecularTexture = gbuffer_->fallbackSpecularTexture();
  return sslr_->prepare(inputs, settings, options);
}

Image FrameRenderer::readFinal() const { return readTexture(final_, gbuffer_->width(), gbuffer_->height(), 3); }
Image FrameRenderer::readReflection() const {
  return readTexture(sslr_->reflectionTexture(), gbuffer_->width(), gbuffer_->height(), 4);
}
Image FrameRenderer::readResolved() const {
  return readTexture(sslr_->resolvedTexture(), gbuffer_->width(), gbuffer_->height(), 4);
}
Image FrameRenderer::readHit() const {
  return readTexture(sslr_->hitTexture(), gbuffer_->width(), gbuffer_->height(), 4);
}
Image FrameRenderer::readIterations() const {
  return readTexture(sslr_->iterationsTexture(), gbuffer_->width(), gbuffer_->height(), 1);
}

}  // namespace sslr::host
