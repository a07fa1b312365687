#include "sslr_host/cpu_tracer.hpp"

#include <vector>

#include "sslr/reference.hpp"
#include "sslr_shared.h"

// The loaders the shared tracers call, over the G-buffer of the current traceOnCpu call.
namespace sslr::shared {
namespace {
thread_local const sslr::host::CpuGBuffer* tG = nullptr;
thread_local SslrProjection tProj{};
thread_local SslrSurface tSurf{};
thread_local bool tStored = false;
// The min-max depth pyramid, built on the CPU with the same shared functions as the GPU's
// pass 2 (passes/pyramid_levels01.glsl, 2_pyramid_*.comp): tPyramid[l] is level l (level 0: sslrHiZLevel0Texel, with curved solids' extra
// depths), tPyramidWidth[l] its cells per row.
thread_local std::vector<std::vector<vec2>> tPyramid;
thread_local std::vector<int> tPyramidWidth, tPyramidHeight;
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
vec2 sslrLoadPyramidTexel(int level, ivec2 cell) {
  const int w = tPyramidWidth[level], h = tPyramidHeight[level];
  if (cell.x < 0 || cell.y < 0 || cell.x >= w || cell.y >= h) return sslrHiZEmpty();
  return tPyramid[level][static_cast<size_t>(cell.y) * w + cell.x];
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

#include "sslr_trace_dda.h"
#include "sslr_trace_ffx.h"
#include "sslr_trace_hiz.h"
#include "sslr_trace_position.h"

namespace sslr::host {

namespace {

// Classification's level-1 cell (cx, cy) (with the curved solids' backs or the measured depths),
// writing the curved pass's level-0 extra depths of the quad's pixels on screen.
shared::vec2 level1Cell(const CpuGBuffer& g, const shared::SslrProjection& proj, const shared::SslrSurface& surf,
                        const shared::SslrTraceParams& t, int cx, int cy, int w, int h) {
  using namespace sslr::shared;
  vec2 m = sslrHiZEmpty();
  const ivec2 cell(cx, cy), last(w - 1, h - 1);
  const ivec2 q0 = sslrQuadPixel(cell, 0, last), q1 = sslrQuadPixel(cell, 1, last);
  const ivec2 q2 = sslrQuadPixel(cell, 2, last), q3 = sslrQuadPixel(cell, 3, last);
  vec4 extra;
  const vec4 depths(sslrLoadDepth(q0), sslrLoadDepth(q1), sslrLoadDepth(q2), sslrLoadDepth(q3));
  if (sslrBackDepth(surf) && g.backDepth) {  // classification's measured cells
    auto back = [&](ivec2 q) { return g.backDepth->at(q.x, q.y, 0); };
    m = sslrHiZLevel1Measured(proj, surf, t, depths, vec4(back(q0), back(q1), back(q2), back(q3)), extra);
    if (!sslrHiZCellHoldsGeometry(surf, m)) extra = vec4(0.0f);
  } else {
    m = sslrHiZLevel1Cell(proj, surf, t, q0, q1, q2, q3, depths, sslrLoadNormal(q0), sslrLoadNormal(q1),
                          sslrLoadNormal(q2), sslrLoadNormal(q3), extra);
  }
  for (int k = 0; k < 4; ++k) {  // the curved pass's level-0 texels: the quad's pixels on screen
    const ivec2 q(2 * cx + (k & 1), 2 * cy + (k >> 1));
    if (q.x < w && q.y < h) tPyramid[0][static_cast<size_t>(q.y) * w + q.x].y = extra[k];
  }
  return m;
}

// The pyramid's levels as pass 2 builds them (level l: ceil(size / 2^l) cells per axis), into
// tPyramid: only when the trace uses them (as dispatch() builds them only then).
void buildCpuPyramid(const CpuGBuffer& g, const shared::SslrProjection& proj, const shared::SslrSurface& surf,
                     const shared::SslrTraceParams& t, int w, int h) {
  using namespace sslr::shared;
  tPyramid.clear();
  tPyramidWidth.clear();
  tPyramidHeight.clear();
  const int levels = t.hizMode != SSLR_HIZ_OFF ? t.hizLevels : -1;
  if (levels >= 0) {  // level 0; its extra depths come with level 1
    std::vector<vec2> texels(static_cast<size_t>(w) * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        texels[static_cast<size_t>(y) * w + x] = sslrHiZLevel0Texel(surf, sslrLoadDepth(ivec2(x, y)), 0.0f);
    tPyramid.push_back(std::move(texels));
    tPyramidWidth.push_back(w);
    tPyramidHeight.push_back(h);
  }
  for (int level = 1; level <= levels; ++level) {
    const int pw = (w + (1 << level) - 1) >> level, ph = (h + (1 << level) - 1) >> level;
    std::vector<vec2> cells(static_cast<size_t>(pw) * ph);
    for (int cy = 0; cy < ph; ++cy)
      for (int cx = 0; cx < pw; ++cx) {
        vec2 m = sslrHiZEmpty();
        if (level == 1) {
          cells[static_cast<size_t>(cy) * pw + cx] = level1Cell(g, proj, surf, t, cx, cy, w, h);
          continue;
        }
        for (int k = 0; k < 4; ++k) {  // levels 2...: the min-max of the level below
          const ivec2 child(2 * cx + (k & 1), 2 * cy + (k >> 1));
          if (child.x < tPyramidWidth[level - 1] && child.y < tPyramidHeight[level - 1])
            m = sslrHiZReduce(m, sslrLoadPyramidTexel(level - 1, child));
        }
        cells[static_cast<size_t>(cy) * pw + cx] = m;
      }
    tPyramid.push_back(std::move(cells));
    tPyramidWidth.push_back(pw);
    tPyramidHeight.push_back(ph);
  }
}

}  // namespace

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
  buildCpuPyramid(g, proj, surf, t, w, h);
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
      if (!geometry || !sslrShouldTrace(surf, t, depth, texel, texel)) continue;  // material in the normal texel
      vec3 vsN;
      sslrDecodeNormal(surf, texel, vsN);
      const vec3 vsV = sslrViewDirection(proj, vsP);
      if (!(dot(-vsV, vsN) > 0.0f)) continue;
      const vec3 vsR = reflect(vsV, vsN);
      const SslrHit r = positionMethod ? sslrTracePositionBuffer(proj, surf, pb, vsP, vsV, vsR)
                        : settings.method == Method::ScreenSpaceDDA
                            ? sslrTraceDda(proj, surf, frame.value().dda, px, vsP, vsR)
                        : settings.method == Method::FidelityFxSssr
                            ? sslrTraceFfx(proj, surf, t, px, vsP, vsR)
                            : sslrTraceDepthOnly(proj, surf, t, px, vsP, vsR);
      float* o = &hit.at(x, y, 0);
      o[0] = r.uvHit.x;
      o[1] = r.uvHit.y;
      o[2] = r.confidence;
      o[3] = r.L;
    }
  tG = nullptr;
  tPyramid.clear();
  return hit;
}

Image idealReflection(const CpuGBuffer& g, const Image& color, const GroundTruth& truth, const FrameInputs& in,
                      const Settings& settings) {
  using namespace sslr::shared;
  const int w = g.depth->width, h = g.depth->height;
  Image out{w, h, 3, std::vector<float>(static_cast<size_t>(w) * h * 3, 0.0f)};
  auto frame = frameConstants(in, settings, w, h);
  if (!frame || truth.width != w || truth.height != h) return out;
  const SslrProjection proj = frame.value().proj;
  const SslrSurface surf = frame.value().surface;
  const SslrTraceParams t = frame.value().trace;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const TruthPixel& tp = truth.pixels[static_cast<size_t>(y) * w + x];
      if (tp.cls != TruthClass::Visible) continue;
      const ivec2 px(x, y);
      const Image& n = *g.normalPacked;
      const vec4 texel(n.at(x, y, 0), n.at(x, y, 1), n.at(x, y, 2), n.at(x, y, 3));
      vec3 vsP, vsN;
      if (!sslrSurfaceFromDepth(proj, surf, px, g.depth->at(x, y, 0), vsP) || !sslrDecodeNormal(surf, texel, vsN))
        continue;
      const vec3 vsV = sslrViewDirection(proj, vsP);
      const float cosVN = dot(-vsV, vsN);
      if (!(cosVN > 0.0f)) continue;
      SslrHit hit = sslrNoHit(SSLR_STATUS_HIT);
      hit.uvHit = tp.uvHit;
      hit.L = tp.length;
      hit.confidence = 1.0f;
      hit.fade = 1.0f;
      const SslrWeights wt = sslrReflectionWeights(proj, surf, t, hit, vsP, vsV, reflect(vsV, vsN), cosVN,
                                                   sslrReflectance(surf, texel), sslrRoughness(surf, texel));
      const glm::vec3 c = sampleBilinear(color, tp.uvHit) * wt.reflection;
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = c[k];
    }
  return out;
}

}  // namespace sslr::host
