// The tools' pipeline for several views (views_renderer.hpp).
#include "sslr_host/views_renderer.hpp"

#include <glm/glm.hpp>

#include "sslr_host/egl_context.hpp"

namespace sslr::host {

namespace {
// The inputs a G-buffer may hand sslr, each copied into an array of its own.
constexpr GLName FrameInputs::*kLayeredMembers[] = {&FrameInputs::colorTexture, &FrameInputs::normalTexture,
                                                    &FrameInputs::depthTexture, &FrameInputs::positionTexture,
                                                    &FrameInputs::backDepthTexture};
}  // namespace

std::vector<Camera> sideBySideCameras(const Camera& camera, int views, double separation) {
  const glm::dvec3 right = glm::normalize(glm::cross(camera.target - camera.eye, camera.up));
  std::vector<Camera> out;
  for (int v = 0; v < views; ++v) {
    const glm::dvec3 shift = right * (separation * (v - 0.5 * (views - 1)));
    Camera c = camera;
    c.eye += shift;
    c.target += shift;
    out.push_back(c);
  }
  return out;
}

Expected<std::unique_ptr<ViewsRenderer>> ViewsRenderer::create(const GBufferOptions& options, int views,
                                                              GetProcAddress getProcAddress, const ContextDesc& shapes) {
  if (views < 2 || views > kMaxViews)  // (one view: FrameRenderer, whose context reads 2D textures)
    return Status::error("views = " + std::to_string(views) + " (must be 2.." + std::to_string(kMaxViews) + ")");
  auto r = std::unique_ptr<ViewsRenderer>(new ViewsRenderer());
  for (int v = 0; v < views; ++v) {
    auto g = GBuffer::create(options);
    if (!g) return Status::error(g.error());
    r->eyes_.push_back(std::move(g.value()));
  }
  const FrameInputs first = r->eyes_[0]->frameInputs();
  for (const auto member : kLayeredMembers) {
    if (first.*member == 0) continue;
    GLint format = 0;
    glGetTextureLevelParameteriv(first.*member, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    GLuint array = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &array);
    glTextureStorage3D(array, 1, static_cast<GLenum>(format), options.width, options.height, views);
    glObjectLabel(GL_TEXTURE, array, -1, "host.layeredInput");
    r->arrays_.push_back(array);
  }
  ContextDesc desc = shapes;
  desc.width = options.width;
  desc.height = options.height;
  desc.views = views;
  desc.getProcAddress = getProcAddress != nullptr ? getProcAddress : HeadlessContext::getProcAddress();
  auto ctx = Context::create(desc);
  if (!ctx) return Status::error(ctx.error());
  r->sslr_ = std::move(ctx.value());
  r->finals_.resize(static_cast<size_t>(views));
  r->finalFbos_.resize(static_cast<size_t>(views));
  glCreateTextures(GL_TEXTURE_2D, views, r->finals_.data());
  glCreateFramebuffers(views, r->finalFbos_.data());
  for (int v = 0; v < views; ++v) {
    glTextureStorage2D(r->finals_[v], 1, GL_RGBA16F, options.width, options.height);
    glNamedFramebufferTexture(r->finalFbos_[v], GL_COLOR_ATTACHMENT0, r->finals_[v], 0);
  }
  r->previousClipFromWorld_.assign(static_cast<size_t>(views), glm::dmat4(0.0));
  return r;
}

ViewsRenderer::~ViewsRenderer() {
  glDeleteFramebuffers(static_cast<GLsizei>(finalFbos_.size()), finalFbos_.data());
  glDeleteTextures(static_cast<GLsizei>(finals_.size()), finals_.data());
  glDeleteTextures(static_cast<GLsizei>(arrays_.size()), arrays_.data());
}

FrameInputs ViewsRenderer::viewInputs(int view) const {
  return eyes_[static_cast<size_t>(view)]->frameInputs();
}

// Each view's G-buffer, its layer of every array, and the layered FrameInputs with each view's
// matrices (the previous ones from the last render, for temporal reuse).
Status ViewsRenderer::rasterize(const GpuScene& scene, std::span<const Camera> cameras) {
  if (static_cast<int>(cameras.size()) != views())
    return Status::error(std::to_string(cameras.size()) + " cameras for " + std::to_string(views()) + " views");
  layered_.clear();
  for (int v = 0; v < views(); ++v) {
    GBuffer& g = *eyes_[static_cast<size_t>(v)];
    if (Status s = g.render(scene, cameras[static_cast<size_t>(v)]); !s) return s;
    FrameInputs in = viewInputs(v);
    size_t array = 0;
    for (const auto member : kLayeredMembers) {
      if (in.*member == 0) continue;
      glCopyImageSubData(in.*member, GL_TEXTURE_2D, 0, 0, 0, 0, arrays_[array], GL_TEXTURE_2D_ARRAY, 0, 0, 0, v,
                         g.width(), g.height(), 1);
      in.*member = arrays_[array++];
    }
    glm::dmat4& previous = previousClipFromWorld_[static_cast<size_t>(v)];
    in.previousClipFromView =
        previous == glm::dmat4(0.0) ? in.clipFromView : previous * glm::inverse(g.viewFromWorld());
    previous = g.clipFromView() * g.viewFromWorld();
    layered_.push_back(in);
  }
  return {};
}

Status ViewsRenderer::render(const GpuScene& scene, std::span<const Camera> cameras, const Settings* settings) {
  if (Status s = rasterize(scene, cameras); !s) return s;
  if (settings != nullptr)
    if (Status s = sslr_->dispatch(layeredInputs(), *settings); !s) return s;
  for (int v = 0; v < views(); ++v) {
    GBuffer& g = *eyes_[static_cast<size_t>(v)];
    glNamedFramebufferReadBuffer(g.framebuffer(), GL_COLOR_ATTACHMENT0);
    glBlitNamedFramebuffer(g.framebuffer(), finalFbos_[v], 0, 0, g.width(), g.height(), 0, 0, g.width(), g.height(),
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    if (settings == nullptr || settings->output != OutputMode::Weighted) continue;
    CompositeOptions o;
    o.mode = compositeMode_;
    if (compositeMode_ == CompositeMode::BlendOverFallback) o.fallbackSpecularTexture = g.fallbackSpecularTexture();
    o.view = v;
    if (Status s = sslr_->composite(finalFbos_[v], o); !s) return s;
  }
  return {};
}

Status ViewsRenderer::prepare(const GpuScene& scene, std::span<const Camera> cameras, const Settings& settings) {
  if (Status s = rasterize(scene, cameras); !s) return s;
  for (FrameInputs& in : layered_) in.previousClipFromView = in.clipFromView;
  for (glm::dmat4& previous : previousClipFromWorld_) previous = glm::dmat4(0.0);
  PrepareOptions options;
  options.composite = settings.output == OutputMode::Weighted;
  options.framebuffer = finalFbos_[0];
  options.compositeOptions.mode = compositeMode_;
  if (compositeMode_ == CompositeMode::BlendOverFallback)
    options.compositeOptions.fallbackSpecularTexture = eyes_[0]->fallbackSpecularTexture();
  return sslr_->prepare(layeredInputs(), settings, options);
}

Image ViewsRenderer::readFinal(int view) const {
  const GBuffer& g = *eyes_[static_cast<size_t>(view)];
  return readTexture(finals_[static_cast<size_t>(view)], g.width(), g.height(), 3);
}

}  // namespace sslr::host
