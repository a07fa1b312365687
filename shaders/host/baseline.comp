// The "physical limit" of a screen-space pass, for the benchmark: read the G-buffer once
// (depth, normal, colour) and write one RGBA16F texel per pixel, nothing else.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uDepth;
layout(binding = 1) uniform sampler2D uNormal;
layout(binding = 2) uniform sampler2D uColor;
layout(binding = 0, rgba16f) uniform writeonly image2D uOut;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, imageSize(uOut)))) return;
  float depth = texelFetch(uDepth, px, 0).r;
  vec4 normal = texelFetch(uNormal, px, 0);
  vec3 color = texelFetch(uColor, px, 0).rgb;
  // Uses every input so nothing is optimized away.
  imageStore(uOut, px, vec4(color * normal.w, depth + normal.x));
}
