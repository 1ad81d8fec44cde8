#pragma once
// Error types shared by the whole program. Each maps to one exit code of the command line
// (docs/cli.md, Exit codes): InputError 1, UsageError 2, NumericalError 3, EnvironmentError 4.
// Messages carry their context: file and line, JSON key path, sample index, solver reason.

#include <stdexcept>
#include <string>

namespace hermite {

// Bad input data: a scene file, a point file, an out-of-range option. Exit code 1.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Wrong use of the command line. Exit code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A factorisation failed or a result is not finite. Exit code 3.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// No GL context, shader compile error, unwritable output. Exit code 4.
class EnvironmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace hermite
