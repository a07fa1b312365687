// shared/temporal.h - Temporal reuse: history keys and reprojection.
// Part of sslr_shared.h, the C++/GLSL source of truth (see its header for the conventions).
#ifndef SSLR_SHARED_TEMPORAL_H
#define SSLR_SHARED_TEMPORAL_H

#include "language.h"
#include "projection.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// ---- Temporal reuse ----------------------------------------------------------------------------
// The history key of a view-space point: what tells a surface from the one that hid it. Under a
// perspective projection the view depth (clip w), under an orthographic one NDC z (linear in
// depth there, and clip w is 1). Always > 0 for visible geometry (0 marks "no history").
SSLR_FN float sslrHistoryKeyFromClip(int orthographic, vec4 clip) {
  return orthographic != 0 ? 2.0f + clip.z / clip.w : clip.w;
}

// This frame's key of view-space point P (the same quantity as sslrHistoryKeyFromClip).
SSLR_FN float sslrHistoryKey(SslrProjection p, vec3 vsP) {
  return sslrOrthographic(p) ? 2.0f + sslrNdcFromView(p, vsP).z : sslrClipW(p, vsP);
}

// Where view-space point P (this frame) was in the previous frame: its uv there and its key
// there. False when it was behind the previous camera or outside its screen.
SSLR_FN bool sslrReproject(SslrProjection p, mat4 previousClipFromView, vec3 vsP, SSLR_OUT(vec2) uvPrevious,
                           SSLR_OUT(float) keyPrevious) {
  vec4 clip = previousClipFromView * vec4(vsP, 1.0f);
  uvPrevious = vec2(-1.0f);
  keyPrevious = 0.0f;
  if (!(clip.w > 0.0f)) return false;
  uvPrevious = sslrUvFromNdc(vec2(clip.x, clip.y) / clip.w);
  keyPrevious = sslrHistoryKeyFromClip(sslrOrthographic(p) ? 1 : 0, clip);
  return sslrInsideUv(uvPrevious);
}

// Where a mirror's reflection was in the previous frame. The reflection of hit Q seen at P
// (normal N, reflected length L) is the virtual point V = P + L * (P - eye) / |P - eye|, behind
// the mirror; the previous camera saw it through the mirror plane at X, where the segment from
// its eye to V crosses the plane. X is returned (view space, this frame); false when the previous
// eye is unknown or on the plane's far side.
SSLR_FN bool sslrVirtualPointOnMirror(vec4 previousEye, vec3 vsP, vec3 vsN, float L, SSLR_OUT(vec3) vsX) {
  vsX = vsP;
  if (previousEye.w == 0.0f || !(L > 0.0f)) return false;
  vec3 eye = vec3(previousEye.x, previousEye.y, previousEye.z);
  vec3 vsVirtual = vsP + normalize(vsP) * L;
  vec3 d = vsVirtual - eye;
  float denom = dot(d, vsN);
  float t = dot(vsP - eye, vsN) / denom;
  if (!(dot(eye - vsP, vsN) > 0.0f) || !(t > 0.0f && t < 1.0f)) return false;
  vsX = eye + d * t;
  return true;
}

// Whether a stored history key belongs to the same surface as the expected one.
SSLR_FN bool sslrHistoryKeyMatches(float stored, float expected, float tolerance) {
  return stored > 0.0f && abs(stored - expected) <= tolerance * expected;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_SHARED_TEMPORAL_H
