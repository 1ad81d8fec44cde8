// Triangle meshes (patches, meshed implicits, hole filling): world-space positions and normals,
// a per-vertex base colour; lit in mesh.frag like the tracer's hits (core/trace/shading.h).

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aColor;

uniform mat4 uViewProj;

out vec3 vPosition;
out vec3 vNormal;
out vec3 vColor;

void main() {
  gl_Position = uViewProj * vec4(aPosition, 1.0);
  vPosition = aPosition;
  vNormal = aNormal;
  vColor = aColor;
}
