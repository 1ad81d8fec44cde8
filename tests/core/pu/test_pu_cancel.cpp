// Cancel reaches the partition-of-unity set-up, not only the box fits: subdividing and measuring
// the reach of 200 000 samples takes about half a second on this machine (docs/performance.md),
// and a cancel must stop a fit within 200 ms wherever it arrives.

#include <doctest/doctest.h>

#include <chrono>
#include <thread>

#include "core/base/cancel_token.h"
#include "core/base/ms_since.h"
#include "core/pu/pu_model.h"
#include "core/shapes/presets.h"

using namespace hermite;

namespace {

PuOptions cubicLinear(const CancelToken* token) {
  PuOptions o;
  o.local = HrbfOptions{Kernel{KernelType::Cubic, 1.0}, Polynomial::Linear, 0.0};
  o.local.cancel = token;
  return o;
}

}  // namespace

TEST_CASE("pu cancel: a token set before the fit stops it in the set-up, before any box is fitted") {
  const HermiteSamples<3> s = makePreset3d("sphere", 200000);
  CancelToken token;
  token.cancel();
  const auto t0 = std::chrono::steady_clock::now();
  CHECK_THROWS_AS(fitPu<3>(s, cubicLinear(&token)), Cancelled);
  const double ms = msSince(t0);
  MESSAGE("pre-cancelled PU fit of 200 000 samples stopped after ", ms, " ms");
  // The first poll comes after 256 splits (about a millisecond); the whole set-up is ~0.5 s.
  CHECK(ms < 100);
}

TEST_CASE("pu cancel: a cancel during the set-up of 200 000 samples stops the fit within 200 ms") {
  const HermiteSamples<3> s = makePreset3d("sphere", 200000);
  CancelToken token;
  std::chrono::steady_clock::time_point set{};
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(40));  // inside the set-up (tree, reach)
    set = std::chrono::steady_clock::now();
    token.cancel();
  });
  bool cancelled = false;
  try {
    fitPu<3>(s, cubicLinear(&token));
  } catch (const Cancelled&) {
    cancelled = true;
  }
  const double ms = msSince(set);
  canceller.join();
  CHECK(cancelled);
  MESSAGE("PU fit of 200 000 samples stopped ", ms, " ms after cancel()");
  CHECK(ms < 200);
}
