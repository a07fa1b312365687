#include "sslr_host/reference_image.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/packing.hpp>

#include "host/lighting.h"

namespace sslr::host {

namespace {

float srgbToLinear(std::uint8_t v) {
  const float c = v / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Bilinear, wrapping (GL_REPEAT), sRGB decoded before filtering as GL_SRGB8_ALPHA8 is; the base
// level only (the G-buffer's trilinear filtering of a minified texture is not reproduced).
glm::vec3 sampleTexture(const Texture& t, glm::vec2 uv) {
  if (t.width <= 0 || t.height <= 0) return glm::vec3(1.0f);
  const float x = uv.x * t.width - 0.5f, y = uv.y * t.height - 0.5f;
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const float fx = x - x0, fy = y - y0;
  auto texel = [&](int tx, int ty) {
    tx = ((tx % t.width) + t.width) % t.width;
    ty = ((ty % t.height) + t.height) % t.height;
    const std::uint8_t* p = &t.rgba8[(static_cast<size_t>(ty) * t.width + tx) * 4];
    return glm::vec3(srgbToLinear(p[0]), srgbToLinear(p[1]), srgbToLinear(p[2]));
  };
  return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx), glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx),
                  fy);
}

glm::vec3 viewDirection(const glm::dmat4& viewFromWorld, glm::dvec3 world) {
  return glm::normalize(glm::vec3(viewFromWorld * glm::dvec4(world, 0.0)));
}

// From a point towards the camera (orthographic: along +z).
glm::vec3 toCameraFrom(const RayTracer::Hit& hit, bool orthographic) {
  return orthographic ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::normalize(-hit.vsPosition);
}

glm::vec3 rgbAt(const Image& image, size_t p) {
  const float* v = &image.pixels[p * static_cast<size_t>(image.channels)];
  return glm::vec3(v[0], v[1], v[2]);
}

}  // namespace

glm::vec3 shadeSeenFrom(const Scene& scene, const RayTracer::Hit& hit, const glm::dmat4& viewFromWorld,
                        glm::vec3 vsToViewer) {
  const Mesh& mesh = scene.meshes.at(hit.mesh);
  const Material& m = scene.materials.at(static_cast<size_t>(mesh.material));
  glm::vec3 base = m.baseColor;
  if (m.baseColorTexture >= 0 && static_cast<size_t>(m.baseColorTexture) < scene.textures.size() &&
      !mesh.uvs.empty()) {
    const std::uint32_t* tri = &mesh.indices[3 * static_cast<size_t>(hit.primitive)];
    const glm::vec2 b = hit.barycentric;
    const glm::vec2 uv = mesh.uvs[tri[0]] * (1.0f - b.x - b.y) + mesh.uvs[tri[1]] * b.x + mesh.uvs[tri[2]] * b.y;
    base *= sampleTexture(scene.textures[static_cast<size_t>(m.baseColorTexture)], uv);
  }
  const glm::vec3 n = glm::dot(hit.vsNormal, vsToViewer) < 0.0f ? -hit.vsNormal : hit.vsNormal;  // the side seen
  const glm::vec3 vsLight = viewDirection(viewFromWorld, glm::dvec3(scene.lightDirection));
  const glm::vec3 vsUp = viewDirection(viewFromWorld, glm::dvec3(0.0, 1.0, 0.0));
  return shared::sslrHostLitColor(base, m.metallic, m.baseColor * m.emissive + m.emissiveColor, n, vsLight, vsUp) +
         shared::sslrHostFallbackSpecular(reflectance(m), vsToViewer, n, vsUp, scene.background);
}

glm::vec3 shadeAsGBuffer(const Scene& scene, const RayTracer::Hit& hit, const glm::dmat4& viewFromWorld,
                         bool orthographic) {
  return shadeSeenFrom(scene, hit, viewFromWorld, toCameraFrom(hit, orthographic));
}

glm::vec3 reflectedRadiance(const Scene& scene, const RayTracer::Hit& hit, glm::vec3 vsRayDirection,
                            const glm::dmat4& viewFromWorld, bool orthographic, bool cameraSeesHit) {
  const glm::vec3 toCamera = toCameraFrom(hit, orthographic);
  const glm::vec3 toRayOrigin = -glm::normalize(vsRayDirection);
  // The camera sees the point on the side the ray meets when both lie in front of its face.
  if (cameraSeesHit && glm::dot(hit.vsNormal, toCamera) * glm::dot(hit.vsNormal, toRayOrigin) > 0.0f)
    return asStoredColor(shadeSeenFrom(scene, hit, viewFromWorld, toCamera));
  return shadeSeenFrom(scene, hit, viewFromWorld, toRayOrigin);
}

glm::vec3 asStoredColor(glm::vec3 rgb) { return glm::unpackF2x11_1x10(glm::packF2x11_1x10(rgb)); }

ReferenceImage referenceComposite(const Scene& scene, const RayTracer& tracer, const GBuffer& gbuffer,
                                  const GroundTruth& truth) {
  ReferenceImage ref;
  const Image color = gbuffer.readColor(), fallback = gbuffer.readFallbackSpecular();
  const int w = truth.width, h = truth.height;
  ref.composite.width = w;
  ref.composite.height = h;
  ref.composite.channels = 3;
  ref.composite.pixels.assign(static_cast<size_t>(w) * h * 3, 0.0f);
  ref.scored.assign(static_cast<size_t>(w) * h, 0);
  const glm::dmat4& clipFromView = gbuffer.clipFromView();
  const bool ortho = clipFromView[3][3] == 1.0;
  const PrimaryRays rays{glm::inverse(clipFromView), ortho, w, h};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = static_cast<size_t>(y) * w + x;
      glm::vec3 out = rgbAt(color, p);
      if (truth.pixels[p].cls != TruthClass::NotReflective) {
        glm::dvec3 origin, dir;
        rays.at(x, y, origin, dir);
        const RayTracer::Hit primary = tracer.intersect(glm::vec3(origin), glm::vec3(dir));
        const Material* m = primary.hit ? &scene.materials.at(static_cast<size_t>(scene.meshes.at(primary.mesh).material))
                                        : nullptr;
        if (m != nullptr && m->roughness <= kReferenceMaxRoughness) {
          const Reflection reflected = traceReflection(tracer, primary, glm::vec3(dir));
          // A point the camera sees on the side the ray meets, as the colour buffer stores it (what a
          // screen-space method can read of it at best); any other, lit on the side the ray meets and
          // seen along the ray. An escaped ray: the colour as it is, whose fallback specular is the
          // environment in the mirror direction as the frame stores it, so that a miss scores 0.
          if (reflected.hit.hit) {
            const glm::vec3 radiance = reflectedRadiance(scene, reflected.hit, reflected.direction,
                                                         gbuffer.viewFromWorld(), ortho,
                                                         truth.pixels[p].cls == TruthClass::Visible);
            const float cosVN = std::max(glm::dot(-glm::vec3(dir), primary.vsNormal), 0.0f);
            out += reflectance(*m) * shared::sslrFresnelClassic(cosVN) * radiance - rgbAt(fallback, p);
          }
          ref.scored[p] = 1;
          ++ref.scoredCount;
        }
      }
      for (int c = 0; c < 3; ++c) ref.composite.pixels[p * 3 + c] = out[c];
    }
  return ref;
}

Expected<ReferenceImage> referenceFor(const Scene& scene, const GBuffer& gbuffer, const GroundTruth& truth) {
  auto tracer = RayTracer::create(scene, gbuffer.viewFromWorld());
  if (!tracer) return Status::error(tracer.error());
  return referenceComposite(scene, *tracer.value(), gbuffer, truth);
}

ImageError compositeError(const ReferenceImage& reference, const Image& composite) {
  ImageError e;
  double sum = 0.0;
  for (size_t p = 0; p < reference.scored.size(); ++p) {
    if (!reference.scored[p]) continue;
    const glm::vec3 d = rgbAt(composite, p) - rgbAt(reference.composite, p);
    sum += double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    ++e.pixels;
  }
  if (e.pixels == 0) return e;
  e.rmse = std::sqrt(sum / (3.0 * double(e.pixels)));
  e.psnr = e.rmse > 0.0 ? 20.0 * std::log10(1.0 / e.rmse) : 99.0;
  return e;
}

namespace {
// CompositeBreakdown::ByTruth's slot of a traced pixel's class (-1: not traced).
int truthIndex(TruthClass cls) {
  switch (cls) {
    case TruthClass::Visible: return 0;
    case TruthClass::Occluded: return 1;
    case TruthClass::OffScreen: return 2;
    case TruthClass::Escaped: return 3;
    default: return -1;
  }
}
}  // namespace

CompositeBreakdown compositeBreakdown(const ReferenceImage& reference, const Image& composite, const GroundTruth& truth,
                                      const Image& hit, const Image& withoutReflection) {
  CompositeBreakdown b;
  double sum[5] = {0, 0, 0, 0, 0}, total = 0.0, wrongAsMisses = 0.0, truthSum[4] = {0, 0, 0, 0};
  CompositeBreakdown::Kind* kinds[5] = {&b.hit, &b.wrong, &b.guessed, &b.missed, &b.unreachable};
  CompositeBreakdown::Kind* truths[4] = {&b.byTruth.visible, &b.byTruth.occluded, &b.byTruth.offScreen,
                                         &b.byTruth.escaped};
  auto squaredError = [&](const Image& image, size_t p) {
    const glm::vec3 d = rgbAt(image, p) - rgbAt(reference.composite, p);
    return double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
  };
  for (size_t p = 0; p < reference.scored.size(); ++p) {
    if (!reference.scored[p]) continue;
    const TruthPixel& tp = truth.pixels[p];
    const float* h = &hit.pixels[p * static_cast<size_t>(hit.channels)];
    const bool reported = h[2] > kReportedConfidence, guessed = !reported && h[2] > 0.0f;
    const bool visible = tp.cls == TruthClass::Visible;
    const bool within1px =
        visible && std::hypot((h[0] - tp.uvHit.x) * truth.width, (h[1] - tp.uvHit.y) * truth.height) <= 1.0f;
    const int k = reported ? (within1px ? 0 : 1) : guessed ? 2 : (visible ? 3 : 4);
    const double e = squaredError(composite, p);
    sum[k] += e;
    total += e;
    ++kinds[k]->pixels;
    if (k == 1) wrongAsMisses += squaredError(withoutReflection, p);
    const int t = truthIndex(tp.cls);
    if (t >= 0) {
      truthSum[t] += e;
      ++truths[t]->pixels;
    }
  }
  auto finish = [total](CompositeBreakdown::Kind& kind, double squared) {
    if (kind.pixels > 0) kind.rmse = std::sqrt(squared / (3.0 * double(kind.pixels)));
    kind.share = total > 0.0 ? squared / total : 0.0;
  };
  for (int k = 0; k < 5; ++k) finish(*kinds[k], sum[k]);
  for (int t = 0; t < 4; ++t) finish(*truths[t], truthSum[t]);
  b.wrongAsMisses.pixels = b.wrong.pixels;
  if (b.wrong.pixels > 0) b.wrongAsMisses.rmse = std::sqrt(wrongAsMisses / (3.0 * double(b.wrong.pixels)));
  b.wrongAsMisses.share = total > 0.0 ? wrongAsMisses / total : 0.0;
  return b;
}

Image compositeErrorMap(const ReferenceImage& reference, const Image& composite) {
  Image map;
  map.width = reference.composite.width;
  map.height = reference.composite.height;
  map.channels = 3;
  map.pixels.assign(static_cast<size_t>(map.width) * map.height * 3, 0.1f);
  for (size_t p = 0; p < reference.scored.size(); ++p) {
    if (!reference.scored[p]) continue;
    const glm::vec3 d = glm::min(glm::abs(rgbAt(composite, p) - rgbAt(reference.composite, p)) * 4.0f, glm::vec3(1.0f));
    for (int c = 0; c < 3; ++c) map.pixels[p * 3 + c] = d[c];
  }
  return map;
}

}  // namespace sslr::host
