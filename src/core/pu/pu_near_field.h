#pragma once
// A partition of unity as a contour grid reads it (ImplicitField::forGridCells): f extended by up
// to a cell beyond the supports.
//
// The smooth blend has a value only inside its blended supports; beyond them f is the no-data
// stand-in. Where the data's outermost boxes are small (dense samples on a flat extreme face) their
// supports end closer to the samples than a grid cell, so a cell the zero set crosses can have a
// corner without a value, and the mesher leaves the cell out: a hole in a closed surface. Here a
// point without a value within `cellDiagonal` of a blended support takes that support's local fit
// (the nearest support; at the union's edge it is the fit the blend tends to), and it is valid
// where the data reach says so (validNear with the grid's margin). Farther away f stays the
// no-data stand-in. docs/maths.md, "No data".

#include "core/pu/pu_model.h"

namespace hermite {

template <int Dim>
class PuNearField : public ImplicitField<Dim> {
 public:
  PuNearField(const PuModel<Dim>& pu, double cellDiagonal) : pu_(pu), reach_(cellDiagonal) {}

  double evaluate(const Vec<Dim>& x, Vec<Dim>* g = nullptr, Mat<Dim>* H = nullptr) const override;
  void evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G = nullptr) const override;
  bool valid(const Vec<Dim>& x) const override { return validNear(x, 0.0); }
  bool validNear(const Vec<Dim>& x, double margin) const override;
  // 1 where the blend is valid, 2 where only the extension is (ImplicitField::validBatch), else 0.
  void validBatch(const Points<Dim>& X, std::vector<char>& out, double margin = 0.0) const override;
  // The blend's: only the corners of the grid see the extension, never the surface's vertices.
  bool validOnZeroSet(const Vec<Dim>& x) const override;
  bool everywhereValid() const override { return false; }
  // The blend's bound, or ∞ for a box no support touches but one lies within a cell of.
  double lipschitzBound(const Box<Dim>& box) const override;

 private:
  // Whether x (world) has no value in the blend: f there is the no-data stand-in. A blended value
  // exactly equal to it (the root box's diagonal) would read as none and take the nearest fit.
  bool standIn(double f) const { return f == pu_.noDataValue(); }
  // Valid only through the extension: no value in the blend, a support within a cell, data reach.
  bool validByExtension(const Vec<Dim>& x, double margin) const;

  const PuModel<Dim>& pu_;
  double reach_;  // world units: how far beyond the supports f has a value
};

extern template class PuNearField<2>;
extern template class PuNearField<3>;

}  // namespace hermite
