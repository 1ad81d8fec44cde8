#include <doctest/doctest.h>

#include <unistd.h>

#include <cstdio>
#include <string>

#include <lapacke.h>

#include "core/rbf/dense_solver.h"
#include "core/rbf/hrbf.h"
#include "core/rbf/lapack_errors.h"

using namespace hermite;

namespace {

// Runs `body` with file descriptor 1 sent to a temporary file and returns what was written to it.
template <class Body>
std::string capturedStdout(Body body) {
  std::fflush(stdout);
  char name[] = "/tmp/hermite_stdout_XXXXXX";
  const int fd = ::mkstemp(name);
  REQUIRE(fd >= 0);
  const int saved = ::dup(1);
  ::dup2(fd, 1);
  body();
  std::fflush(stdout);
  ::dup2(saved, 1);
  ::close(saved);
  std::string text;
  char buf[256];
  ::lseek(fd, 0, SEEK_SET);
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;) text.append(buf, static_cast<std::size_t>(n));
  ::close(fd);
  ::unlink(name);
  return text;
}

}  // namespace

TEST_CASE("LAPACK argument errors are recorded, not printed on standard output") {
  takeLapackError();
  double a = 1, b = 1;
  lapack_int info = 0;
  // dpotrs with ldb = 0 < max(1, n): the reference LAPACK prints "** On entry to DPOTRS ...".
  const std::string out = capturedStdout([&] { info = LAPACKE_dpotrs(LAPACK_COL_MAJOR, 'L', 1, 1, &a, 1, &b, 0); });
  CHECK(info < 0);
  CHECK(out.empty());
  const auto error = takeLapackError();
  REQUIRE(error.has_value());
  CHECK(error->find("DPOTRS") != std::string::npos);
  CHECK(error->find("parameter") != std::string::npos);
  CHECK_FALSE(takeLapackError().has_value());  // taking clears the record
}

TEST_CASE("a one-sample HRBF fit (nothing left after the polynomial) solves without LAPACK output") {
  // One 3D sample with a linear polynomial: 4 unknowns, 4 polynomial coefficients, so the
  // nullspace-Cholesky block is empty.
  HermiteSamples<3> s;
  s.points = Points<3>::Zero(3, 1);
  s.normals = Points<3>::Zero(3, 1);
  s.normals(2, 0) = 1;
  HrbfModel<3> model;
  FitReport report;
  const std::string out = capturedStdout([&] {
    model = fitHrbf<3>(s, {{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0, SolverChoice::Auto}, &report);
  });
  CHECK(out.empty());
  Vec<3> g;
  const double f = model.evaluate(Vec<3>(0, 0, 0), &g);
  CHECK(std::abs(f) <= 1e-12);
  CHECK((g - Vec<3>(0, 0, 1)).norm() <= 1e-12);
  CHECK_FALSE(takeLapackError().has_value());
}
