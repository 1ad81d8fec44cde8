// Streamed marching cubes (marching_slab.h): the slabs' mesh is the dense grid's, across slab
// seams, on a partition-of-unity field with "no data" regions; the slab plan bounds memory by
// the cross-section and a grid beyond the available memory is refused before it starts.

#include <doctest/doctest.h>

#include <chrono>
#include <string>

#include "core/base/memory_check.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/marching_memory.h"
#include "core/pu/pu_model.h"
#include "core/shapes/analytic_shapes.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

Box<3> cube(double h) { return Box<3>{Vec<3>::Constant(-h), Vec<3>::Constant(h)}; }

std::uint64_t gFakeBytes = 0;
AvailableMemory fakeAvailable() { return {gFakeBytes, "test limit"}; }

struct FakeMemory {
  explicit FakeMemory(std::uint64_t bytes) {
    gFakeBytes = bytes;
    setAvailableMemorySource(fakeAvailable);
  }
  ~FakeMemory() { setAvailableMemorySource(nullptr); }
  FakeMemory(const FakeMemory&) = delete;
  FakeMemory& operator=(const FakeMemory&) = delete;
};

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The streamed mesh (cull on) against the dense one (every grid point evaluated, every cell
// marched); the streamed one evaluates f at fewer than maxFraction of the grid points.
void checkSameAsDense(const ImplicitField<3>& field, const Box<3>& box, int resolution, bool closed,
                      double maxFraction) {
  CAPTURE(resolution);
  MarchingOptions streamed{resolution}, dense{resolution};
  dense.cull = false;
  MarchingReport rs, rd;
  const TriMesh a = marchingCubes(field, box, streamed, &rs);
  const TriMesh b = marchingCubes(field, box, dense, &rd);
  MESSAGE("streamed: evaluated " << rs.evaluatedPoints << " of " << rd.evaluatedPoints << " grid points");
  CHECK(rs.cells == rd.cells);
  CHECK(double(rs.evaluatedPoints) < maxFraction * double(rd.evaluatedPoints));
  REQUIRE(a.vertexCount() == b.vertexCount());
  REQUIRE(a.triangleCount() == b.triangleCount());
  REQUIRE(a.vertexCount() > 0);
  CHECK((a.vertices - b.vertices).cwiseAbs().maxCoeff() <= 1e-12);
  CHECK((a.normals - b.normals).cwiseAbs().maxCoeff() <= 1e-12);
  CHECK((a.triangles - b.triangles).cwiseAbs().maxCoeff() == 0);
  CHECK(rs.maxAbsF == doctest::Approx(rd.maxAbsF).epsilon(1e-12));
  CHECK(checkMesh(a).closedManifold() == closed);
}

}  // namespace

TEST_CASE("streamed marching cubes: the dense grid's mesh across slab seams, on a PU field with no-data regions") {
  const HermiteSamples<3> s = testing::blob(3000);
  PuOptions o;
  o.local = HrbfOptions{{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  o.maxPointsPerBox = 20;
  const PuModel<3> pu = fitPu<3>(s, o);
  REQUIRE_FALSE(pu.everywhereValid());
  // 150 cells along z: slabs of 64, 64 and 22 layers, the surface crossing both seams. A coarse
  // PU: its Lipschitz bound proves little inside the data's shell (56 % evaluated when written).
  checkSameAsDense(pu, cube(1.6), 150, true, 0.75);
  // A box that cuts the surface (open mesh) and is not a cube: 130 x 98 x 70 cells, two slabs;
  // mostly the data's shell (84 % evaluated when written).
  checkSameAsDense(pu, Box<3>{Vec<3>(-1.6, -1.2, -0.2), Vec<3>(1.6, 1.2, 1.5)}, 130, false, 0.95);
}

TEST_CASE("streamed marching cubes: an analytic surface through many thin slabs") {
  const SphereField sphere(Vec<3>(0.05, -0.03, 0.3), 0.7);
  // 300 cells along z, 80 across: five slabs, the last of 44 layers; the two caps the column cuts
  // out of the sphere span z ∈ [−0.4, −0.1] and [0.7, 1.0], across the seams at z = −0.36 and 0.92.
  checkSameAsDense(sphere, Box<3>{Vec<3>(-0.4, -0.4, -1.0), Vec<3>(0.4, 0.4, 2.0)}, 300, false, 0.1);
}

TEST_CASE("streamed marching cubes are sized by their slab and refuse a grid beyond memory before it starts") {
  const Box<3> unit{Vec<3>::Zero(), Vec<3>::Ones()};
  // 512³: one slab of 513 x 513 x 65 points, 10 bytes each (171 MB), not the 1.2 GB of the grid.
  const PlannedAllocation p512 = marchingSlabPlan(unit, 512);
  CHECK(p512.bytes == 513ull * 513 * 65 * 10);
  CHECK(contains(p512.purpose, "marching cubes at resolution 512 (slabs of 513 x 513 x 65 points"));
  // A grid thinner than a slab holds all its layers.
  Box<3> flat = unit;
  flat.hi[2] = 0.0625;
  CHECK(marchingSlabPlan(flat, 256).bytes == 257ull * 257 * 17 * 10);
  const PlannedAllocation p4096 = marchingSlabPlan(unit, 4096);
  CHECK(p4096.bytes == 4097ull * 4097 * 65 * 10);
  FakeMemory fake(1'000'000'000ull);
  CHECK_NOTHROW(checkMemory(p512, kMarchingRemedy));
  const SphereField sphere(Vec<3>(0.5, 0.5, 0.5), 0.3);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    marchingCubes(sphere, unit, {4096});
    FAIL("no refusal");
  } catch (const MemoryLimitError& e) {
    CHECK(contains(e.what(), "marching cubes at resolution 4096 (slabs of 4097 x 4097 x 65 points"));
    CHECK(contains(e.what(), "needs 11 GB"));
    CHECK(contains(e.what(), "1.0 GB available (test limit)"));
    CHECK(contains(e.what(), "--resolution"));
  }
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 1.0);
}
