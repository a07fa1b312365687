// Composite, drawn with additive blending (alpha kept):
//   default:                the resolved reflection's rgb (final = existing + reflection);
//   SSLR_COMPOSITE_FALLBACK: coverage x the host's fallback specular, drawn first with a reverse
//                            subtraction (final = existing - coverage x fallback), see composite.cpp.
#include "sslr_shared.h"

layout(binding = SSLR_UNIT_COMPOSITE_RESOLVED) uniform SSLR_SAMPLER uResolved;  // rgb = reflection, a = coverage
#if SSLR_VIEWS > 1
layout(location = SSLR_COMPOSITE_VIEW_LOCATION) uniform int uView;  // its layer drawn (the host's fallback: that view's)
#endif
#ifdef SSLR_COMPOSITE_FALLBACK
layout(binding = SSLR_UNIT_COMPOSITE_FALLBACK) uniform sampler2D uFallbackSpecular;
#endif
layout(location = 0) out vec4 oColor;

void main() {
  SSLR_SET_VIEW(uView);
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 resolved = texelFetch(uResolved, SSLR_AT(px), 0);
#ifdef SSLR_COMPOSITE_FALLBACK
  vec3 fallback = texelFetch(uFallbackSpecular, px, 0).rgb;
  // A poisoned fallback texel must not spread NaN into the host's frame.
  if (any(isnan(fallback)) || any(isinf(fallback))) fallback = vec3(0.0f);
  oColor = vec4(resolved.a * max(fallback, vec3(0.0f)), 0.0f);
#else
  oColor = vec4(resolved.rgb, 0.0f);
#endif
}
