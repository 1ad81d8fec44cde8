#include "core/mesh/zero_set_check.h"

#include <cmath>
#include <vector>

#include "core/mesh/marching_cubes.h"
#include "core/mesh/marching_squares.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

namespace {

// The zero set's vertices (Dim × V) and each vertex's component index; returns the count.
int contourComponents(const ImplicitField<2>& field, const Box<2>& box, const MarchingOptions& o, MarchingReport& rep,
                      Points<2>& vertices, std::vector<int>& component) {
  const std::vector<Polyline2d> lines = marchingSquares(field, box, o, &rep);
  Eigen::Index n = 0;
  for (const Polyline2d& l : lines) n += l.points.cols();
  vertices.resize(2, n);
  component.assign(std::size_t(n), 0);
  Eigen::Index at = 0;
  for (int c = 0; c < int(lines.size()); ++c)
    for (Eigen::Index k = 0; k < lines[std::size_t(c)].points.cols(); ++k, ++at) {
      vertices.col(at) = lines[std::size_t(c)].points.col(k);
      component[std::size_t(at)] = c;
    }
  return int(lines.size());
}

int contourComponents(const ImplicitField<3>& field, const Box<3>& box, const MarchingOptions& o, MarchingReport& rep,
                      Points<3>& vertices, std::vector<int>& component) {
  const TriMesh mesh = marchingCubes(field, box, o, &rep);
  int count = 0;
  const std::vector<int> perTriangle = triangleComponents(mesh, &count);
  vertices = mesh.vertices;
  component.assign(std::size_t(mesh.vertexCount()), -1);
  for (int t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) component[std::size_t(mesh.triangles(k, t))] = perTriangle[std::size_t(t)];
  return count;
}

// Samples whose pushed points p ± εn have the wrong sign (or a non-finite value).
template <int Dim>
int countSignFailures(const ImplicitField<Dim>& field, const HermiteSamples<Dim>& s, double eps) {
  const Eigen::Index n = s.points.cols();
  Points<Dim> pushed(Dim, 2 * n);
  pushed.leftCols(n) = s.points + eps * s.normals;
  pushed.rightCols(n) = s.points - eps * s.normals;
  Eigen::VectorXd f;
  field.evaluateBatch(pushed, f);
  int failures = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (!(f(i) > 0) || !(f(n + i) < 0)) ++failures;
  return failures;
}

}  // namespace

template <int Dim>
ZeroSetCheck checkZeroSet(const ImplicitField<Dim>& field, const Box<Dim>& box, const HermiteSamples<Dim>& samples,
                          const ZeroSetCheckOptions& options) {
  MarchingOptions mo;
  mo.resolution = options.resolution > 0 ? options.resolution : (Dim == 2 ? 200 : 40);
  MarchingReport rep;
  Points<Dim> vertices;
  std::vector<int> component;
  ZeroSetCheck out;
  out.components = contourComponents(field, box, mo, rep, vertices, component);
  Vec<Dim> cell;
  for (int k = 0; k < Dim; ++k) cell(k) = box.extent()(k) / std::max(1, rep.cells[std::size_t(k)]);
  out.supportDistance = 1.5 * cell.norm();
  // A component is supported when one of its vertices lies within supportDistance of a sample
  // (interpolated samples lie on the zero set, so within a cell of its contour).
  std::vector<char> supported(std::size_t(out.components), 0);
  const double d2 = out.supportDistance * out.supportDistance;
  for (Eigen::Index v = 0; v < vertices.cols(); ++v) {
    const int c = component[std::size_t(v)];
    if (c < 0 || supported[std::size_t(c)]) continue;
    supported[std::size_t(c)] = (samples.points.colwise() - vertices.col(v)).colwise().squaredNorm().minCoeff() <= d2;
  }
  for (char s : supported) out.spurious += s ? 0 : 1;
  out.pushDistance = options.pushFraction * meanSampleSpacing<Dim>(samples.points);
  out.signFailures = countSignFailures(field, samples, out.pushDistance);
  DegenerateFieldOptions dego = options.degenerate;
  dego.resolution = mo.resolution;
  out.degenerate = detectDegenerateField<Dim>(field, box, samples, dego);
  return out;
}

template ZeroSetCheck checkZeroSet<2>(const ImplicitField<2>&, const Box<2>&, const HermiteSamples<2>&,
                                      const ZeroSetCheckOptions&);
template ZeroSetCheck checkZeroSet<3>(const ImplicitField<3>&, const Box<3>&, const HermiteSamples<3>&,
                                      const ZeroSetCheckOptions&);

}  // namespace hermite
