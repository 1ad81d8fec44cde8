#pragma once
// Wall-clock timing of the figures the reports and benches print.

#include <chrono>

namespace hermite {

// Milliseconds of the steady clock since t0.
inline double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace hermite
