#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "core/base/blas_setup.h"

int main(int argc, char** argv) {
  hermite::reexecWithTunedBlas(argv);
  return doctest::Context(argc, argv).run();
}
