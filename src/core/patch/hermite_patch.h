#pragma once
// Bicubic Hermite patch (docs/maths.md, Patches): X(s,t) = H(s)ᵀ C H(t), s, t ∈ [0, 1], with
// H(t) = (1 − 3t² + 2t³, t − 2t² + t³, t³ − t², 3t² − 2t³) and, per coordinate,
//   C = [[X00,  Xt00,  Xt01,  X01 ],
//        [Xs00, Xst00, Xst01, Xs01],
//        [Xs10, Xst10, Xst11, Xs11],
//        [X10,  Xt10,  Xt11,  X11 ]]      Xab = X(s = a, t = b).

#include <array>

#include "core/base/geometry.h"

namespace hermite {

// Point and first derivatives of a parametric surface at (s, t).
struct SurfacePoint {
  Vec<3> X = Vec<3>::Zero();
  Vec<3> Xs = Vec<3>::Zero();
  Vec<3> Xt = Vec<3>::Zero();
  Vec<3> Xst = Vec<3>::Zero();
  // Unit normal Xs × Xt (zero where the patch is degenerate).
  Vec<3> normal() const {
    const Vec<3> n = Xs.cross(Xt);
    const double len = n.norm();
    return len > 0 ? Vec<3>(n / len) : Vec<3>::Zero();
  }
};

// The 4 × 4 coefficient matrix of one coordinate.
using PatchMatrix = Eigen::Matrix4d;

// Hermite basis H(t) and its derivative H′(t).
Eigen::Vector4d hermiteBasis(double t);
Eigen::Vector4d hermiteBasisDerivative(double t);

struct HermitePatch {
  std::array<PatchMatrix, 3> C{PatchMatrix::Zero(), PatchMatrix::Zero(), PatchMatrix::Zero()};  // x, y, z

  // Corner data by (a, b) ∈ {0,1}²: the entries of C named in the header comment.
  Vec<3> point(int a, int b) const;
  Vec<3> sTangent(int a, int b) const;
  Vec<3> tTangent(int a, int b) const;
  Vec<3> twist(int a, int b) const;
  void setPoint(int a, int b, const Vec<3>& v);
  void setSTangent(int a, int b, const Vec<3>& v);
  void setTTangent(int a, int b, const Vec<3>& v);
  void setTwist(int a, int b, const Vec<3>& v);

  SurfacePoint evaluate(double s, double t) const;
};

}  // namespace hermite
