#include "core/rbf/lapack_errors.h"

#include <cstddef>
#include <string>

namespace hermite {

namespace {

thread_local std::string t_lastError;

void record(const char* routine, std::size_t length, int parameter) {
  std::string name(routine, length);
  while (!name.empty() && name.back() == ' ') name.pop_back();  // Fortran pads names with blanks
  t_lastError = name + ": parameter " + std::to_string(parameter) + " has an illegal value";
}

}  // namespace

std::optional<std::string> takeLapackError() {
  if (t_lastError.empty()) return std::nullopt;
  std::string error;
  error.swap(t_lastError);
  return error;
}

}  // namespace hermite

// The Fortran error handler (OpenBLAS declares its own weak; ours takes precedence). The hidden
// length argument of the CHARACTER name follows the gfortran convention.
extern "C" void xerbla_(const char* routine, const int* info, std::size_t length) {
  std::size_t n = 0;
  while (n < length && n < 32 && routine[n] != '\0') ++n;
  hermite::record(routine, n, info ? *info : 0);
}

// LAPACKE's own argument check (a wrong layout, a work-space failure): info is the negated
// parameter number, or a LAPACK_*_MEMORY_ERROR code below −1000.
extern "C" void LAPACKE_xerbla(const char* routine, int info) {
  std::size_t n = 0;
  while (routine && routine[n] != '\0' && n < 64) ++n;
  hermite::record(routine ? routine : "LAPACKE", n, info < 0 ? -info : info);
}
