#include <doctest/doctest.h>

#include "app/commands/bench_field2d.h"

using namespace hermite;

// Not a timed test (docs/design.md, Testing): skipped unless run with --no-skip; prints the figures.
TEST_CASE("2D field view bench: refit + redraw of a 200-point curve at 512x512" * doctest::skip()) {
  for (double scale : {1.0, 0.5, 0.25}) {
    for (KernelType k : {KernelType::Cubic, KernelType::Gaussian}) {
      Field2dBenchOptions o;
      o.gridScale = scale;
      o.kernel = Kernel{k, 0.2};
      const Field2dBenchResult r = benchField2dRefitRedraw(o);
      MESSAGE(kernelName(k) << " grid " << scale << ": total " << r.medianMs << " ms (fit " << r.fitMs << ", evaluate "
                            << r.evaluateMs << ", upload + draw " << r.drawMs << ")");
      CHECK(r.medianMs > 0);
    }
  }
}
