// libFuzzer target for the GLTF reader (scripts/fuzz.sh builds and runs it). Any input must
// either parse into a mesh that keeps TriMesh's promises or throw InputError: a crash, a
// sanitizer report, another exception type or a hang is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/base/errors.h"
#include "fuzz_check.h"
#include "io/gltf_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    hermite::fuzz::checkMesh(hermite::readGltf(bytes, "fuzz.gltf"));
  } catch (const hermite::InputError&) {
  }
  return 0;
}
