// Viewer: one full-screen triangle.
out vec2 vUv;

void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  vUv = p;
  gl_Position = vec4(p * 2.0f - 1.0f, 0.0f, 1.0f);
}
