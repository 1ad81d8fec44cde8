#include "app/commands/error_report.h"

#include <cstdio>
#include <cstring>
#include <regex>

#include <nlohmann/json.hpp>

#include "app/commands/output.h"

namespace hermite::app {

namespace {

bool jsonRequested = false;

// A key path as the scene reader writes it: fit.radius, data.points[3], view.camera.eye.
bool looksLikeKey(const std::string& s) {
  static const std::regex key(R"([A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*|\[[0-9]+\])*)");
  return std::regex_match(s, key);
}

}  // namespace

void noteJsonRequested(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--json") == 0) jsonRequested = true;
}

ErrorPlace errorPlace(const std::string& message) {
  ErrorPlace p;
  // FILE:LINE[:COLUMN]: …  (a file name without spaces, then a line number)
  static const std::regex withLine(R"(^([^\s:][^:]*):([0-9]+)(:[0-9]+)?: )");
  std::smatch m;
  if (std::regex_search(message, m, withLine)) {
    p.file = m[1];
    p.line = std::stoi(m[2]);
    return p;
  }
  // FILE: KEY: …  or  FILE: …  (the first part names a file when it has a dot or a slash)
  const std::size_t first = message.find(": ");
  if (first == std::string::npos) return p;
  const std::string head = message.substr(0, first);
  if (head.find_first_of("./") == std::string::npos || head.find(' ') != std::string::npos) return p;
  p.file = head;
  const std::size_t second = message.find(": ", first + 2);
  if (second != std::string::npos) {
    const std::string part = message.substr(first + 2, second - first - 2);
    if (looksLikeKey(part)) p.key = part;
  }
  return p;
}

int reportError(int exitCode, const std::string& prefix, const std::string& message) {
  std::fprintf(stderr, "%s: %s\n", prefix.c_str(), message.c_str());
  if (!jsonRequested) return exitCode;
  const ErrorPlace place = errorPlace(message);
  nlohmann::json out;
  out["error"] = message;
  out["exit_code"] = exitCode;
  out["file"] = place.file.empty() ? nlohmann::json(nullptr) : nlohmann::json(place.file);
  out["line"] = place.line > 0 ? nlohmann::json(place.line) : nlohmann::json(nullptr);
  out["key"] = place.key.empty() ? nlohmann::json(nullptr) : nlohmann::json(place.key);
  // Quoted bytes of a malformed file may not be UTF-8: replaced, never an exception here.
  writeStdout(out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  finishStdout();
  return exitCode;
}

}  // namespace hermite::app
