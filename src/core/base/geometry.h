#pragma once
// Small fixed-size geometric types shared by core: vectors, point matrices and boxes.
// Point sets are stored column-wise: a Dim × N matrix holds N points.

#include <Eigen/Core>

namespace hermite {

template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;
template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;
// Dim × N, one point (or vector) per column.
template <int Dim>
using Points = Eigen::Matrix<double, Dim, Eigen::Dynamic>;

// Axis-aligned box [lo, hi].
template <int Dim>
struct Box {
  Vec<Dim> lo = Vec<Dim>::Zero();
  Vec<Dim> hi = Vec<Dim>::Zero();

  Vec<Dim> center() const { return 0.5 * (lo + hi); }
  Vec<Dim> extent() const { return hi - lo; }
  bool contains(const Vec<Dim>& x) const {
    return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
  }
  // Distance from x to the nearest point of the box (0 inside).
  double distanceTo(const Vec<Dim>& x) const {
    const Vec<Dim> d = (lo - x).cwiseMax(x - hi).cwiseMax(Vec<Dim>::Zero());
    return d.norm();
  }
  // Distance from x to the farthest corner of the box.
  double farthestDistance(const Vec<Dim>& x) const {
    const Vec<Dim> d = (x - lo).cwiseAbs().cwiseMax((hi - x).cwiseAbs());
    return d.norm();
  }
};

// Bounding box of the columns of P (Dim × N, N ≥ 1).
template <int Dim>
Box<Dim> boundingBox(const Points<Dim>& P) {
  Box<Dim> b;
  b.lo = P.rowwise().minCoeff();
  b.hi = P.rowwise().maxCoeff();
  return b;
}

}  // namespace hermite
