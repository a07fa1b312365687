// host/lighting.h - the tools' G-buffer lighting, shared by the G-buffer pass (host/gbuffer.frag)
// and the ray-traced reference that shades a reflected point the same way
// (src/host/truth/reference_image.cpp): one directional light, a sky/ground ambient, emission, and
// a fallback specular standing in for an engine's probes.
#ifndef SSLR_HOST_LIGHTING_H
#define SSLR_HOST_LIGHTING_H

#include "sslr_shared.h"

#ifdef __cplusplus
namespace sslr::shared {
#endif

// The fallback environment in direction vsR: the sky above the horizon, a dim ground below it.
SSLR_FN vec3 sslrHostEnvironment(vec3 vsR, vec3 vsUp, vec3 sky) {
  return mix(0.25f * sky, sky, smoothstep(-0.05f, 0.05f, dot(vsR, vsUp)));
}

// The fallback specular of a surface seen along vsV (towards the eye): the environment in the
// mirror direction times the Fresnel term sslr's default (Classic) mode uses, so that a traced
// reflection and the fallback meet without a seam.
SSLR_FN vec3 sslrHostFallbackSpecular(float reflectance, vec3 vsV, vec3 n, vec3 vsUp, vec3 sky) {
  vec3 environment = sslrHostEnvironment(reflect(-vsV, n), vsUp, sky);
  return reflectance * sslrFresnelClassic(max(dot(vsV, n), 0.0f)) * environment;
}

// The lit colour without the fallback: a directional light (vsLight: the direction it travels)
// and a sky/ground ambient; metals get little diffuse light, their look comes from reflections.
SSLR_FN vec3 sslrHostLitColor(vec3 base, float metallic, vec3 emission, vec3 n, vec3 vsLight, vec3 vsUp) {
  float diffuse = max(dot(n, -vsLight), 0.0f);
  float ambient = 0.18f + 0.12f * dot(n, vsUp);
  float kd = 1.0f - 0.85f * metallic;
  return base * kd * (0.85f * diffuse + ambient) + emission;
}

#ifdef __cplusplus
}  // namespace sslr::shared
#endif

#endif  // SSLR_HOST_LIGHTING_H
