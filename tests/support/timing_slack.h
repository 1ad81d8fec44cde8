#pragma once
// How much slower this build runs than the Release build that timing bounds are written for:
// the sanitizer build (AddressSanitizer + UBSan, `make test-sanitize`) instruments every memory
// access and runs Eigen-heavy code 4–5 times slower (the 2 000-edge hole: 5 s → 26 s). Bounds on
// wall time (hang guards, gaps between progress reports) scale by it; bounds on results do not.

namespace hermite::testing {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr double kTimingSlack = 5.0;
#else
inline constexpr double kTimingSlack = 1.0;
#endif

}  // namespace hermite::testing
