#include <doctest/doctest.h>

#include <cstdio>

#include "app/commands/bench_tracer.h"

using namespace hermite::app;

TEST_CASE("implicit tracer: bench figures" * doctest::skip()) {
  const TracerBenchResult r = benchTracer();
  std::printf("bake %d^3 N=%d: %.1f ms; trace %dx%d N=%d: %.1f ms; refine: %.1f ms (%d hit pixels)\n",
              r.bakeResolution, r.bakeCentres, r.bakeMs, r.width, r.height, r.traceCentres, r.traceMs, r.refineMs,
              r.hitPixels);
}
