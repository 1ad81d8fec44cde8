// Flat overlay colour; round points when uRoundPoints is set.

in vec4 vColor;
uniform int uRoundPoints;
layout(location = 0) out vec4 outColor;

void main() {
  if (uRoundPoints == 1 && length(gl_PointCoord - vec2(0.5)) > 0.5) discard;
  outColor = vColor;
}
