// Exact mode of the implicit tracer: f(x) = Σ αⱼ φ(‖x − cⱼ‖) − βⱼ·∇φ(x − cⱼ) + p(x) summed per
// evaluation from SSBOs (RadialSum<3>: HRBF or RBF-offset; DESIGN.md §3), with per-brick
// Lipschitz bounds of the field. Coordinates are relative to uOrigin (the bounds centre) to keep
// float cancellation small; centres and polynomial coefficients are uploaded in that frame.

layout(std430, binding = 0) readonly buffer Centres { vec4 uCentreAlpha[]; };  // (c − origin, α)
layout(std430, binding = 1) readonly buffer Betas { vec4 uBeta[]; };           // (β, 0)
uniform highp sampler3D uBricks;  // RGBA32F per brick; .zw = (L field, field may contain a zero)
uniform int uCount;      // N centres
uniform int uHasBeta;
uniform int uKernel;     // KernelType order: gaussian, wendland, multiquadric, inverse-mq, cubic, polyharmonic
uniform float uRadius;
uniform int uPolyCount;  // 0, 4 or 10
uniform float uPoly[10]; // in the shifted frame, order 1, x, y, z, xx, xy, xz, yy, yz, zz
uniform vec3 uOrigin;

float fieldValue(vec3 p);
vec3 fieldGradient(vec3 p);
vec2 brickInfo(ivec3 b);

#include "trace_common.glsl"

// φ(x), a = φ′(x)/x, e = (φ″ − φ′/x)/x² (0 at x = 0) of the kernel (core/kernels.cpp).
vec3 kernelTerms(float x) {
  float r = uRadius;
  float r2 = r * r;
  if (uKernel == 0) {
    float p = exp(-(x * x) / r2);
    return vec3(p, -2.0 / r2 * p, 4.0 / (r2 * r2) * p);
  } else if (uKernel == 1) {
    float s = x / r;
    if (s >= 1.0) return vec3(0.0);
    float u = 1.0 - s;
    float u3 = u * u * u;
    return vec3(u3 * u * (4.0 * s + 1.0), -20.0 * u3 / r2, x > 0.0 ? 60.0 * u * u / (r2 * r * x) : 0.0);
  } else if (uKernel == 2) {
    float p = sqrt(1.0 + x * x / r2);
    return vec3(p, 1.0 / (r2 * p), -1.0 / (r2 * r2 * p * p * p));
  } else if (uKernel == 3) {
    float p = inversesqrt(1.0 + x * x / r2);
    float p3 = p * p * p;
    return vec3(p, -p3 / r2, 3.0 * p3 * p * p / (r2 * r2));
  } else if (uKernel == 4) {
    return vec3(x * x * x, 3.0 * x, x > 0.0 ? 3.0 / x : 0.0);
  } else {
    if (!(x > 0.0)) return vec3(0.0);
    float lx = log(x);
    float x2 = x * x;
    return vec3(x2 * x2 * lx, x2 * (4.0 * lx + 1.0), 8.0 * lx + 6.0);
  }
}

float evaluateField(vec3 p, bool withGradient, out vec3 g) {
  vec3 x = p - uOrigin;
  float f = 0.0;
  g = vec3(0.0);
  for (int j = 0; j < uCount; ++j) {
    vec4 ca = uCentreAlpha[j];
    vec3 d = x - ca.xyz;
    float dist = length(d);
    vec3 k = kernelTerms(dist);
    f += ca.w * k.x;
    if (withGradient) g += ca.w * k.y * d;
    if (uHasBeta == 1) {
      vec3 b = uBeta[j].xyz;
      float db = dot(d, b);
      f -= k.y * db;
      if (withGradient) g -= k.y * b + k.z * db * d;
    }
  }
  if (uPolyCount >= 4) {
    f += uPoly[0] + uPoly[1] * x.x + uPoly[2] * x.y + uPoly[3] * x.z;
    g += vec3(uPoly[1], uPoly[2], uPoly[3]);
  }
  if (uPolyCount >= 10) {
    f += uPoly[4] * x.x * x.x + uPoly[5] * x.x * x.y + uPoly[6] * x.x * x.z + uPoly[7] * x.y * x.y +
         uPoly[8] * x.y * x.z + uPoly[9] * x.z * x.z;
    g += vec3(2.0 * uPoly[4] * x.x + uPoly[5] * x.y + uPoly[6] * x.z,
              uPoly[5] * x.x + 2.0 * uPoly[7] * x.y + uPoly[8] * x.z,
              uPoly[6] * x.x + uPoly[8] * x.y + 2.0 * uPoly[9] * x.z);
  }
  return f;
}

float fieldValue(vec3 p) {
  vec3 g;
  return evaluateField(p, false, g);
}

vec3 fieldGradient(vec3 p) {
  vec3 g;
  evaluateField(p, true, g);
  return g;
}

vec2 brickInfo(ivec3 b) { return texelFetch(uBricks, b, 0).zw; }

