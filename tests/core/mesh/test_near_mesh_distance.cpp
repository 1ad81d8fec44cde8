// distancesToMeshWithin (near_mesh_distance.h): the exact point-triangle distance to the nearest
// triangle within the reach, the reach beyond it, whatever cells the triangles span.

#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/mesh/near_mesh_distance.h"
#include "support/mesh_distance.h"
#include "support/mesh_samples.h"

using namespace hermite;

namespace {

// The 12 triangles of the cube [0, s]³.
TriMesh cubeMesh(double s) { return testing::boxMesh(Vec<3>::Zero(), Vec<3>::Constant(s)); }

}  // namespace

TEST_CASE("near mesh distance: exact within the reach, the reach beyond it") {
  const TriMesh cube = cubeMesh(1.0);  // faces much larger than the reach's cells
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.3, 1.3);
  Points<3> p(3, 400);
  for (Eigen::Index i = 0; i < p.cols(); ++i) p.col(i) = Vec<3>(u(rng), u(rng), u(rng));
  for (double reach : {0.05, 0.2}) {
    CAPTURE(reach);
    const std::vector<double> d = distancesToMeshWithin(cube, p, reach);
    int within = 0;
    for (Eigen::Index i = 0; i < p.cols(); ++i) {
      const double exact = testing::bruteMeshDistance(cube, p.col(i));
      if (exact < reach) {
        ++within;
        CHECK(d[static_cast<std::size_t>(i)] == doctest::Approx(exact).epsilon(1e-12));
      } else {
        CHECK(d[static_cast<std::size_t>(i)] == reach);
      }
    }
    CHECK(within > 20);  // both cases are exercised
  }
}

TEST_CASE("near mesh distance: no points or no triangles") {
  CHECK(distancesToMeshWithin(cubeMesh(1.0), Points<3>(3, 0), 0.1).empty());
  Points<3> p(3, 1);
  p.col(0) = Vec<3>(0.5, 0.5, 0.5);
  CHECK(distancesToMeshWithin(TriMesh{}, p, 0.1) == std::vector<double>{0.1});
}

TEST_CASE("near mesh distance: a triangle spanning millions of cells, and points that are not finite") {
  TriMesh big;
  big.vertices.resize(3, 3);
  big.vertices << 0, 1e4, 0, 0, 0, 1e4, 0, 0, 0;  // columns (0,0,0), (1e4,0,0), (0,1e4,0)
  big.triangles.resize(3, 1);
  big.triangles.col(0) = Eigen::Vector3i(0, 1, 2);
  Points<3> p(3, 3);
  p.col(0) = Vec<3>(5e3, 1e3, 2e-3);
  p.col(1) = Vec<3>(5e3, 1e3, 0.5);
  p.col(2) = Vec<3>(NAN, 0, 0);
  const std::vector<double> d = distancesToMeshWithin(big, p, 1e-2);
  CHECK(d[0] == doctest::Approx(2e-3).epsilon(1e-9));
  CHECK(d[1] == 1e-2);
  CHECK(d[2] == 1e-2);
}
