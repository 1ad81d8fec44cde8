#pragma once
// Memory of a dense fit before it starts (core/base/memory_check.h): the saddle system of
// `unknowns` = n + m unknowns (n kernel unknowns, m polynomial terms) as solveSaddle factorises it.
// Peak, in n + m square matrices of doubles (8 bytes), per solver path:
//   cholesky, nullspace-cholesky   1  (the kernel block, factorised in place; the projection
//                                      adds n × m blocks, counted below)
//   lu                             2  (the kernel block and the saddle matrix copy it factorises;
//                                      1 when m = 0: the block itself)
//   ldlt (and auto, not knowing)   3  (as lu plus the copy kept for the LU fallback; 2 when m = 0)
// plus 8 n × m blocks and 16 vectors of n + m doubles. The plan (denseFitPlan) adds OpenBLAS's
// work buffer of each thread that runs a BLAS call: 128 MiB of address space each, allocated on
// first use and kept. OpenBLAS retries a failed buffer allocation forever, so a check that leaves
// it out can turn a refusal into a hang under an address-space limit.

#include <cstdint>

#include "core/base/memory_check.h"
#include "core/rbf/dense_solver.h"

namespace hermite {

// Peak bytes of solveSaddle on `unknowns` unknowns of which `polynomialTerms` polynomial, on the
// path `solver` takes first (plannedSolverPath; Auto counts as ldlt, the largest).
std::uint64_t denseFitBytes(std::int64_t unknowns, SolverChoice solver, std::int64_t polynomialTerms = 0);

// OpenBLAS's work buffer per thread on x86-64 (BUFFER_SIZE, 32 << 22 bytes).
inline constexpr std::uint64_t kBlasBufferBytes = 128ull << 20;
// The buffers of `threads` BLAS threads.
std::uint64_t blasBufferBytes(int threads);

// The plan of a dense fit: denseFitBytes, plus the BLAS buffers of the current thread count
// (threading.h) when the matrices reach kUncheckedBytes; its purpose names the unknowns and the
// solver path.
PlannedAllocation denseFitPlan(std::int64_t unknowns, SolverChoice solver, std::int64_t polynomialTerms = 0);

// What a refused global fit suggests.
inline constexpr const char* kDenseFitRemedy =
    "use partition of unity (fit.partition.enabled: true, or \"auto\" to choose by size) or fewer points";

// Throws MemoryLimitError when the fit does not fit in the available memory.
void checkDenseFitMemory(std::int64_t unknowns, SolverChoice solver, std::int64_t polynomialTerms);

}  // namespace hermite
