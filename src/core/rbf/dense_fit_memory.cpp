#include "core/rbf/dense_fit_memory.h"

#include <string>

#include "core/base/threading.h"

namespace hermite {

namespace {

// Square matrices of n + m doubles held at the peak of a path (dense_fit_memory.h).
int squareMatrices(SolverChoice path, bool polynomial) {
  switch (path) {
    case SolverChoice::Cholesky:
    case SolverChoice::NullspaceCholesky:
    case SolverChoice::ProjectedCholesky:
      return 1;
    case SolverChoice::Lu:
      return polynomial ? 2 : 1;
    case SolverChoice::Ldlt:
    case SolverChoice::Auto:
      break;
  }
  return polynomial ? 3 : 2;
}

}  // namespace

std::uint64_t denseFitBytes(std::int64_t unknowns, SolverChoice solver, std::int64_t polynomialTerms) {
  const std::uint64_t N = unknowns > 0 ? static_cast<std::uint64_t>(unknowns) : 0;
  const std::uint64_t m = polynomialTerms > 0 ? static_cast<std::uint64_t>(polynomialTerms) : 0;
  const std::uint64_t matrices = static_cast<std::uint64_t>(squareMatrices(solver, m > 0));
  return saturatingSum({saturatingProduct({matrices, N, N, sizeof(double)}), saturatingProduct({8, N, m, sizeof(double)}),
                        saturatingProduct({16, N, sizeof(double)})});
}

std::uint64_t blasBufferBytes(int threads) {
  return saturatingProduct({static_cast<std::uint64_t>(threads > 0 ? threads : 1), kBlasBufferBytes});
}

PlannedAllocation denseFitPlan(std::int64_t unknowns, SolverChoice solver, std::int64_t polynomialTerms) {
  const int matrices = squareMatrices(solver, polynomialTerms > 0);
  const std::string path = solver == SolverChoice::Auto ? std::string("ldlt") : std::string(solverName(solver));
  const std::string size = std::to_string(unknowns);
  const std::uint64_t bytes = denseFitBytes(unknowns, solver, polynomialTerms);
  std::string what = "the dense fit of " + size + " unknowns (" + path + ": " +
                     (matrices == 1 ? std::string("its system matrix") : std::to_string(matrices) + " matrices") +
                     " of " + size + " x " + size + " doubles";
  // Small fits (hole filling, local fits) run by the thousand once the buffers exist: counting
  // them again would refuse a few-megabyte fit under a tight limit.
  if (bytes < kUncheckedBytes) return {bytes, what + ")"};
  const int threads = threadCount();
  return {saturatingSum({bytes, blasBufferBytes(threads)}),
          what + ", and the BLAS buffers of " + std::to_string(threads) + " threads)"};
}

void checkDenseFitMemory(std::int64_t unknowns, SolverChoice solver, std::int64_t polynomialTerms) {
  checkMemory(denseFitPlan(unknowns, solver, polynomialTerms), kDenseFitRemedy);
}

}  // namespace hermite
