// The depth-only G-buffer pass of the tools: rasterizes a Scene into
//   colour  R11F_G11F_B10F  lit colour (deterministic direct + ambient light)       4 B/px
//   normal  RGBA16          RG = octahedral view-space normal, B = roughness, A = F0 8 B/px
//           (or RGBA8 with RGB = n * 0.5 + 0.5, A = F0: the article's packing)
//   depth   D32F (D24 for GlDefault)                                                 4 B/px
// and nothing else: 16 B/px in all. A view-space position texture (RGBA32F) is added only on
// request, for tests and the position-buffer comparison.
// The same pass writes the host's fallback specular (R11F_G11F_B10F: Fresnel x a sky/ground
// environment, what a probe or IBL gives an engine); it is already part of the lit colour, and
// sslr's BlendOverFallback composite swaps it for the traced reflection where that has coverage.
#pragma once

#include <memory>

#include "sslr/sslr.hpp"
#include "sslr_host/camera.hpp"
#include "sslr_host/gl.hpp"
#include "sslr_host/image_io.hpp"
#include "sslr_host/scene.hpp"

namespace sslr::host {

struct GBufferOptions {
  int width = 640;
  int height = 360;
  DepthMode depth = DepthMode::Reversed;
  NormalEncoding normals = NormalEncoding::Octahedral;
  bool withPosition = false;  // also write view-space position (RGBA32F, w = 1 on geometry)
  bool withBackDepth = false; // also render the back-face depth (front faces culled), for
                              // FrameInputs::backDepthTexture
};

// A scene uploaded to GL: one vertex/index buffer pair, one draw per mesh.
class GpuScene {
 public:
  explicit GpuScene(const Scene& scene);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  struct Draw {
    GLsizei indexCount = 0;
    size_t firstIndex = 0;
    GLint baseVertex = 0;
    int material = 0;
    glm::dmat4 worldFromModel{1.0};
  };
  const Scene& scene() const { return scene_; }
  GLuint vao() const { return vao_; }
  const std::vector<Draw>& draws() const { return draws_; }
  GLuint texture(int index) const { return index >= 0 && index < (int)textures_.size() ? textures_[index] : 0; }

 private:
  Scene scene_;
  GLuint vao_ = 0, vbo_ = 0, ibo_ = 0;
  std::vector<GLuint> textures_;
  std::vector<Draw> draws_;
};

class GBuffer {
 public:
  static Expected<std::unique_ptr<GBuffer>> create(const GBufferOptions& options);
  ~GBuffer();
  GBuffer(const GBuffer&) = delete;
  GBuffer& operator=(const GBuffer&) = delete;

  // Rasterizes the scene from the camera; jitterPx offsets the projection (sub-pixel).
  Status render(const GpuScene& scene, const Camera& camera, glm::dvec2 jitterPx = {0.0, 0.0});

  const GBufferOptions& options() const { return options_; }
  int width() const { return options_.width; }
  int height() const { return options_.height; }
  GLuint colorTexture() const { return color_; }
  GLuint normalTexture() const { return normal_; }
  GLuint depthTexture() const { return depth_; }
  GLuint positionTexture() const { return position_; }
  GLuint backDepthTexture() const { return backDepth_; }  // withBackDepth only, else 0
  GLuint fallbackSpecularTexture() const { return fallback_; }
  GLuint framebuffer() const { return fbo_; }
  const glm::dmat4& clipFromView() const { return clipFromView_; }
  const glm::dmat4& viewFromWorld() const { return viewFromWorld_; }

  // What sslr needs for this G-buffer (textures, projection, convention, layout).
  FrameInputs frameInputs() const;
  // Bytes per pixel of the G-buffer proper (colour + normal + depth; position excluded).
  int bytesPerPixel() const;

  // Read-backs (GL row order).
  Image readColor() const;
  Image readNormalPacked() const;  // RGBA as stored
  Image readDepth() const;         // 1 channel, raw window depth
  Image readPosition() const;      // RGBA32F position texture (withPosition only)
  Image readBackDepth() const;     // 1 channel, raw window depth of the nearest back face (withBackDepth only)
  Image readFallbackSpecular() const;  // RGB
  // Whether no pixel shows the scene: every depth the clear value (`depth`: readDepth()'s). A
  // model scaled to nothing, degenerate triangles or a camera looking away render the background.
  bool showsNothing(const Image& depth) const;

 private:
  GBuffer() = default;
  GBufferOptions options_;
  GLuint fbo_ = 0, color_ = 0, normal_ = 0, depth_ = 0, position_ = 0, fallback_ = 0, program_ = 0;
  GLuint backFbo_ = 0, backDepth_ = 0;
  void renderBackDepth(const GpuScene& gpu, float clearDepth);
  glm::dmat4 clipFromView_{1.0}, viewFromWorld_{1.0};
};

// Reads a texture's level 0 as float (format GL_RGBA/GL_RED/GL_DEPTH_COMPONENT).
Image readTexture(GLuint texture, int width, int height, int channels, GLenum format = 0);

// Decodes a packed normal image (as read back) into view-space unit normals (RGB).
Image decodeNormals(const Image& packed, NormalEncoding encoding);
// View-space positions rebuilt from raw depth with the shared header's formulas (what the GPU
// does); background pixels get NaN-free zeros and alpha 0.
Image reconstructPositions(const Image& depth, const glm::dmat4& clipFromView, DepthConvention convention);

}  // namespace sslr::host
