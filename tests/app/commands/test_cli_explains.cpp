// A command line that explains itself: --version, suggestions for mistyped commands, errors as
// JSON on standard output with --json, and what render wrote (docs/cli.md, Output conventions).

#include <doctest/doctest.h>

#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands/error_report.h"
#include "support/cli_runner.h"

using hermite::testing::runCli;
using nlohmann::json;

namespace {

const std::string kScenes = std::string(HERMITE_SOURCE_DIR) + "/tests/fixtures/scenes/";

}  // namespace

TEST_CASE("cli: --version prints the version and exits 0") {
  const auto r = runCli("--version");
  CHECK(r.rc == 0);
  CHECK(std::regex_match(r.out, std::regex("hermite-lab [0-9]+\\.[0-9]+\\.[0-9]+\n")));
}

TEST_CASE("cli: a mistyped command names the command meant; the default command's hint is right") {
  const auto typo = runCli("fti " + kScenes + "minimal.json");
  CHECK(typo.rc == 2);
  CHECK(typo.err.find("unknown command 'fti' (did you mean 'fit'?)") != std::string::npos);
  const auto flag = runCli("--no-such-flag");
  CHECK(flag.rc == 2);
  CHECK(flag.err.find("run 'hermite-lab --help' for usage") != std::string::npos);
  CHECK(flag.err.find("hermite-lab hermite-lab") == std::string::npos);
}

TEST_CASE("cli: with --json an error is also a JSON object on standard output") {
  const auto bad = runCli("fit " + kScenes + "bad_radius.json --json");
  CHECK(bad.rc == 1);
  const json j = json::parse(bad.out);
  CHECK(j["exit_code"] == 1);
  CHECK(j["key"] == "fit.radius");
  CHECK(j["file"].get<std::string>().find("bad_radius.json") != std::string::npos);
  CHECK(j["error"].get<std::string>().find("must be > 0") != std::string::npos);
  CHECK(bad.err.find("error: ") == 0);  // the message stays on standard error

  const auto syntax = runCli("fit " + kScenes + "syntax_error.json --json");
  CHECK(syntax.rc == 1);
  const json s = json::parse(syntax.out);
  CHECK(s["line"] == 5);
  CHECK(s["key"].is_null());

  const auto usage = runCli("fit " + kScenes + "minimal.json --json --no-such-flag");
  CHECK(usage.rc == 2);
  CHECK(json::parse(usage.out)["exit_code"] == 2);

  const auto plain = runCli("fit " + kScenes + "bad_radius.json");
  CHECK(plain.rc == 1);
  CHECK(plain.out.empty());  // without --json nothing changes on standard output
}

TEST_CASE("cli: error places read from message prefixes") {
  using hermite::app::errorPlace;
  const auto a = errorPlace("scenes/a.json:12:5: JSON syntax error: x");
  CHECK(a.file == "scenes/a.json");
  CHECK(a.line == 12);
  const auto b = errorPlace("a.json: data.points[3]: must have 3 numbers");
  CHECK(b.file == "a.json");
  CHECK(b.key == "data.points[3]");
  const auto c = errorPlace("points.xyz: cannot read (it is a FIFO, not a regular file)");
  CHECK(c.file == "points.xyz");
  CHECK(c.key.empty());
  const auto d = errorPlace("sweep: no radius could be fitted");
  CHECK(d.file.empty());
}

TEST_CASE("cli: render says what it wrote on standard error, standard output stays empty") {
  const std::string out = (std::filesystem::temp_directory_path() / "hermite_cli_explains.png").string();
  const auto r = runCli("render " + kScenes + "square_2d.json --size 64x48 -o " + out);
  CHECK(r.rc == 0);
  CHECK(r.out.empty());
  CHECK(r.err.find("render: wrote " + out + " (64 x 48)") != std::string::npos);
  std::filesystem::remove(out);
}
