#include <doctest/doctest.h>

#include <chrono>
#include <string>

#include "core/base/memory_check.h"
#include "core/base/threading.h"
#include "core/mesh/marching_memory.h"
#include "core/patch/torus_patch_study.h"
#include "core/pu/pu_model.h"
#include "core/rbf/dense_fit_memory.h"
#include "core/rbf/hrbf.h"
#include "core/rbf/hrbf_bordered_refit.h"
#include "core/rbf/rbf_offset.h"
#include "support/test_data.h"

using namespace hermite;

namespace {

// A fixed "available" amount instead of this machine's, restored when the test ends.
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

}  // namespace

TEST_CASE("checkMemory refuses exactly when the plan exceeds what is available, naming both sizes and the remedy") {
  const PlannedAllocation plan{3'500'000'000ull, "the dense fit of 20844 unknowns"};
  CHECK_NOTHROW(checkMemory(plan, "use fewer points", {3'500'000'000ull, "MemAvailable"}));
  try {
    checkMemory(plan, "use fewer points", {1'200'000'000ull, "MemAvailable"});
    FAIL("no refusal");
  } catch (const MemoryLimitError& e) {
    const std::string m = e.what();
    CHECK(m == "the dense fit of 20844 unknowns needs 3.5 GB; this process has 1.2 GB available (MemAvailable); "
               "use fewer points");
    CHECK(e.needed() == plan.bytes);
    CHECK(e.available() == 1'200'000'000ull);
  }
  // A MemoryLimitError is an environment error: exit code 4.
  CHECK_THROWS_AS(checkMemory(plan, "", {1, "RLIMIT_AS"}), EnvironmentError);
}

TEST_CASE("without a source memory is unlimited; small plans are not checked") {
  setAvailableMemorySource(nullptr);
  CHECK(availableMemory().bytes == kUnlimitedBytes);
  CHECK_NOTHROW(checkMemory({kUnlimitedBytes, "anything"}, ""));
  FakeMemory fake(1000);
  CHECK(availableMemory().bytes == 1000);
  CHECK_NOTHROW(checkMemory({kUncheckedBytes - 1, "small"}, ""));
  CHECK_THROWS_AS(checkMemory({kUncheckedBytes, "large"}, ""), MemoryLimitError);
}

TEST_CASE("byte arithmetic saturates instead of wrapping; formatBytes keeps 2-3 digits") {
  CHECK(saturatingProduct({1ull << 40, 1ull << 40}) == kUnlimitedBytes);
  CHECK(saturatingProduct({3, 0, kUnlimitedBytes}) == 0);
  CHECK(saturatingProduct({4097, 4097, 4097, 9}) == 4097ull * 4097 * 4097 * 9);
  CHECK(saturatingSum({kUnlimitedBytes - 1, 5}) == kUnlimitedBytes);
  CHECK(formatBytes(512) == "512 B");
  CHECK(formatBytes(3'456'000) == "3.5 MB");
  CHECK(formatBytes(618'000'000'000ull) == "618 GB");
}

TEST_CASE("denseFitBytes: N² doubles per square matrix the solver path holds") {
  const std::int64_t N = 20844;
  const std::uint64_t square = std::uint64_t(N) * N * 8;
  // Within the n × m blocks and vectors (< 0.5 % at this size) of the square matrices.
  CHECK(denseFitBytes(N, SolverChoice::Cholesky, 0) == doctest::Approx(double(square)).epsilon(5e-3));
  CHECK(denseFitBytes(N, SolverChoice::NullspaceCholesky, 4) == doctest::Approx(double(square)).epsilon(5e-3));
  CHECK(denseFitBytes(N, SolverChoice::Lu, 4) == doctest::Approx(2.0 * square).epsilon(5e-3));
  CHECK(denseFitBytes(N, SolverChoice::Ldlt, 4) == doctest::Approx(3.0 * square).epsilon(5e-3));
  CHECK(denseFitBytes(N, SolverChoice::Auto, 4) == denseFitBytes(N, SolverChoice::Ldlt, 4));
  CHECK(plannedSolverPath(SolverChoice::Auto, 4, 1) == SolverChoice::NullspaceCholesky);
  CHECK(plannedSolverPath(SolverChoice::Auto, 0, -1) == SolverChoice::Cholesky);
  // Indefinite: LU (OpenBLAS's dgetrf beats LAPACK's dsytrf), or the projected Cholesky path.
  CHECK(plannedSolverPath(SolverChoice::Auto, 4, 0) == SolverChoice::Lu);
  CHECK(plannedSolverPath(SolverChoice::Auto, 0, 0, true) == SolverChoice::ProjectedCholesky);
  CHECK(denseFitBytes(N, SolverChoice::ProjectedCholesky, 0) == doctest::Approx(double(square)).epsilon(5e-3));
}

TEST_CASE("a global fit too large for the available memory is refused before assembly, quickly") {
  FakeMemory fake(200'000'000ull);  // 200 MB
  const int threads = threadCount();
  setThreadCount(1);  // one BLAS buffer (128 MiB) in the plan
  const HermiteSamples<3> s = hermite::testing::goldenSphere(3000);  // 12 004 unknowns: 1.15 GB for the kernel block
  const auto t0 = std::chrono::steady_clock::now();
  try {
    fitHrbf<3>(s, HrbfOptions{});
    FAIL("no refusal");
  } catch (const MemoryLimitError& e) {
    const std::string m = e.what();
    CHECK(contains(m, "the dense fit of 12004 unknowns"));
    CHECK(contains(m, "needs 1.3 GB"));  // 1.153 GB + 0.134 GB
    CHECK(contains(m, "200 MB available (test limit)"));
    CHECK(contains(m, "fit.partition.enabled"));
  }
  CHECK_THROWS_AS(fitRbfOffset<3>(s, RbfOffsetOptions{}), MemoryLimitError);
  CHECK_THROWS_AS(HrbfBorderedRefit<3>(s, HrbfOptions{}, 0), MemoryLimitError);
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 1.0);
  // The same data fit by partition of unity: local systems of a few hundred unknowns.
  PuOptions pu;
  pu.maxPointsPerBox = 20;
  CHECK_NOTHROW(fitPu<3>(s, pu));
  setThreadCount(threads);
}

TEST_CASE("marching grids and the patch study are sized before they allocate") {
  Box<3> cube;
  cube.lo.setZero();
  cube.hi.setOnes();
  const PlannedAllocation grid = marchingGridPlan<3>(cube, 4096);
  CHECK(grid.bytes == 4097ull * 4097 * 4097 * kMarchingBytesPerPoint);
  CHECK(contains(grid.purpose, "4097 x 4097 x 4097"));
  Box<3> flat = cube;
  flat.hi[2] = 0.25;
  CHECK(marchingCells<3>(flat, 64) == std::array<int, 3>{64, 64, 16});
  FakeMemory fake(1'000'000'000ull);
  try {
    checkMemory(grid, kMarchingRemedy);
    FAIL("no refusal");
  } catch (const MemoryLimitError& e) {
    CHECK(contains(e.what(), "needs 619 GB"));
    CHECK(contains(e.what(), "--resolution"));
  }
  PatchStudyOptions o;
  o.samples = 100000;
  CHECK(patchStudyPlan(o.samples).bytes == 4ull * 100000 * 100000 * 8);
  CHECK_THROWS_AS(torusPatchStudy(o), MemoryLimitError);
}
