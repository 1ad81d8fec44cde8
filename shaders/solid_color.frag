#version 450 core
// A single colour everywhere (tests, backgrounds).

uniform vec4 u_color;

out vec4 frag_color;

void main() {
  frag_color = u_color;
}
