#version 450 core
// One triangle covering the viewport, drawn with glDrawArrays(GL_TRIANGLES, 0, 3) and an empty
// vertex array. v_uv is (0,0) at the bottom-left and (1,1) at the top-right of the viewport.

out vec2 v_uv;

void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));  // (0,0) (2,0) (0,2)
  v_uv = corner;
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
