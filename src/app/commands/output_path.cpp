#include "app/commands/output_path.h"

#include <filesystem>

#include "core/base/errors.h"
#include "io/mesh_file.h"

namespace hermite::app {

std::string lowerExtension(const std::string& path) {
  std::string ext = lowercaseExtension(path);
  if (!ext.empty()) ext.erase(0, 1);
  return ext;
}

std::string requireExtension(const std::string& command, const std::string& path,
                             const std::vector<std::string>& accepted) {
  const std::string ext = lowerExtension(path);
  for (const std::string& a : accepted)
    if (ext == a) return ext;
  std::string list;
  for (const std::string& a : accepted) list += (list.empty() ? "." : ", .") + a;
  throw UsageError(command + ": cannot write '" + path + "': unknown extension '" + (ext.empty() ? "" : "." + ext) +
                   "' (expected " + list + ")");
}

void requireWritableLocation(const std::string& command, const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  if (p.filename().empty()) throw EnvironmentError(command + ": cannot write '" + path + "': not a file name");
  const fs::path dir = p.parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw EnvironmentError(command + ": cannot write '" + path + "': directory '" + dir.string() + "' does not exist");
  if (fs::is_directory(p, ec)) throw EnvironmentError(command + ": cannot write '" + path + "': it is a directory");
}

}  // namespace hermite::app
