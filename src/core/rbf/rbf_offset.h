#pragma once
// The plain RBF method with offset points (docs/maths.md, RBF-offset): centres pᵢ, pᵢ + δnᵢ, pᵢ − δnᵢ with
// values 0, +δ, −δ (δ = shift), f = Σⱼ wⱼ φ(‖x − cⱼ‖) + p(x).

#include "core/rbf/hrbf.h"

namespace hermite {

struct RbfOffsetOptions {
  Kernel kernel{KernelType::Cubic, 1.0};
  Polynomial polynomial = Polynomial::Linear;
  double smoothing = 0.0;  // λ ≥ 0, same sign rule as HRBF
  double shift = 0.01;     // δ > 0, in data units
  SolverChoice solver = SolverChoice::Auto;
  const CancelToken* cancel = nullptr;  // as HrbfOptions::cancel
};

template <int Dim>
class RbfOffsetModel : public RadialSum<Dim> {
 public:
  RbfOffsetModel() = default;
  RbfOffsetModel(Kernel kernel, Polynomial polynomial, Points<Dim> centres, Eigen::VectorXd weights,
                 Eigen::VectorXd poly, double shift, Vec<Dim> polyOrigin = Vec<Dim>::Zero())
      : RadialSum<Dim>(kernel, polynomial, std::move(centres), std::move(weights), Points<Dim>(),
                       std::move(poly), polyOrigin),
        shift_(shift) {}
  double shift() const { return shift_; }

 private:
  double shift_ = 0.01;
};

template <int Dim>
RbfOffsetModel<Dim> fitRbfOffset(const HermiteSamples<Dim>& samples, const RbfOffsetOptions& options,
                                 FitReport* report = nullptr);

}  // namespace hermite
