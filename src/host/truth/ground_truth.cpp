#include "sslr_host/ground_truth.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>

#include "sslr/reference.hpp"
#include "sslr_shared.h"

namespace sslr::host {

size_t GroundTruth::count(TruthClass c) const {
  return static_cast<size_t>(std::count_if(pixels.begin(), pixels.end(), [c](const TruthPixel& p) { return p.cls == c; }));
}

struct RayTracer::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  // Per geometry: view-space vertex normals and indices, for interpolation.
  std::vector<std::vector<glm::vec3>> normals;
  std::vector<std::vector<std::uint32_t>> indices;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

Expected<std::unique_ptr<RayTracer>> RayTracer::create(const Scene& scene, const glm::dmat4& viewFromWorld) {
  auto rt = std::unique_ptr<RayTracer>(new RayTracer());
  rt->impl_ = std::make_unique<Impl>();
  Impl& im = *rt->impl_;
  im.device = rtcNewDevice(nullptr);
  if (im.device == nullptr) return Status::error("Embree: rtcNewDevice failed");
  im.scene = rtcNewScene(im.device);
  rtcSetSceneFlags(im.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(im.scene, RTC_BUILD_QUALITY_HIGH);
  for (const Mesh& m : scene.meshes) {
    const glm::dmat4 viewFromModel = viewFromWorld * m.worldFromModel;
    const glm::dmat3 normalMatrix = normalMatrixOf(viewFromModel);
    RTCGeometry geom = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), m.positions.size()));
    std::vector<glm::vec3> vsNormals(m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
      const glm::dvec3 p = glm::dvec3(viewFromModel * glm::dvec4(glm::dvec3(m.positions[i]), 1.0));
      v[3 * i] = static_cast<float>(p.x);
      v[3 * i + 1] = static_cast<float>(p.y);
      v[3 * i + 2] = static_cast<float>(p.z);
      const glm::dvec3 n = i < m.normals.size() ? glm::dvec3(m.normals[i]) : glm::dvec3(0, 0, 1);
      vsNormals[i] = glm::vec3(normalMatrix * n);
    }
    auto* idx = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                    3 * sizeof(std::uint32_t), m.indices.size() / 3));
    std::copy(m.indices.begin(), m.indices.end(), idx);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(im.scene, geom);
    rtcReleaseGeometry(geom);
    im.normals.push_back(std::move(vsNormals));
    im.indices.push_back(m.indices);
  }
  rtcCommitScene(im.scene);
  if (rtcGetDeviceError(im.device) != RTC_ERROR_NONE) return Status::error("Embree: building the scene failed");
  return rt;
}

RayTracer::~RayTracer() = default;

RayTracer::Hit RayTracer::intersect(glm::vec3 o, glm::vec3 d, float tFar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh{};
  rh.ray.org_x = o.x; rh.ray.org_y = o.y; rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x; rh.ray.dir_y = d.y; rh.ray.dir_z = d.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tFar;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.mesh = rh.hit.geomID;
  h.primitive = rh.hit.primID;
  h.barycentric = glm::vec2(rh.hit.u, rh.hit.v);
  h.t = rh.ray.tfar;
  h.vsPosition = o + d * h.t;
  const auto& idx = impl_->indices[rh.hit.geomID];
  const auto& nrm = impl_->normals[rh.hit.geomID];
  const std::uint32_t* tri = &idx[3 * static_cast<size_t>(rh.hit.primID)];
  const float u = rh.hit.u, v = rh.hit.v;
  glm::vec3 n = nrm[tri[0]] * (1.0f - u - v) + nrm[tri[1]] * u + nrm[tri[2]] * v;
  // Vertex normals that a singular transform flattened to zero: the face's own normal, as the
  // G-buffer pass takes it.
  const float length2 = glm::dot(n, n);
  n = length2 > 1e-30f && std::isfinite(length2) ? n / std::sqrt(length2)
                                                  : glm::normalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  if (glm::dot(n, d) > 0.0f) n = -n;  // two-sided, like the G-buffer pass
  h.vsNormal = n;
  return h;
}

bool RayTracer::occluded(glm::vec3 o, glm::vec3 d, float tFar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray{};
  ray.org_x = o.x; ray.org_y = o.y; ray.org_z = o.z;
  ray.dir_x = d.x; ray.dir_y = d.y; ray.dir_z = d.z;
  ray.tnear = 0.0f;
  ray.tfar = tFar;
  ray.mask = 0xffffffffu;
  rtcOccluded1(impl_->scene, &ctx, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

std::vector<std::uint8_t> reflectiveMask(const Image& depth, const Image& normalPacked, const FrameInputs& in,
                                         const Settings& settings) {
  std::vector<std::uint8_t> none(static_cast<size_t>(depth.width) * depth.height, 0);
  auto frame = frameConstants(in, settings, depth.width, depth.height);
  if (!frame) return none;
  const shared::SslrSurface s = frame.value().surface;
  const shared::SslrTraceParams t = frame.value().trace;
  std::vector<std::uint8_t> mask(static_cast<size_t>(depth.width) * depth.height, 0);
  for (size_t p = 0; p < mask.size(); ++p) {
    const float* n = &normalPacked.pixels[p * normalPacked.channels];
    const glm::vec4 texel(n[0], n[1], n[2], n[3]);  // the tools keep the material in the normal texel
    mask[p] = shared::sslrShouldTrace(s, t, depth.pixels[p], texel, texel) ? 1 : 0;
  }
  return mask;
}

namespace {

// What a pixel shows (mesh and normal), traced once on first use: neighbouring visible hits ask
// for the same pixels many times over.
class ShownPixels {
 public:
  ShownPixels(const RayTracer& tracer, const PrimaryRays& rays)
      : tracer_(tracer), rays_(rays), shown_(static_cast<size_t>(rays.width) * rays.height) {}

  // Whether a pixel within 1 px of `hit` (at uv) shows its surface: same mesh, normals within 25 deg.
  bool near(glm::dvec2 uv, const RayTracer::Hit& hit) {
    const int cx = static_cast<int>(std::floor(uv.x * rays_.width)), cy = static_cast<int>(std::floor(uv.y * rays_.height));
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, rays_.height - 1); ++y)
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, rays_.width - 1); ++x) {
        const Shown& seen = at(x, y);
        if (seen.mesh == std::int32_t(hit.mesh) && glm::dot(seen.vsNormal, hit.vsNormal) > 0.906f) return true;
      }
    return false;
  }

 private:
  struct Shown {
    glm::vec3 vsNormal{0.0f};
    std::int32_t mesh = -2;  // -2: not traced yet; -1: nothing (16 bytes a pixel)
  };
  const Shown& at(int x, int y) {
    Shown& s = shown_[static_cast<size_t>(y) * rays_.width + x];
    if (s.mesh == -2) {
      glm::dvec3 origin, dir;
      rays_.at(x, y, origin, dir);
      const RayTracer::Hit h = tracer_.intersect(glm::vec3(origin), glm::vec3(dir));
      s.mesh = h.hit ? std::int32_t(h.mesh) : -1;
      s.vsNormal = h.vsNormal;
    }
    return s;
  }
  const RayTracer& tracer_;
  const PrimaryRays& rays_;
  std::vector<Shown> shown_;
};

// The true reflection of the reflective pixel (x, y), classified.
TruthPixel truthAt(const RayTracer& tracer, const glm::dmat4& clipFromView, const PrimaryRays& rays,
                   ShownPixels& shown, int x, int y) {
  const bool ortho = rays.ortho;
  glm::dvec3 origin, dir;
  rays.at(x, y, origin, dir);
  const RayTracer::Hit primary = tracer.intersect(glm::vec3(origin), glm::vec3(dir));
  TruthPixel tp;
  if (!primary.hit) {
    tp.cls = TruthClass::Escaped;  // the G-buffer saw geometry the tracer missed (edge pixel)
    return tp;
  }
  const RayTracer::Hit refl = traceReflection(tracer, primary, glm::vec3(dir)).hit;
  if (!refl.hit) {
    tp.cls = TruthClass::Escaped;
    return tp;
  }
  tp.length = glm::length(refl.vsPosition - primary.vsPosition);
  const glm::dvec4 clip = clipFromView * glm::dvec4(glm::dvec3(refl.vsPosition), 1.0);
  if (!(clip.w > 0.0)) {
    tp.cls = TruthClass::OffScreen;
    return tp;
  }
  const glm::dvec3 ndcHit = glm::dvec3(clip) / clip.w;
  const glm::dvec2 uv = glm::dvec2(ndcHit) * 0.5 + 0.5;
  const bool inDepth = ndcHit.z >= -1.0 - 1e-9 && ndcHit.z <= 1.0 + 1e-9;  // within near..far (either range)
  if (uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0 || !inDepth) {
    tp.cls = TruthClass::OffScreen;
    return tp;
  }
  tp.uvHit = glm::vec2(uv);
  // Visible if nothing lies between the camera and the hit point.
  const glm::vec3 camOrigin = ortho ? glm::vec3(refl.vsPosition.x, refl.vsPosition.y, 0.0f) : glm::vec3(0.0f);
  const glm::vec3 toHit = refl.vsPosition - camOrigin;
  const float dist = glm::length(toHit);
  const bool hidden = tracer.occluded(camOrigin, toHit / dist, dist * (1.0f - 1e-4f));
  tp.cls = hidden ? TruthClass::Occluded : TruthClass::Visible;
  if (!hidden) {
    // The hit's normal as the camera sees it (the tracer's faces the reflected ray's origin).
    RayTracer::Hit facingCamera = refl;
    if (glm::dot(facingCamera.vsNormal, toHit) > 0.0f) facingCamera.vsNormal = -facingCamera.vsNormal;
    tp.shown = shown.near(uv, facingCamera);
  }
  return tp;
}

}  // namespace

GroundTruth computeGroundTruth(const RayTracer& tracer, const glm::dmat4& clipFromView, int width, int height,
                               const std::vector<std::uint8_t>& reflective) {
  GroundTruth gt;
  gt.width = width;
  gt.height = height;
  gt.pixels.resize(static_cast<size_t>(width) * height);
  const PrimaryRays rays{glm::inverse(clipFromView), clipFromView[3][3] == 1.0, width, height};
  ShownPixels shown(tracer, rays);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t p = static_cast<size_t>(y) * width + x;
      if (reflective[p]) gt.pixels[p] = truthAt(tracer, clipFromView, rays, shown, x, y);
    }
  return gt;
}

Expected<GroundTruth> groundTruthFor(const Scene& scene, const GBuffer& gbuffer, const Settings& settings) {
  auto tracer = RayTracer::create(scene, gbuffer.viewFromWorld());
  if (!tracer) return Status::error(tracer.error());
  return groundTruthFor(*tracer.value(), gbuffer, settings);
}

GroundTruth groundTruthFor(const RayTracer& tracer, const GBuffer& gbuffer, const Settings& settings) {
  const auto mask = reflectiveMask(gbuffer.readDepth(), gbuffer.readNormalPacked(), gbuffer.frameInputs(), settings);
  return computeGroundTruth(tracer, gbuffer.clipFromView(), gbuffer.width(), gbuffer.height(), mask);
}

HitMetrics compareHits(const GroundTruth& truth, const Image& hit, float threshold, const Image* color) {
  HitMetrics m;
  double sqErr = 0.0;
  size_t sqCount = 0;
  std::vector<double> errors;
  size_t within1 = 0, within2 = 0, within4 = 0, falseHits = 0, hiddenByHair = 0, shownWithin1 = 0;
  for (size_t p = 0; p < truth.pixels.size(); ++p) {
    const float* h = &hit.pixels[p * hit.channels];
    bool finite = true;
    for (int c = 0; c < hit.channels; ++c) finite = finite && std::isfinite(h[c]);
    m.nonFinite += finite ? 0 : 1;
    const TruthPixel& t = truth.pixels[p];
    const bool reported = finite && h[2] > threshold;
    switch (t.cls) {
      case TruthClass::NotReflective: break;
      case TruthClass::Visible: {
        ++m.visible;
        m.unshown += t.shown ? 0 : 1;
        if (color != nullptr) {
          const glm::vec3 ref = sampleBilinear(*color, t.uvHit);
          const glm::vec3 got = reported ? sampleBilinear(*color, glm::vec2(h[0], h[1])) : glm::vec3(0.0f);
          const glm::vec3 d = got - ref;
          sqErr += glm::dot(d, d) / 3.0;
          ++sqCount;
        }
        if (!reported) break;
        const double ex = (h[0] - t.uvHit.x) * truth.width, ey = (h[1] - t.uvHit.y) * truth.height;
        const double e = std::sqrt(ex * ex + ey * ey);
        errors.push_back(e);
        within1 += e <= 1.0;
        shownWithin1 += t.shown && e <= 1.0;
        within2 += e <= 2.0;
        within4 += e <= 4.0;
        break;
      }
      case TruthClass::Occluded: {
        ++m.occluded;
        falseHits += reported;
        // The true hit is hidden, but by less than a pixel: the reported point is it, to the pixel.
        const double ex = (h[0] - t.uvHit.x) * truth.width, ey = (h[1] - t.uvHit.y) * truth.height;
        hiddenByHair += reported && ex * ex + ey * ey <= 1.0;
        break;
      }
      case TruthClass::OffScreen: ++m.offScreen; falseHits += reported; break;
      case TruthClass::Escaped: ++m.escaped; falseHits += reported; break;
    }
  }
  if (m.visible > 0) {
    m.recall1px = double(within1) / m.visible;
    m.recall2px = double(within2) / m.visible;
    m.recall4px = double(within4) / m.visible;
  }
  if (m.visible > m.unshown) m.recallShown1px = double(shownWithin1) / double(m.visible - m.unshown);
  if (!errors.empty()) {
    std::sort(errors.begin(), errors.end());
    m.medianErrorPx = errors[errors.size() / 2];
    m.p95ErrorPx = errors[std::min(errors.size() - 1, static_cast<size_t>(std::ceil(0.95 * errors.size())) - 1)];
  }
  if (sqCount > 0) {
    m.reflectionRmse = std::sqrt(sqErr / sqCount);
    m.reflectionPsnr = m.reflectionRmse > 0 ? 20.0 * std::log10(1.0 / m.reflectionRmse) : 99.0;
  }
  const size_t negatives = m.occluded + m.offScreen + m.escaped;
  m.falseHitRate = negatives > 0 ? double(falseHits) / negatives : 0.0;
  m.falseHitRateBeyond1px = negatives > 0 ? double(falseHits - hiddenByHair) / negatives : 0.0;
  return m;
}

Image hitErrorImage(const GroundTruth& gt, const Image& hit) {
  Image img{gt.width, gt.height, 3, std::vector<float>(static_cast<size_t>(gt.width) * gt.height * 3, 0.0f)};
  for (int y = 0; y < gt.height; ++y)
    for (int x = 0; x < gt.width; ++x) {
      const TruthPixel& t = gt.pixels[static_cast<size_t>(y) * gt.width + x];
      const bool reported = hit.at(x, y, 2) > kReportedConfidence;
      glm::vec3 c(0.0f);
      if (t.cls == TruthClass::Visible) {
        const float e =
            glm::length((glm::vec2(hit.at(x, y, 0), hit.at(x, y, 1)) - t.uvHit) * glm::vec2(gt.width, gt.height));
        if (!reported) c = {0.8f, 0.0f, 0.8f};
        else if (e <= 1.0f) c = {0.0f, e, 0.0f};
        else if (e <= 2.0f) c = {e - 1.0f, 1.0f, 0.0f};
        else c = {1.0f, std::max(0.0f, 1.0f - (e - 2.0f) / 2.0f), 0.0f};
      } else if (t.cls != TruthClass::NotReflective && reported) {
        c = glm::vec3(1.0f);
      }
      for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[k];
    }
  return img;
}

Image truthImage(const GroundTruth& gt) {
  Image img{gt.width, gt.height, 4, std::vector<float>(static_cast<size_t>(gt.width) * gt.height * 4, 0.0f)};
  for (int y = 0; y < gt.height; ++y)
    for (int x = 0; x < gt.width; ++x) {
      const TruthPixel& t = gt.pixels[static_cast<size_t>(y) * gt.width + x];
      img.at(x, y, 0) = t.uvHit.x;
      img.at(x, y, 1) = t.uvHit.y;
      img.at(x, y, 2) = static_cast<float>(t.cls);
      img.at(x, y, 3) = t.shown ? 1.0f : 0.0f;
    }
  return img;
}

}  // namespace sslr::host
