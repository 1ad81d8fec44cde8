#pragma once
// Radial kernels φ(x), x = distance, and the factors of their gradient and Hessian (docs/maths.md, Kernels).
//
// For φ(‖d‖) with x = ‖d‖:
//   ∇φ  = a(x)·d                      a = φ′(x)/x
//   Hφ  = a(x)·I + e(x)·d dᵀ          e = b/x² = a′(x)/x,  b = φ″ − φ′/x
//   ∂³φ = e·(dᵢδⱼₖ + dⱼδᵢₖ + dₖδᵢⱼ) + g(x)·dᵢdⱼdₖ,    g = e′(x)/x
// a and b have finite limits at x = 0 for all six kernels. e and g may diverge at 0 (cubic,
// wendland, polyharmonic) but always multiply enough factors of d to vanish there, so at x = 0
// exactly they are reported as 0 and every product they enter is then the exact limit.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hermite {

enum class KernelType { Gaussian, Wendland, Multiquadric, InverseMultiquadric, Cubic, Polyharmonic };

// The one table of the kernels' identities: the enum, the scene-file name, and the id and macro
// name the shaders use (the tracer injects `#define <macro> <id>` and sets the uniform uKernel
// to the id). Rows are in enum order, so a kernel's id is its row.
struct KernelInfo {
  KernelType type;
  std::string_view name;
  std::string_view shaderMacro;
  int id;
};
inline constexpr std::array<KernelInfo, 6> kKernelTable{{
    {KernelType::Gaussian, "gaussian", "KERNEL_GAUSSIAN", 0},
    {KernelType::Wendland, "wendland", "KERNEL_WENDLAND", 1},
    {KernelType::Multiquadric, "multiquadric", "KERNEL_MULTIQUADRIC", 2},
    {KernelType::InverseMultiquadric, "inverse-multiquadric", "KERNEL_INVERSE_MULTIQUADRIC", 3},
    {KernelType::Cubic, "cubic", "KERNEL_CUBIC", 4},
    {KernelType::Polyharmonic, "polyharmonic", "KERNEL_POLYHARMONIC", 5},
}};
const KernelInfo& kernelInfo(KernelType t);

// φ and its derivative factors at one distance.
struct RadialTerms {
  double phi = 0;   // φ(x)
  double dphi = 0;  // φ′(x)
  double a = 0;     // φ′(x)/x        (finite at 0)
  double b = 0;     // φ″(x) − φ′(x)/x (0 at 0)
  double e = 0;     // b/x²           (0 reported at x = 0)
  double g = 0;     // e′(x)/x        (0 reported at x = 0)
  double ddphi() const { return a + b; }  // φ″(x)
};

// Upper bounds of the radial factors over a distance interval, for Lipschitz bounds.
struct RadialBounds {
  double dphi = 0;     // sup |φ′(x)|
  double hessian = 0;  // sup max(|a(x)|, |φ″(x)|): the spectral norm of Hφ
};

struct Kernel {
  KernelType type = KernelType::Cubic;
  double radius = 1.0;  // r, in data units; ignored by cubic and polyharmonic

  RadialTerms terms(double x) const;
  double phi(double x) const { return terms(x).phi; }
  // Bounds over x ∈ [lo, hi] (0 ≤ lo ≤ hi): exact, from the endpoints and the kernel's
  // interior critical points.
  RadialBounds bounds(double lo, double hi) const;

  bool usesRadius() const;
  // Order of conditional positive definiteness; a polynomial of degree ≥ order − 1 is needed.
  int cpdOrder() const;
  // +1 for conditionally positive definite kernels, −1 for conditionally negative definite
  // ones (multiquadric, polyharmonic). Smoothing λ enters the diagonal as smoothingSign()·λ.
  double smoothingSign() const;
  // True when the kernel matrix alone is strictly positive definite (order 0).
  bool strictlyPositiveDefinite() const { return cpdOrder() == 0; }
  // Support radius in data units (infinity for global kernels).
  double supportRadius() const;
};

// The scene-file names: gaussian, wendland, multiquadric, inverse-multiquadric, cubic, polyharmonic.
std::string_view kernelName(KernelType t);
const std::vector<KernelType>& allKernelTypes();

// Parses a kernel name. Throws InputError naming the valid kernels; kernels that cannot carry
// Hermite data (thin-plate x² ln x, linear x: φ′(x)/x has no limit at 0) are rejected with
// that reason.
KernelType parseKernelType(std::string_view name);

}  // namespace hermite
