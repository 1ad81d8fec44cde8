// Overlay points and lines (samples, normals, bounds box) in world space, nudged towards the
// eye by uBias world units so samples lying on the surface are not hidden by its depth.

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aColor;

uniform mat4 uViewProj;
uniform vec3 uEye;
uniform vec3 uForward;
uniform int uOrtho;
uniform float uBias;
uniform float uPointSize;

out vec4 vColor;

void main() {
  vec3 toEye = uOrtho == 1 ? -uForward : normalize(uEye - aPosition);
  gl_Position = uViewProj * vec4(aPosition + uBias * toEye, 1.0);
  gl_PointSize = uPointSize;
  vColor = aColor;
}
