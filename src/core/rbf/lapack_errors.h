#pragma once
// LAPACK's argument errors, caught instead of printed.
//
// Reference LAPACK and OpenBLAS report an illegal argument by calling xerbla_, and LAPACKE by
// calling LAPACKE_xerbla; both print a line on standard output ("** On entry to DPOTRS parameter
// number 7 had an illegal value"), which would corrupt machine-readable output such as
// `fit --json`. This file defines both functions: they print nothing and record the routine and
// the parameter for the calling thread, where the solver picks the record up and reports it as
// an error of its own.

#include <optional>
#include <string>

namespace hermite {

// The error recorded on this thread since the last call ("DPOTRS: parameter 7 has an illegal
// value"), cleared by the call; nullopt when LAPACK reported nothing.
std::optional<std::string> takeLapackError();

}  // namespace hermite
