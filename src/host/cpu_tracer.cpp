#include "sslr_host/cpu_tracer.hpp"

#include "sslr/reference.hpp"
#include "sslr_shared.h"

// The loaders the shared tracers call, over the G-buffer of the current traceOnCpu call.
namespace sslr::shared {
namespace {
thread_local const sslr::host::CpuGBuffer* tG = nullptr;
thread_local SslrProjection tProj{};
thread_local SslrSurface tSurf{};
thread_local bool tStored = false;
}  // namespace
float sslrLoadDepth(ivec2 px) { return tG->depth->at(px.x, px.y, 0); }
vec4 sslrLoadNormal(ivec2 px) {
  const sslr::host::Image& n = *tG->normalPacked;
  return vec4(n.at(px.x, px.y, 0), n.at(px.x, px.y, 1), n.at(px.x, px.y, 2), n.at(px.x, px.y, 3));
}
bool sslrLoadPosition(ivec2 px, vec4& vsPosition) {
  const sslr::host::Image& p = *tG->positions;
  vsPosition = vec4(p.at(px.x, px.y, 0), p.at(px.x, px.y, 1), p.at(px.x, px.y, 2), p.at(px.x, px.y, 3));
  return vsPosition.w > 0.0f;
}
bool sslrLoadSurface(ivec2 px, vec3& vsPos) {
  if (tStored) {
    vec4 p;
    const bool ok = sslrLoadPosition(px, p);
    vsPos = vec3(p);
    return ok;
  }
  return sslrSurfaceFromDepth(tProj, tSurf, px, sslrLoadDepth(px), vsPos);
}
}  // namespace sslr::shared

#include "sslr_trace_position.h"

namespace sslr::host {

Image traceOnCpu(const CpuGBuffer& g, const FrameInputs& in, const Settings& settings, SurfaceSource source) {
  using namespace sslr::shared;
  const int w = g.depth->width, h = g.depth->height;
  Image hit;
  hit.width = w;
  hit.height = h;
  hit.channels = 4;
  hit.pixels.assign(static_cast<size_t>(w) * h * 4, 0.0f);
  auto frame = frameConstants(in, settings, w, h);  // the block the GPU pass would read
  if (!frame) return hit;
  const SslrProjection proj = frame.value().proj;
  const SslrSurface surf = frame.value().surface;
  const SslrTraceParams t = frame.value().trace;
  const SslrPositionParams pb = frame.value().positionBuffer;
  tG = &g;
  tProj = proj;
  tSurf = surf;
  tStored = source == SurfaceSource::StoredPositions;
  const bool positionMethod = settings.method == Method::PositionBuffer;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const ivec2 px(x, y);
      const vec4 texel = sslrLoadNormal(px);
      const float depth = sslrLoadDepth(px);
      vec3 vsP;
      bool geometry;
      if (positionMethod || tStored) {
        vec4 stored;
        geometry = sslrLoadPosition(px, stored);
        vsP = vec3(stored);
      } else {
        geometry = sslrSurfaceFromDepth(proj, surf, px, depth, vsP);
      }
      if (!geometry || !sslrShouldTrace(surf, t, depth, texel)) continue;
      vec3 vsN;
      sslrDecodeNormal(surf, texel, vsN);
      const vec3 vsV = sslrViewDirection(proj, vsP);
      if (!(dot(-vsV, vsN) > 0.0f)) continue;
      const vec3 vsR = reflect(vsV, vsN);
      const SslrHit r = positionMethod ? sslrTracePositionBuffer(proj, surf, pb, vsP, vsV, vsR)
                                       : sslrTraceAdaptiveL(proj, surf, t, px, vsP, vsV, vsR);
      float* o = &hit.at(x, y, 0);
      o[0] = r.uvHit.x;
      o[1] = r.uvHit.y;
      o[2] = r.confidence;
      o[3] = r.L;
    }
  tG = nullptr;
  return hit;
}

}  // namespace sslr::host
