// Composite: final = existing colour + resolved reflection (additive blending; alpha kept).
#include "sslr_shared.h"

layout(binding = 4) uniform sampler2D uResolved;
layout(location = 0) out vec4 oColor;

void main() {
  oColor = vec4(texelFetch(uResolved, ivec2(gl_FragCoord.xy), 0).rgb, 0.0f);
}
