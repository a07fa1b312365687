// Host G-buffer pass: lit colour, packed normal + material, optional exact view position.
#include "sslr_shared.h"
#include "lighting.h"

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
layout(location = 12) uniform vec3 uSky;              // the background colour: the environment
layout(location = 13) uniform int uOrthographic;
layout(binding = 0) uniform sampler2D uBaseColorTexture;

layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out vec4 oPosition;
layout(location = 3) out vec4 oFallbackSpecular;

float unorm(float v, float steps) { return roundEven(clamp(v, 0.0f, 1.0f) * steps) / steps; }

void main() {
  // Vertex normals that a singular node transform flattened to zero take the face's own normal,
  // turned towards the eye (derivatives outside the branch: they need uniform control flow).
  vec3 vsFaceNormal = cross(dFdx(vVsPosition), dFdy(vVsPosition));
  float normalLength2 = dot(vVsNormal, vVsNormal);
  vec3 n;
  if (normalLength2 > 1e-30f) {
    n = vVsNormal * inversesqrt(normalLength2);
    if (!gl_FrontFacing) n = -n;  // two-sided: the visible side's normal
  } else {
    n = normalize(vsFaceNormal);
    if (dot(n, uOrthographic != 0 ? vec3(0.0f, 0.0f, 1.0f) : -vVsPosition) < 0.0f) n = -n;
  }
  vec3 base = uBaseColor;
  if (uHasTexture != 0) base *= texture(uBaseColorTexture, vUv).rgb;
  // Deterministic lighting (host/lighting.h) and the fallback specular, the stand-in for an engine's
  // probes / IBL.
  vec3 vsV = uOrthographic != 0 ? vec3(0.0f, 0.0f, 1.0f) : normalize(-vVsPosition);
  vec3 fallback = sslrHostFallbackSpecular(uReflectance, vsV, n, uVsUp, uSky);
  oFallbackSpecular = vec4(fallback, 1.0f);
  oColor = vec4(sslrHostLitColor(base, uMetallic, uEmission, n, uVsLightDirection, uVsUp) + fallback, 1.0f);
  // Material values quantized here, halves to even: a value on a half-step (roughness 0.5 is
  // 32767.5 of RGBA16's steps, 0.3 is 19660.5 in float) is rounded by each driver its own way, and
  // the glossy scene's panels sit on the presets' cutoffs (an H100 traced the 0.5 panel at cutoff
  // 0.5, llvmpipe did not). Half to even is what llvmpipe does.
  if (uNormalEncoding == SSLR_NORMALS_OCTAHEDRAL)
    oNormal = vec4(sslrOctEncode(n), unorm(uRoughness, 65535.0f), unorm(uReflectance, 65535.0f));
  else
    oNormal = vec4(n * 0.5f + 0.5f, unorm(uReflectance, 255.0f));
  oPosition = vec4(vVsPosition, 1.0f);
}
