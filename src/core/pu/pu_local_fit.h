#pragma once
// The local HRBF fit of one partition-of-unity box (pu_model.h; docs/maths.md, "Partition of
// unity"): small systems of 30–800 unknowns, solved in-process with Eigen, because LAPACK's
// per-call overhead (NaN checks, condition estimation, workspace queries) is 4–5 times the solve
// at these sizes; larger ones, and an explicit solver choice, go through fitHrbfAbout.
//
// Paths, cheapest first, each falling back to the next:
//  - cholesky:            no polynomial and A positive definite: LLT of A.
//  - nullspace-cholesky:  a polynomial P (n × m) and A definite on null(Pᵀ) with sign s:
//                         P = Q R, B = Qᵀ A Q, LLT of s·B₂₂ ((n − m) unknowns, x = Q [0; y],
//                         R c = (Qᵀb)₁ − B₁₂ y). About half the work of the saddle's LU
//                         ((n − m)³/3 + O(n²m) flops against 2(n + m)³/3).
//  - lu:                  partial-pivot LU of the whole saddle matrix.
// The LLTs are small_cholesky.h's: Eigen's unblocked loop, or 32-column blocks, in place, with
// Eigen's 1-norm condition estimate made for less on the factor (cholesky_condition.h).
// A path whose factorisation fails, whose reciprocal condition estimate is ≤ 1e-15 or whose
// solution is not finite falls through; the last resort is fitHrbfAbout (pivoted fallbacks,
// warnings, NumericalError for a failed factorisation — the caller then grows the support).
// The polynomial stays in box-frame coordinates (no centring: the frame already puts the data
// near the origin, and all paths must agree).

#include "core/rbf/hrbf.h"

namespace hermite {

// Local systems up to this many unknowns are solved in-process.
inline constexpr int kPuInProcessUnknowns = 800;

// Fits `sub`; fills report (solver, condition estimate, warnings, unknowns). Throws NumericalError
// for a singular or non-finite local system.
template <int Dim>
HrbfModel<Dim> fitPuLocal(const HermiteSamples<Dim>& sub, const HrbfOptions& options, FitReport& report);

}  // namespace hermite
