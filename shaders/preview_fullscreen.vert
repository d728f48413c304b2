#version 330 core
// One triangle that covers the viewport (no vertex buffer: from gl_VertexID).
out vec2 uv;

void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  uv = p;
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
