// Viewer: shows one channel set of a texture per side of the split (left: view A, right: view B)
// as sRGB: the final image, a colour buffer, or a debug quantity as grey or false colour.
in vec2 vUv;

layout(binding = 0) uniform sampler2D uViewA;
layout(binding = 1) uniform sampler2D uViewB;
layout(location = 0) uniform int uMode;     // PRESENT_* below
layout(location = 1) uniform float uSplit;  // fraction of the width showing view A
layout(location = 2) uniform float uScale;  // divides the shown quantity (L, iterations)
layout(location = 0) out vec4 oColor;

#define PRESENT_RGB 0        // rgb as colour (final, reflection, resolved, error map)
#define PRESENT_ALPHA 1      // alpha as grey (blur weight, coverage)
#define PRESENT_BLUE 2       // b as grey (hit confidence)
#define PRESENT_ALPHA_SCALED 3  // a / scale (reflected length L)
#define PRESENT_RED_SCALED 4    // r / scale (iterations)
#define PRESENT_RG 5         // rg as colour (hit uv)

vec3 linearToSrgb(vec3 c) {
  c = clamp(c, vec3(0.0f), vec3(1.0f));
  return mix(c * 12.92f, 1.055f * pow(c, vec3(1.0f / 2.4f)) - 0.055f, step(vec3(0.0031308f), c));
}

void main() {
  bool left = vUv.x < uSplit;
  vec4 t = left ? texture(uViewA, vUv) : texture(uViewB, vUv);
  vec3 c;
  if (uMode == PRESENT_ALPHA) c = vec3(t.a);
  else if (uMode == PRESENT_BLUE) c = vec3(t.b);
  else if (uMode == PRESENT_ALPHA_SCALED) c = vec3(t.a / uScale);
  else if (uMode == PRESENT_RED_SCALED) c = vec3(t.r / uScale);
  else if (uMode == PRESENT_RG) c = vec3(t.rg, 0.0f);
  else c = t.rgb;
  oColor = vec4(linearToSrgb(c), 1.0f);
  // The split line.
  if (uSplit > 0.0f && uSplit < 1.0f && abs(gl_FragCoord.x - uSplit * float(textureSize(uViewA, 0).x)) < 1.0f)
    oColor = vec4(1.0f, 1.0f, 1.0f, 1.0f);
}
