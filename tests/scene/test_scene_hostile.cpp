#include <doctest/doctest.h>

#include <string>

#include "core/base/errors.h"
#include "scene/scene_file.h"

using hermite::InputError;

TEST_CASE("scene_file: a number beyond double range is an input error naming the key") {
  CHECK_THROWS_WITH_AS(
      hermite::parseSceneText(R"({"version": 1, "mode": "implicit3d", "fit": {"radius": 1e400}})", "s.json"),
      "s.json: fit.radius: number out of range (number overflow parsing '1e400'); numbers must lie within "
      "±1.7976931348623157e308",
      InputError);
  const std::string digits(100000, '9');
  CHECK_THROWS_WITH_AS(
      hermite::parseSceneText(R"({"version": 1, "view": {"size": [)" + digits + "e999]}}", "s.json"),
      ("s.json: view.size: number out of range (number overflow parsing '" + std::string(60, '9') +
       "…' (100004 bytes)); numbers must lie within ±1.7976931348623157e308")
          .c_str(),
      InputError);
}

TEST_CASE("scene_file: huge tokens and deep nesting give short messages, never a crash") {
  const std::string key(20'000'000, 'k');
  const std::string message = [&] {
    try {
      hermite::parseSceneText(R"({"version": 1, ")" + key + R"(": 1})", "s.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("<no error>");
  }();
  CHECK(message.size() < 600);
  CHECK(message.find("s.json: " + std::string(60, 'k') + "… (20000000 bytes): unknown key") == 0);
  // A bad literal after a long token: the "last read" part is shortened too.
  const std::string bad = [&] {
    try {
      hermite::parseSceneText(R"({"version": 1, "mode": ")" + std::string(1'000'000, 'x') + "\n\"}", "s.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("<no error>");
  }();
  CHECK(bad.size() < 600);
  CHECK(bad.find("s.json:1:") == 0);
  // 100 000 nested arrays: parsed without recursion, refused by the key check.
  const std::string deep = R"({"version": 1, "mode": "implicit3d", "view": {"size": )" + std::string(100000, '[') +
                           std::string(100000, ']') + "}}";
  CHECK_THROWS_AS(hermite::parseSceneText(deep, "s.json"), InputError);
}
