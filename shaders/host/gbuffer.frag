// Host G-buffer pass: lit colour, packed normal + material, optional exact view position.
#include "sslr_shared.h"

in vec3 vVsPosition;
in vec3 vVsNormal;
in vec2 vUv;

layout(location = 3) uniform vec3 uBaseColor;
layout(location = 4) uniform float uMetallic;
layout(location = 5) uniform float uRoughness;
layout(location = 6) uniform float uReflectance;
layout(location = 7) uniform vec3 uEmission;  // emitted colour, added to the lit colour
layout(location = 8) uniform int uHasTexture;
layout(location = 9) uniform vec3 uVsLightDirection;  // direction the light travels, view space
layout(location = 10) uniform vec3 uVsUp;             // world up in view space (sky ambient)
layout(location = 11) uniform int uNormalEncoding;    // SSLR_NORMALS_*
layout(binding = 0) uniform sampler2D uBaseColorTexture;

layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out vec4 oPosition;

void main() {
  vec3 n = normalize(vVsNormal);
  if (!gl_FrontFacing) n = -n;  // two-sided: the visible side's normal
  vec3 base = uBaseColor;
  if (uHasTexture != 0) base *= texture(uBaseColorTexture, vUv).rgb;
  // Deterministic lighting: one directional light plus a sky/ground ambient. Metals get little
  // diffuse light, so their look comes from the reflection sslr adds.
  float diffuse = max(dot(n, -uVsLightDirection), 0.0f);
  float ambient = 0.18f + 0.12f * dot(n, uVsUp);
  float kd = 1.0f - 0.85f * uMetallic;
  oColor = vec4(base * kd * (0.85f * diffuse + ambient) + uEmission, 1.0f);
  if (uNormalEncoding == SSLR_NORMALS_OCTAHEDRAL)
    oNormal = vec4(sslrOctEncode(n), uRoughness, uReflectance);
  else
    oNormal = vec4(n * 0.5f + 0.5f, uReflectance);
  oPosition = vec4(vVsPosition, 1.0f);
}
