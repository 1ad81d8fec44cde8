#pragma once
// Runs the real hermite-lab executable (HERMITE_EXE) and captures exit code, stdout, stderr.

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace hermite::testing {

struct CliResult {
  int rc = -1;
  std::string out;
  std::string err;
};

inline std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// `args` is appended to the executable path verbatim (shell syntax); stdout goes to `stdoutPath`
// (a temporary file when empty) and stderr to a temporary file.
inline CliResult runCli(const std::string& args, const std::string& stdoutPath = "") {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() / ("hermite_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string base = (dir / std::to_string(counter++)).string();
  const std::string out = stdoutPath.empty() ? base + ".out" : stdoutPath;
  const std::string cmd = std::string(HERMITE_EXE) + " " + args + " > " + out + " 2> " + base + ".err";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readAll(base + ".out");
  r.err = readAll(base + ".err");
  fs::remove(base + ".out");
  fs::remove(base + ".err");
  return r;
}

inline std::string writeTemp(const std::string& name, const std::string& contents) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("hermite_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << contents;
  return p.string();
}

}  // namespace hermite::testing
