// sslr_trace_position.h - the position-buffer SSR of "3D Game Shaders For Beginners" (screen
// space reflection chapter), for side-by-side comparison. Shared by the GPU pass and the CPU.
//
// The includer defines:  bool sslrLoadPosition(ivec2 px, out vec4 vsPosition);
// (the stored view-space position; w = 1 on geometry, 0 on the background).
#ifndef SSLR_TRACE_POSITION_H
#define SSLR_TRACE_POSITION_H

#include "sslr_trace.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// View distance along -z (both projections: the tutorial's "view distance" is its depth axis).
SSLR_FN float sslrDepthAlongView(vec3 vsPos) { return -vsPos.z; }

// The ray's view distance at fraction `search` of the screen-space segment: perspective-correct
// (1/z is linear in screen space), or linear for orthographic projections.
SSLR_FN float sslrRayDistanceAt(SslrProjection p, float startDist, float endDist, float search) {
  return sslrOrthographic(p) ? mix(startDist, endDist, search)
                             : (startDist * endDist) / mix(endDist, startDist, search);
}

// Coarse march from the ray's start to its end (start + R maxDistance) along the larger screen
// axis, `resolution` of the pixels, with perspective-correct depth; then `steps` of bisection
// between the last miss and the hit. Guards not in the tutorial (they only stop it from reading
// outside the screen or dividing by zero): the end point is pulled in front of the camera, the
// march stops at the screen border, and its step count is capped.
// The march's end point, maxDistance along the ray; an end point behind the camera would flip
// when projected: the segment is clipped in front of it.
SSLR_FN vec3 sslrPositionBufferEnd(SslrProjection p, vec3 startView, vec3 vsR, float maxDistance) {
  vec3 endView = startView + vsR * maxDistance;
  if (sslrOrthographic(p)) return endView;
  float minDist = 1e-3f * max(sslrDepthAlongView(startView), 1e-6f);
  if (sslrDepthAlongView(endView) < minDist) {
    float tClip = (sslrDepthAlongView(startView) - minDist) /
                  (sslrDepthAlongView(startView) - sslrDepthAlongView(endView));
    endView = startView + (endView - startView) * tClip;
  }
  return endView;
}

SSLR_FN SslrHit sslrTracePositionBuffer(SslrProjection p, SslrSurface s, SslrPositionParams pb,
                                        vec3 vsP, vec3 vsV, vec3 vsR) {
  SslrHit hit = sslrNoHit(SSLR_STATUS_MISS);

  vec2 sizePx = vec2(s.width, s.height);
  vec3 startView = vsP;
  vec3 endView = sslrPositionBufferEnd(p, startView, vsR, pb.maxDistance);
  vec3 ndcStart = sslrNdcFromView(p, startView);
  vec3 ndcEnd = sslrNdcFromView(p, endView);
  vec2 startFrag = sslrUvFromNdc(vec2(ndcStart.x, ndcStart.y)) * sizePx;
  vec2 endFrag = sslrUvFromNdc(vec2(ndcEnd.x, ndcEnd.y)) * sizePx;

  vec2 frag = startFrag;
  float deltaX = endFrag.x - startFrag.x;
  float deltaY = endFrag.y - startFrag.y;
  bool useX = abs(deltaX) >= abs(deltaY);
  float delta = (useX ? abs(deltaX) : abs(deltaY)) * clamp(pb.resolution, 0.0f, 1.0f);
  vec2 increment = vec2(deltaX, deltaY) / max(delta, 0.001f);

  float search0 = 0.0f;
  float search1 = 0.0f;
  int hit0 = 0;
  int hit1 = 0;
  float startDist = sslrDepthAlongView(startView);
  float endDist = sslrDepthAlongView(endView);
  float depth = pb.hitTolerance;
  vec4 positionTo = vec4(0.0f);
  int marchSteps = int(min(delta, 16384.0f));
  for (int i = 0; i < marchSteps; ++i) {
    frag += increment;
    if (!(frag.x >= 0.0f && frag.y >= 0.0f && frag.x < sizePx.x && frag.y < sizePx.y)) break;
    sslrLoadPosition(ivec2(floor(frag)), positionTo);
    hit.iterations += 1;
    search1 = useX ? (frag.x - startFrag.x) / deltaX : (frag.y - startFrag.y) / deltaY;
    search1 = clamp(search1, 0.0f, 1.0f);
    depth = sslrRayDistanceAt(p, startDist, endDist, search1) -
            sslrDepthAlongView(vec3(positionTo.x, positionTo.y, positionTo.z));
    if (positionTo.w > 0.0f && depth > 0.0f && depth < pb.hitTolerance) {
      hit0 = 1;
      break;
    } else {
      search0 = search1;
    }
  }
  search1 = search0 + ((search1 - search0) / 2.0f);
  int refineSteps = hit0 != 0 ? pb.steps : 0;
  for (int i = 0; i < refineSteps; ++i) {
    frag = mix(startFrag, endFrag, search1);
    sslrLoadPosition(clamp(ivec2(floor(frag)), ivec2(0), ivec2(sizePx) - 1), positionTo);
    hit.iterations += 1;
    depth = sslrRayDistanceAt(p, startDist, endDist, search1) -
            sslrDepthAlongView(vec3(positionTo.x, positionTo.y, positionTo.z));
    if (positionTo.w > 0.0f && depth > 0.0f && depth < pb.hitTolerance) {
      hit1 = 1;
      search1 = search0 + ((search1 - search0) / 2.0f);
    } else {
      float temp = search1;
      search1 = search1 + ((search1 - search0) / 2.0f);
      search0 = temp;
    }
  }
  vec2 uv = frag / sizePx;
  bool onScreen = sslrInsideUv(uv);
  hit.uvHit = clamp(uv, vec2(0.0f), vec2(1.0f));
  hit.L = length(vec3(positionTo.x, positionTo.y, positionTo.z) - vsP);
  // The tutorial's visibility: hit * position.w * (1 - max(dot(-V, R), 0)) *
  // (1 - depth/thickness) * (1 - distance/maxDistance) * on-screen. The hit decision (hit,
  // w, on-screen) is the confidence; the three fades are its weight (hit.fade), as sslr's own
  // screen-edge fade is.
  bool isHit = hit1 != 0 && positionTo.w > 0.0f && onScreen;
  hit.confidence = isHit ? 1.0f : 0.0f;
  hit.fade = isHit ? sslrSaturate((1.0f - max(dot(-vsV, vsR), 0.0f)) *
                                  (1.0f - clamp(depth / pb.hitTolerance, 0.0f, 1.0f)) *
                                  (1.0f - clamp(hit.L / pb.maxDistance, 0.0f, 1.0f)))
                   : 0.0f;
  hit.status = isHit ? SSLR_STATUS_HIT : (onScreen ? SSLR_STATUS_MISS : SSLR_STATUS_OFF_SCREEN);
  return hit;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_TRACE_POSITION_H
