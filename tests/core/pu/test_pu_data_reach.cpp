// The data reach of a partition-of-unity field (pu_data_reach.h; docs/maths.md, "No data"):
// points sampled from a closed mesh with thin parts reconstruct as one watertight component near
// the true surface at the sampling's grid step and at a finer one, and the reach follows the
// sampling density.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "core/mesh/marching_cubes.h"
#include "core/mesh/tri_mesh.h"
#include "core/pu/pu_model.h"
#include "support/mesh_samples.h"

using namespace hermite;

namespace {

// Signed distance to a capsule: the segment a–b thickened by r.
double capsule(const Vec<3>& x, const Vec<3>& a, const Vec<3>& b, double r) {
  const Vec<3> ab = b - a;
  const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (x - (a + t * ab)).norm() - r;
}

// An armadillo-like solid: an ellipsoidal body with thin limbs, two thin "fingers" 2.5 sample
// spacings apart, and an ear; f = the smallest of the parts' signed distances (exact outside).
class CreatureField final : public ImplicitField<3> {
 public:
  // The signed distance (exact outside).
  double sdf(const Vec<3>& x) const {
    const double body = (x.cwiseQuotient(Vec<3>(0.6, 0.45, 0.4)).norm() - 1.0) * 0.4;
    double f = body;
    f = std::min(f, capsule(x, Vec<3>(0.3, 0.2, 0), Vec<3>(0.9, 0.6, 0.1), 0.07));
    f = std::min(f, capsule(x, Vec<3>(-0.3, 0.2, 0), Vec<3>(-0.9, 0.6, 0.1), 0.07));
    f = std::min(f, capsule(x, Vec<3>(0.2, -0.3, 0), Vec<3>(0.3, -0.95, 0.0), 0.06));
    f = std::min(f, capsule(x, Vec<3>(0.2, -0.3, 0.12), Vec<3>(0.3, -0.95, 0.12), 0.035));  // finger beside the leg
    f = std::min(f, capsule(x, Vec<3>(-0.1, 0.0, 0.3), Vec<3>(-0.2, 0.1, 0.75), 0.05));      // ear
    return f;
  }
  double evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const override {
    if (g || H) {  // central differences suffice for the meshing's vertex refinement
      const double e = 1e-6;
      Vec<3> d;
      for (int k = 0; k < 3; ++k) {
        Vec<3> p = x, m = x;
        p(k) += e;
        m(k) -= e;
        d(k) = (sdf(p) - sdf(m)) / (2 * e);
      }
      if (g) *g = d;
      if (H) H->setZero();
    }
    return sdf(x);
  }
  double lipschitzBound(const Box<3>&) const override { return 1.0; }
};

Box<3> grownBox(const Points<3>& P, double margin) {
  Box<3> b{P.rowwise().minCoeff(), P.rowwise().maxCoeff()};
  const double d = margin * b.extent().norm();
  b.lo.array() -= d;
  b.hi.array() += d;
  return b;
}

}  // namespace

TEST_CASE("pu data reach: 20 000 samples of a closed mesh with thin parts: one watertight component near the surface") {
  const CreatureField truth;
  MarchingOptions fine;
  fine.resolution = 160;
  fine.cull = false;
  const TriMesh truthMesh = marchingCubes(truth, Box<3>{Vec<3>(-1.1, -1.1, -0.6), Vec<3>(1.1, 1.0, 0.9)}, fine);
  REQUIRE(checkMesh(truthMesh).closedManifold());
  const HermiteSamples<3> s = testing::sampleMesh(truthMesh, 20000, 17);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  const PuModel<3> pu = fitPu<3>(s, o);
  const Box<3> bounds = grownBox(s.points, 0.25);  // view bounds well beyond the data
  const double diagonal = (s.points.rowwise().maxCoeff() - s.points.rowwise().minCoeff()).norm();
  // At about the sampling's spacing and at half of it: closed either way.
  for (int resolution : {96, 192}) {
    CAPTURE(resolution);
    MarchingOptions mo;
    mo.resolution = resolution;
    const TriMesh mesh = marchingCubes(pu, bounds, mo);
    const MeshCheck check = checkMesh(mesh);
    CHECK(check.components == 1);
    CHECK(check.closedManifold());
    CHECK(check.eulerCharacteristic == 2);  // a sphere's topology: limbs and ear attached, none fused
    double worst = 0;
    for (int v = 0; v < mesh.vertexCount(); ++v) worst = std::max(worst, std::abs(truth.sdf(mesh.vertices.col(v))));
    MESSAGE("creature at " << resolution << ": " << mesh.triangleCount() << " triangles, farthest vertex "
                           << 100 * worst / diagonal << " % of the diagonal");
    CHECK(worst <= 0.005 * diagonal);
  }
}

TEST_CASE("pu data reach: the reach follows the local spacing, and no data far from every sample") {
  // A dense patch and a sparse one of the same plane: the reach scales with each one's spacing.
  HermiteSamples<3> s;
  const int dense = 60, sparse = 15;
  s.points.resize(3, dense * dense + sparse * sparse);
  s.normals.resize(3, s.points.cols());
  int c = 0;
  for (int i = 0; i < dense; ++i)
    for (int j = 0; j < dense; ++j) s.points.col(c++) = Vec<3>(i / double(dense), j / double(dense), 0);
  for (int i = 0; i < sparse; ++i)
    for (int j = 0; j < sparse; ++j) s.points.col(c++) = Vec<3>(2 + i / double(sparse), j / double(sparse), 0);
  s.normals.colwise() = Vec<3>(0, 0, 1);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  o.dataReach = 3.0;
  const PuModel<3> pu = fitPu<3>(s, o);
  // k = 6 neighbours on a square grid of step a: d₆ = √2·a, so the reach is 3√2·a ≈ 4.24 a.
  const double aDense = 1.0 / dense, aSparse = 1.0 / sparse;
  const auto reaches = [&](const PuModel<3>& m, const Vec<3>& y) { return m.dataReach().reaches(m.tree(), y); };
  CHECK(reaches(pu, Vec<3>(0.5, 0.5, 4.2 * aDense)));
  CHECK_FALSE(reaches(pu, Vec<3>(0.5, 0.5, 4.3 * aDense)));
  const Vec<3> sparseCentre(2 + 7 * aSparse, 7 * aSparse, 0);
  CHECK(reaches(pu, sparseCentre + Vec<3>(0, 0, 4.2 * aSparse)));
  CHECK_FALSE(reaches(pu, sparseCentre + Vec<3>(0, 0, 4.3 * aSparse)));
  CHECK(pu.valid(Vec<3>(0.5, 0.5, 0.0)));
  CHECK_FALSE(pu.valid(Vec<3>(1.5, 0.5, 0.0)));  // between the patches, far from both
  PuOptions wide = o;
  wide.dataReach = 6.0;
  CHECK(reaches(fitPu<3>(s, wide), Vec<3>(0.5, 0.5, 8.4 * aDense)));
}
