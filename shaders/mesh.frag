// Shading of core/trace/shading.h: base × (ambient + Σ Iₖ max(0, ns·Lₖ)), ns facing the viewer; the
// back side (seen against its normal) takes the back colour so inside-out regions stand out.

in vec3 vPosition;
in vec3 vNormal;
in vec3 vColor;

uniform vec3 uEye;
uniform vec3 uForward;
uniform int uOrtho;
uniform vec3 uLightDir[2];
uniform float uLightIntensity[2];
uniform float uAmbient;
uniform vec3 uBackColor;

layout(location = 0) out vec4 outColor;

void main() {
  vec3 d = uOrtho == 1 ? uForward : normalize(vPosition - uEye);
  vec3 n = normalize(vNormal);
  bool back = dot(n, d) > 0.0;
  vec3 ns = back ? -n : n;
  vec3 base = back ? uBackColor : vColor;
  float light = uAmbient;
  for (int k = 0; k < 2; ++k) light += uLightIntensity[k] * max(0.0, dot(ns, uLightDir[k]));
  outColor = vec4(clamp(base * light, 0.0, 1.0), 1.0);
}
