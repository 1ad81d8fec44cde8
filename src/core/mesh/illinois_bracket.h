#pragma once
// One step of the Illinois variant of false position on a sign bracket: the edge vertices of
// marching cubes (marching_grid.h) and the centre vertices (centre_vertices.h) both narrow theirs
// with it.

namespace hermite::detail {

// The bracket [a, b] of a root of f (f(a) and f(b) on opposite sides, f ≥ 0 counting as outside)
// takes ft = f(t): t replaces the end on ft's side. When the same end moves twice running, the
// other end's value is halved, which keeps false position superlinear where f bends (one end
// would otherwise stay put). lastMoved: −1 a, +1 b, 0 none yet.
inline void illinoisUpdate(double& a, double& fa, double& b, double& fb, signed char& lastMoved, double t, double ft) {
  const signed char moved = (ft < 0) == (fa < 0) ? -1 : 1;
  if (moved < 0) a = t, fa = ft;
  else b = t, fb = ft;
  if (moved == lastMoved) (moved < 0 ? fb : fa) *= 0.5;
  lastMoved = moved;
}

}  // namespace hermite::detail
