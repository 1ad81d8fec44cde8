#include "core/base/format_number.h"

#include <charconv>

namespace hermite {

std::string formatNumber(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

}  // namespace hermite
