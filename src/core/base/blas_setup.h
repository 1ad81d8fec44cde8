#pragma once
// OpenBLAS chooses its compute kernels from the CPU model when the library loads. Under
// hypervisors that hide the model (this project's machines report "Intel(R) Xeon(R)
// Processor") it falls back to the generic "Prescott" SSE3 kernels, several times slower than the
// AVX2/AVX-512 kernels the CPU supports (docs/performance.md, Fitting and solvers).
//
// The choice cannot be changed after loading, so a program that wants the fast kernels calls
// this first thing in main(): when OpenBLAS picked a generic core but the CPU has AVX2/AVX-512,
// it sets OPENBLAS_CORETYPE from the CPU's feature flags; it also sets OMP_WAIT_POLICY=PASSIVE
// (spinning OpenMP workers starve OpenBLAS's threads on small machines) and
// OPENBLAS_THREAD_TIMEOUT=16 (OpenBLAS's own workers spin ~0.1 s after each call by default,
// starving the renderer), and re-executes itself
// once when it changed anything. Values set by the user are always respected.

namespace hermite {

// Returns normally when no re-execution is needed or it failed (the program then runs with the
// generic kernels). On success it does not return.
void reexecWithTunedBlas(char** argv);

// The OpenBLAS core in use ("SkylakeX", "Haswell", "Prescott", ...).
const char* blasCoreName();

}  // namespace hermite
