// The consumers of ImplicitField::valid (docs/maths.md, "No data"): the CPU tracer, the 2D
// reference view and the mesher never show a no-data point as surface; and the mesher's culling
// octree gives exactly the dense grid's mesh.

#include <doctest/doctest.h>

#include <cmath>

#include "core/mesh/marching_cubes.h"
#include "core/mesh/marching_squares.h"
#include "core/pu/pu_model.h"
#include "core/shapes/analytic_shapes.h"
#include "core/trace/color_map.h"
#include "core/trace/cpu_tracer.h"
#include "core/trace/field2d_reference.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

// A field with data only where x_k ≥ 0 (k = the axis): f is the inner field's value there; on
// the other side the value of the inner field too, but valid() is false.
template <int Dim, class Inner>
class HalfValid final : public ImplicitField<Dim> {
 public:
  HalfValid(Inner inner, int axis) : inner_(std::move(inner)), axis_(axis) {}
  double evaluate(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H) const override { return inner_.evaluate(x, g, H); }
  double lipschitzBound(const Box<Dim>& b) const override { return inner_.lipschitzBound(b); }
  bool valid(const Vec<Dim>& x) const override { return x(axis_) >= 0; }
  bool everywhereValid() const override { return false; }

 private:
  Inner inner_;
  int axis_;
};

Box<3> cube(double h) { return Box<3>{Vec<3>::Constant(-h), Vec<3>::Constant(h)}; }

}  // namespace

TEST_CASE("no data: the CPU tracer passes zeros without data and shows the surface beyond them") {
  const HalfValid<3, SphereField> field(SphereField(Vec<3>::Zero(), 1.0), 2);  // data where z ≥ 0
  const CpuTracer tracer(field, cube(2));
  const RayHit top = tracer.trace(Ray{Vec<3>(0.1, 0.2, 3), Vec<3>(0, 0, -1)});
  REQUIRE(top.hit);
  CHECK(top.position.z() > 0);
  CHECK(std::abs(top.position.norm() - 1.0) < 1e-6);
  CHECK_FALSE(top.back);
  // From below, the sphere's lower half has no data: the ray passes it and meets the upper half
  // from inside, as an open bowl seen through its opening.
  const RayHit bottom = tracer.trace(Ray{Vec<3>(0.1, 0.2, -3), Vec<3>(0, 0, 1)});
  REQUIRE(bottom.hit);
  CHECK(bottom.position.z() > 0);
  CHECK(std::abs(bottom.position.norm() - 1.0) < 1e-6);
  CHECK(bottom.back);
  // render() (the wavefront) agrees with trace(): every hit seen from below is the upper half's inside.
  CameraSpec spec;
  spec.eye = {0.0, 0.0, -4.0};
  spec.target = {0.0, 0.0, 0.0};
  const Camera camera(spec, Projection::Perspective, 32, 32, 1.5);
  const CpuTraceResult image = tracer.render(camera, {0.0, 0.0, 0.0});
  int hits = 0;
  for (std::size_t p = 0; p < image.hit.size(); ++p) {
    if (!image.hit[p]) continue;
    ++hits;
    const RayHit h = tracer.trace(camera.pixelRay(int(p % 32), int(p / 32)));
    REQUIRE(h.hit);
    CHECK(h.position.z() > -1e-9);
    CHECK(h.back);
  }
  CHECK(hits > 100);
}

TEST_CASE("no data: the 2D reference draws no-data pixels hatched grey, without the zero curve") {
  const HalfValid<2, CircleField> field(CircleField(Vec<2>::Zero(), 0.8), 0);  // data where x ≥ 0
  const View2d view(Vec<2>(0, 0), 1.2, 96, 80);
  const Field2dImage out = renderField2dReference(field, view);
  int hatched = 0, plain = 0;
  for (int j = 0; j < view.height(); ++j)
    for (int i = 0; i < view.width(); ++i) {
      const Vec<2> x = view.pixelCenter(i, j);
      const std::uint8_t* px = out.image.at(i, j);
      const std::size_t p = std::size_t(j) * view.width() + i;
      if (x.x() >= 0) continue;
      CHECK(out.zeroCoverage[p] == 0.0f);
      const int row = view.height() - 1 - j;
      const bool hatch = (i + row) % kNoDataHatchPeriod < kNoDataHatchWidth;
      const auto& c = hatch ? kNoDataHatchColor : kNoDataColor;
      for (int k = 0; k < 3; ++k) CHECK(std::abs(px[k] - 255.0 * c[k]) <= 1.0);
      (hatch ? hatched : plain) += 1;
    }
  CHECK(hatched > 0);
  CHECK(plain > hatched);
  // The data side still has its zero curve.
  int black = 0;
  for (std::size_t p = 0; p < out.zeroCoverage.size(); ++p) black += out.zeroCoverage[p] > 0.5f;
  CHECK(black > 0);
}

TEST_CASE("no data: marching makes no geometry in cells with a no-data corner") {
  const HalfValid<3, SphereField> field(SphereField(Vec<3>::Zero(), 1.0), 2);
  MarchingOptions mo;
  mo.resolution = 40;
  const TriMesh mesh = marchingCubes(field, cube(1.5), mo);
  REQUIRE(mesh.triangleCount() > 0);
  CHECK(mesh.vertices.row(2).minCoeff() >= 0.0);
  const MeshCheck check = checkMesh(mesh);
  CHECK(check.boundaryEdges > 0);  // open along the edge of the data
  CHECK(check.components == 1);
  const HalfValid<2, CircleField> circle(CircleField(Vec<2>::Zero(), 0.8), 0);
  const std::vector<Polyline2d> lines = marchingSquares(circle, Box<2>{Vec<2>(-1, -1), Vec<2>(1, 1)}, {40});
  REQUIRE(lines.size() == 1);
  CHECK_FALSE(lines[0].closed);
  CHECK(lines[0].points.row(0).minCoeff() >= 0.0);
}

TEST_CASE("no data: the culling octree gives the dense grid's mesh, vertex for vertex, on a PU field") {
  const HermiteSamples<3> s = testing::blob(3000);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  o.maxPointsPerBox = 20;
  const PuModel<3> pu = fitPu<3>(s, o);
  MarchingOptions culled, dense;
  culled.resolution = dense.resolution = 72;
  dense.cull = false;
  MarchingReport rc, rd;
  const Box<3> bounds = cube(1.6);
  const TriMesh a = marchingCubes(pu, bounds, culled, &rc);
  const TriMesh b = marchingCubes(pu, bounds, dense, &rd);
  MESSAGE("evaluated " << rc.evaluatedPoints << " of " << rd.evaluatedPoints << " grid points");
  CHECK(rc.evaluatedPoints < 3 * rd.evaluatedPoints / 4);  // a coarse PU: its data shell is much of the grid
  REQUIRE(a.vertexCount() == b.vertexCount());
  REQUIRE(a.triangleCount() == b.triangleCount());
  CHECK((a.vertices - b.vertices).cwiseAbs().maxCoeff() == 0.0);
  CHECK((a.triangles - b.triangles).cwiseAbs().maxCoeff() == 0);
  CHECK(checkMesh(a).closedManifold());
}
