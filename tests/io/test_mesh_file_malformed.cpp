#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "core/base/errors.h"
#include "io/mesh_file.h"

namespace fs = std::filesystem;

// The corpus of tests/fixtures/malformed (written by make_malformed.py): every file must be
// refused with an InputError that names the file and says what is wrong (expected.txt).
TEST_CASE("mesh_io: every malformed fixture is an InputError naming the file and the fault") {
  const fs::path dir = fs::path(HERMITE_FIXTURES) / "malformed";
  std::map<std::string, std::string> expected;
  std::ifstream list(dir / "expected.txt");
  REQUIRE(list);
  std::string line;
  while (std::getline(list, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    REQUIRE(tab != std::string::npos);
    expected[line.substr(0, tab)] = line.substr(tab + 1);
  }
  REQUIRE(expected.size() >= 60);

  int checked = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name == "expected.txt" || name == "make_malformed.py" || entry.path().extension() == ".bin")
      continue;  // .bin: external buffers the .gltf fixtures refer to
    CAPTURE(name);
    const auto it = expected.find(name);
    REQUIRE_MESSAGE(it != expected.end(), "fixture without an expected message in expected.txt");
    const std::string path = entry.path().string();
    std::string message = "<no error>";
    try {
      hermite::loadMeshFile(path);
    } catch (const hermite::InputError& e) {
      message = e.what();
    }
    CAPTURE(message);
    CHECK(message.rfind(path, 0) == 0);  // starts with the file name
    CHECK(message.find(it->second) != std::string::npos);
    ++checked;
  }
  CHECK(checked == static_cast<int>(expected.size()));
}
