#include "app/cli.h"
#include "core/blas_setup.h"

int main(int argc, char** argv) {
  hermite::reexecWithTunedBlas(argv);
  return hermite::app::runCli(argc, argv);
}
