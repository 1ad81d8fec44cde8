// libFuzzer target for the point-file reader (scripts/fuzz.sh builds and runs it): the text
// formats .xyz / .pwn (3D, with or without normals), .xyn (2D) and probe files. Any input must
// either give finite samples with unit normals or throw InputError: a crash, a sanitizer report,
// another exception type or a hang is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/errors.h"
#include "fuzz_check.h"
#include "io/point_file.h"

namespace {

template <int Dim>
void checkSamples(const hermite::HermiteSamples<Dim>& s) {
  using hermite::fuzz::require;
  require(s.points.cols() > 0 && s.points.cols() == s.normals.cols(), "one normal per point");
  require(s.points.allFinite() && s.normals.allFinite(), "finite samples");
  for (Eigen::Index i = 0; i < s.normals.cols(); ++i)
    require(std::abs(s.normals.col(i).norm() - 1) < 1e-9, "unit normals");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> warnings;
  try {
    checkSamples(hermite::parsePointText3d(bytes, "fuzz.xyz", warnings));
  } catch (const hermite::InputError&) {
  }
  try {
    checkSamples(hermite::parsePointText2d(bytes, "fuzz.xyn", warnings));
  } catch (const hermite::InputError&) {
  }
  try {
    hermite::fuzz::require(hermite::parseProbeText3d(bytes, "fuzz.txt").allFinite(), "finite probes");
  } catch (const hermite::InputError&) {
  }
  return 0;
}
