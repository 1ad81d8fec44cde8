// libFuzzer target for the scene reader (scripts/fuzz.sh builds and runs it): strict JSON with
// unique keys, then every key checked against its table. Any input must either give a Scene or
// throw InputError (UsageError for a malformed override): a crash, a sanitizer report, another
// exception type or a hang is a bug. No file is read: data.file is only resolved here.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/base/errors.h"
#include "scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const hermite::Scene scene = hermite::parseSceneText(text, "fuzz/scene.json");
    // What the writer makes of it must read back.
    (void)hermite::parseScene(hermite::sceneToJson(scene), "fuzz/again.json", "fuzz");
  } catch (const hermite::InputError&) {
  }
  return 0;
}
