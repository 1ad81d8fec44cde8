#pragma once
// A field whose sign the samples' winding number overrules inside a guard region (docs/maths.md,
// "Stray pockets"). Inside the region, where w(x) is above kGuardInside (inside the sampled
// surface) or below kGuardOutside (outside) and f has the other sign, f, ∇f and the Hessian
// change sign; elsewhere the field is the inner one. The region is a union of balls
// around points where a contour strayed from the data; the Lipschitz bound is infinite over
// boxes that meet it, so the marching cubes' octree evaluates f at every grid point there.

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/base/implicit_field.h"
#include "core/points/cloud_winding.h"

namespace hermite {

// A winding number above kGuardInside or below kGuardOutside is decided: a vertex there that
// strayed from the samples is a stray (stray_pockets.h), and a guard overrules f there. Well off
// the ½ that w has on the surface, yet near enough to it that a repaired dent or bulge ends
// within about a spacing of the samples: below (above) randomly placed samples w can stay under
// 0.85 (over 0.15) more than a spacing deep (docs/maths.md, "Stray pockets").
inline constexpr double kGuardInside = 0.75;
inline constexpr double kGuardOutside = 0.25;

inline bool windingDecided(double w) { return w > kGuardInside || w < kGuardOutside; }
// Whether f's sign disagrees with a decided w (f > 0 where w says inside, f < 0 where it says
// outside): where a guard overrules f.
inline bool windingOverrules(double w, double f) { return (w > kGuardInside && f > 0) || (w < kGuardOutside && f < 0); }

// A union of balls of one radius, with a hash of cells of that size for the tests.
class GuardRegion {
 public:
  explicit GuardRegion(double radius) : radius_(radius) {}
  void add(const Vec<3>& centre);
  int size() const { return static_cast<int>(centres_.size()); }
  double radius() const { return radius_; }
  bool contains(const Vec<3>& x) const;
  // Whether some ball meets the box.
  bool touches(const Box<3>& box) const;

 private:
  std::int64_t key(const Eigen::Vector3i& cell) const;
  Eigen::Vector3i cellOf(const Vec<3>& x) const;

  double radius_;
  std::vector<Vec<3>> centres_;
  // Cell key → the centres whose ball may reach into that cell (each centre is listed in the 27
  // cells around its own).
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

class WindingGuardField : public ImplicitField<3> {
 public:
  // `inner` must outlive the field; `owned`, when given, is `inner` itself.
  WindingGuardField(const ImplicitField<3>& inner, std::shared_ptr<const CloudWinding<3>> winding, GuardRegion region,
                    std::unique_ptr<ImplicitField<3>> owned = nullptr);

  double evaluate(const Vec<3>& x, Vec<3>* g = nullptr, Mat<3>* H = nullptr) const override;
  void evaluateBatch(const Points<3>& X, Eigen::VectorXd& f, Points<3>* G = nullptr) const override;
  bool valid(const Vec<3>& x) const override { return inner_.valid(x); }
  bool validNear(const Vec<3>& x, double margin) const override { return inner_.validNear(x, margin); }
  bool validOnZeroSet(const Vec<3>& x) const override { return inner_.validOnZeroSet(x); }
  void validBatch(const Points<3>& X, std::vector<char>& out, double margin = 0.0) const override {
    inner_.validBatch(X, out, margin);
  }
  void evaluateValidBatch(const Points<3>& X, Eigen::VectorXd& f, std::vector<char>& valid) const override;
  bool everywhereValid() const override { return inner_.everywhereValid(); }
  // The inner field's grid form, guarded the same way (null when the inner field has none).
  std::unique_ptr<ImplicitField<3>> forGridCells(double cellDiagonal) const override;
  double lipschitzBound(const Box<3>& box) const override;

 private:
  // Whether f at x changes sign here.
  bool overrules(const Vec<3>& x, double f) const;
  // Changes the sign of f (and G's columns) where overrules() says so.
  void guardBatch(const Points<3>& X, Eigen::VectorXd& f, Points<3>* G) const;

  const ImplicitField<3>& inner_;
  std::shared_ptr<const CloudWinding<3>> winding_;
  GuardRegion region_;
  std::unique_ptr<ImplicitField<3>> owned_;
};

}  // namespace hermite
