#pragma once
// Numbers in messages: the shortest decimal that reads back as the same double.

#include <string>

namespace hermite {

// std::to_chars' shortest round-trip form: 0.1 → "0.1", 1e300 → "1e+300", NaN → "nan".
std::string formatNumber(double v);

}  // namespace hermite
