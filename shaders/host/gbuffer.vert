// Host G-buffer pass (tools only, not part of the library): transforms with matrices built in
// double on the CPU.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;

layout(location = 0) uniform mat4 uClipFromModel;
layout(location = 1) uniform mat4 uViewFromModel;
layout(location = 2) uniform mat3 uNormalViewFromModel;

out vec3 vVsPosition;
out vec3 vVsNormal;
out vec2 vUv;

void main() {
  vVsPosition = (uViewFromModel * vec4(aPosition, 1.0)).xyz;
  vVsNormal = uNormalViewFromModel * aNormal;
  vUv = aUv;
  gl_Position = uClipFromModel * vec4(aPosition, 1.0);
}
