// Exact mode of the implicit tracer: f(x) = Σ αⱼ φ(‖x − cⱼ‖) − βⱼ·∇φ(x − cⱼ) + p(x) summed per
// evaluation from SSBOs (RadialSum<3>: HRBF or RBF-offset; docs/maths.md), with per-brick
// Lipschitz bounds of the field. Coordinates are relative to uOrigin (the bounds centre) to keep
// cancellation small; centres and polynomial coefficients are uploaded in that frame.
//
// Precision: with EXACT_DOUBLE defined the sum is formed in double (ImplicitTracer chooses it
// when the terms that cancel into f are so large that float rounding would move the surface:
// RBF-offset dipoles, polyharmonic and cubic kernels over wide bounds). GLSL has no double
// exp / log, so that variant carries its own (exactDoubleExp, exactDoubleLog below).

#ifdef EXACT_DOUBLE
#define real double
#define real3 dvec3
#define real4 dvec4
#else
#define real float
#define real3 vec3
#define real4 vec4
#endif

layout(std430, binding = 0) readonly buffer Centres { real4 uCentreAlpha[]; };  // (c − origin, α)
layout(std430, binding = 1) readonly buffer Betas { real4 uBeta[]; };           // (β, 0)
uniform highp sampler3D uBricks;  // RGBA32F per brick; .zw = (L field, field may contain a zero)
uniform int uCount;      // N centres rounded up to a multiple of 4 (padding: α = β = 0)
uniform int uHasBeta;
uniform int uKernel;     // a KERNEL_* id, defined by the tracer from the kernel table (core/rbf/kernels.h)
uniform real uRadius;
uniform int uPolyCount;  // 0, 4 or 10
uniform real uPoly[10];  // in the shifted frame, order 1, x, y, z, xx, xy, xz, yy, yz, zz
uniform vec3 uOrigin;

float fieldValue(vec3 p);
vec3 fieldGradient(vec3 p);
vec2 brickInfo(ivec3 b);
vec3 shadingDirection(vec3 p) { return fieldGradient(p); }
bool hasDataAt(vec3 p) { return true; }  // one global sum of kernels: data everywhere

#include "trace_common.glsl"

#ifdef EXACT_DOUBLE
// Straight-line code (no loops: see uLoopBudget in trace_common.glsl).
// e^x to a few ulp for x ≤ 0 (the gaussian's argument): x = k ln2 + s, |s| ≤ ln2 / 2, e^s by
// its Taylor polynomial to s¹⁴/14! in Horner form (< 2e-16 relative there), then the exact
// scaling by 2^k.
double exactDoubleExp(double x) {
  if (x < -745.0LF) return 0.0LF;
  const double ln2Hi = 6.93147180369123816490e-01LF;  // ln 2 = hi + lo, hi with 11 zero bits
  const double ln2Lo = 1.90821492927058770002e-10LF;
  double k = floor(x * 1.44269504088896338700LF + 0.5LF);
  double s = (x - k * ln2Hi) - k * ln2Lo;
  double p = 1.0LF / 14.0LF;
  p = 1.0LF + s * p;
  p = 1.0LF + s * p / 13.0LF;
  p = 1.0LF + s * p / 12.0LF;
  p = 1.0LF + s * p / 11.0LF;
  p = 1.0LF + s * p / 10.0LF;
  p = 1.0LF + s * p / 9.0LF;
  p = 1.0LF + s * p / 8.0LF;
  p = 1.0LF + s * p / 7.0LF;
  p = 1.0LF + s * p / 6.0LF;
  p = 1.0LF + s * p / 5.0LF;
  p = 1.0LF + s * p / 4.0LF;
  p = 1.0LF + s * p / 3.0LF;
  p = 1.0LF + s * p / 2.0LF;
  p = 1.0LF + s * p;
  return ldexp(p, int(k));
}

// ln x for x > 0: x = m·2^e with m in [√½, √2), ln m = 2 atanh(t) = 2t(1 + t²/3 + t⁴/5 + …),
// t = (m − 1)/(m + 1), |t| ≤ 0.172: terms to t²² in Horner form (< 1e-17 relative).
double exactDoubleLog(double x) {
  int e;
  double m = frexp(x, e);  // m in [½, 1)
  if (m < 0.70710678118654752440LF) {
    m *= 2.0LF;
    e -= 1;
  }
  double t = (m - 1.0LF) / (m + 1.0LF);
  double u = t * t;
  double p = 1.0LF / 23.0LF;
  p = p * u + 1.0LF / 21.0LF;
  p = p * u + 1.0LF / 19.0LF;
  p = p * u + 1.0LF / 17.0LF;
  p = p * u + 1.0LF / 15.0LF;
  p = p * u + 1.0LF / 13.0LF;
  p = p * u + 1.0LF / 11.0LF;
  p = p * u + 1.0LF / 9.0LF;
  p = p * u + 1.0LF / 7.0LF;
  p = p * u + 1.0LF / 5.0LF;
  p = p * u + 1.0LF / 3.0LF;
  p = p * u + 1.0LF;
  return double(e) * 6.93147180559945309417e-01LF + 2.0LF * t * p;
}
#define realExp exactDoubleExp
#define realLog exactDoubleLog
#else
#define realExp exp
#define realLog log
#endif

// φ(x), a = φ′(x)/x, e = (φ″ − φ′/x)/x² (0 at x = 0) of the kernel (core/rbf/kernels.cpp).
real3 kernelTerms(real x) {
  real r = uRadius;
  real r2 = r * r;
  real3 terms = real3(0.0);
  if (uKernel == KERNEL_GAUSSIAN) {
    real p = realExp(-(x * x) / r2);
    terms = real3(p, -2.0 / r2 * p, 4.0 / (r2 * r2) * p);
  } else if (uKernel == KERNEL_WENDLAND) {
    real s = x / r;
    if (s < 1.0) {
      real u = 1.0 - s;
      real u3 = u * u * u;
      terms = real3(u3 * u * (4.0 * s + 1.0), -20.0 * u3 / r2, x > 0.0 ? 60.0 * u * u / (r2 * r * x) : 0.0);
    }
  } else if (uKernel == KERNEL_MULTIQUADRIC) {
    real p = sqrt(1.0 + x * x / r2);
    terms = real3(p, 1.0 / (r2 * p), -1.0 / (r2 * r2 * p * p * p));
  } else if (uKernel == KERNEL_INVERSE_MULTIQUADRIC) {
    real p = inversesqrt(1.0 + x * x / r2);
    real p3 = p * p * p;
    terms = real3(p, -p3 / r2, 3.0 * p3 * p * p / (r2 * r2));
  } else if (uKernel == KERNEL_CUBIC) {
    terms = real3(x * x * x, 3.0 * x, x > 0.0 ? 3.0 / x : 0.0);
  } else if (uKernel == KERNEL_POLYHARMONIC && x > 0.0) {
    real lx = realLog(x);
    real x2 = x * x;
    terms = real3(x2 * x2 * lx, x2 * (4.0 * lx + 1.0), 8.0 * lx + 6.0);
  }
  return terms;
}

// Adds centre j's terms at x (relative to the origin) to f and, when asked, to the gradient g.
void addCentre(int j, real3 x, bool withGradient, inout real f, inout real3 g) {
  real4 ca = uCentreAlpha[j];
  real3 d = x - ca.xyz;
  real dist = length(d);
  real3 k = kernelTerms(dist);
  f += ca.w * k.x;
  if (withGradient) g += ca.w * k.y * d;
  if (uHasBeta == 1) {
    real3 b = uBeta[j].xyz;
    real db = dot(d, b);
    f -= k.y * db;
    if (withGradient) g -= k.y * b + k.z * db * d;
  }
}

float evaluateField(vec3 p, bool withGradient, out vec3 gradient) {
  real3 x = real3(p) - real3(uOrigin);
  real f = 0.0;
  real3 g = real3(0.0);
  // Four centres per iteration (uCount is a multiple of 4; padding centres have α = β = 0), so
  // that one evaluation costs uCount / 4 iterations of the loop budget.
  for (int j = 0; j < uCount; j += 4) {
    addCentre(j, x, withGradient, f, g);
    addCentre(j + 1, x, withGradient, f, g);
    addCentre(j + 2, x, withGradient, f, g);
    addCentre(j + 3, x, withGradient, f, g);
  }
  gLoops += uCount / 4;
  if (uPolyCount >= 4) {
    f += uPoly[0] + uPoly[1] * x.x + uPoly[2] * x.y + uPoly[3] * x.z;
    g += real3(uPoly[1], uPoly[2], uPoly[3]);
  }
  if (uPolyCount >= 10) {
    f += uPoly[4] * x.x * x.x + uPoly[5] * x.x * x.y + uPoly[6] * x.x * x.z + uPoly[7] * x.y * x.y +
         uPoly[8] * x.y * x.z + uPoly[9] * x.z * x.z;
    g += real3(2.0 * uPoly[4] * x.x + uPoly[5] * x.y + uPoly[6] * x.z,
               uPoly[5] * x.x + 2.0 * uPoly[7] * x.y + uPoly[8] * x.z,
               uPoly[6] * x.x + uPoly[8] * x.y + 2.0 * uPoly[9] * x.z);
  }
  gradient = vec3(g);
  return float(f);
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
