#include "io/gltf_file_access.h"

#include <tiny_gltf.h>

#include <cctype>
#include <vector>

#include "core/base/errors.h"
#include "io/mesh_format_common.h"
#include "io/quoted_token.h"

namespace hermite {

namespace {

namespace fs = std::filesystem;

// RFC 3986 scheme: a letter, then letters, digits, '+', '-', '.', then ':'.
bool hasScheme(std::string_view uri) {
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
  for (char c : uri.substr(1)) {
    if (c == ':') return true;
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  return false;
}

// True when `inner`, made of canonical components, lies in `folder` or below it.
bool isInside(const fs::path& inner, const fs::path& folder) {
  auto i = inner.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++i)
    if (i == inner.end() || *i != *f) return false;
  return true;
}

[[noreturn]] void refuse(const std::string& gltfPath, std::string_view uri, const std::string& reason) {
  throw InputError(gltfPath + ": uri " + quotedToken(uri) + " " + reason +
                   "; a glTF file may only refer to data: URIs and to files in its own folder");
}

fs::path folderOf(const std::string& gltfPath) {
  const fs::path folder = fs::path(gltfPath).parent_path();
  return folder.empty() ? fs::path(".") : folder;
}

// The URI behind a path tinygltf joined from baseDirectory() and the decoded URI; false for a
// path it joined from another directory (its working-directory fallback).
bool uriOf(const std::string& joined, std::string& uri) {
  const std::string& marker = GltfFileAccess::baseDirectory();
  if (joined.size() <= marker.size() || joined.compare(0, marker.size(), marker) != 0 || joined[marker.size()] != '/')
    return false;
  uri = joined.substr(marker.size() + 1);
  return true;
}

GltfFileAccess& self(void* userData) { return *static_cast<GltfFileAccess*>(userData); }

bool fileExistsCallback(const std::string& joined, void* userData) { return self(userData).exists(joined); }

std::string expandPathCallback(const std::string& path, void*) { return path; }

bool readCallback(std::vector<unsigned char>* out, std::string* err, const std::string& joined, void* userData) {
  std::string bytes;
  if (!self(userData).read(bytes, joined)) {
    if (err) *err += "refused or unreadable (see the reason above)\n";
    return false;
  }
  out->assign(bytes.begin(), bytes.end());
  return true;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing files is not used by this reader\n";
  return false;
}

}  // namespace

fs::path resolveGltfUri(std::string_view uri, const std::string& gltfPath) {
  if (uri.empty()) refuse(gltfPath, uri, "is empty");
  if (uri.find('\0') != std::string_view::npos) refuse(gltfPath, uri, "contains a NUL byte");
  if (hasScheme(uri)) refuse(gltfPath, uri, "has a scheme (" + shortenedToken(uri.substr(0, uri.find(':') + 1)) + ")");
  const fs::path relative(uri);
  if (relative.is_absolute() || uri[0] == '/') refuse(gltfPath, uri, "is an absolute path");
  const fs::path normal = relative.lexically_normal();
  if (!normal.empty() && *normal.begin() == "..") refuse(gltfPath, uri, "leaves the folder of the glTF file ('..')");
  const fs::path folder = folderOf(gltfPath);
  const fs::path file = folder / relative;
  std::error_code ec;
  const fs::path canonicalFolder = fs::weakly_canonical(folder, ec);
  if (ec) refuse(gltfPath, uri, "cannot be resolved (" + ec.message() + ")");
  const fs::path canonicalFile = fs::weakly_canonical(file, ec);
  if (ec) refuse(gltfPath, uri, "cannot be resolved (" + ec.message() + ")");
  if (!isInside(canonicalFile, canonicalFolder))
    refuse(gltfPath, uri,
           "resolves to " + canonicalFile.string() + ", outside the folder of the glTF file (a symlink?)");
  return file;
}

const std::string& GltfFileAccess::baseDirectory() {
  static const std::string marker = "\x1Fhermite-gltf-folder";
  return marker;
}

void GltfFileAccess::install(tinygltf::TinyGLTF& loader) {
  tinygltf::FsCallbacks callbacks{};
  callbacks.FileExists = &fileExistsCallback;
  callbacks.ExpandFilePath = &expandPathCallback;
  callbacks.ReadWholeFile = &readCallback;
  callbacks.WriteWholeFile = &refuseWrite;
  callbacks.user_data = this;
  loader.SetFsCallbacks(callbacks);
}

void GltfFileAccess::throwIfFailed() const {
  if (!failure_.empty()) throw InputError(failure_);
}

bool GltfFileAccess::exists(const std::string& joined) {
  std::string uri;
  if (!uriOf(joined, uri)) return false;
  try {
    const fs::path file = resolveGltfUri(uri, gltfPath_);
    std::error_code ec;
    // Anything that exists goes on to read(), which names a FIFO or a device as such. A missing
    // file is tinygltf's to report: an error for a buffer, a warning for an image.
    return fs::exists(fs::symlink_status(file, ec));
  } catch (const InputError& e) {
    if (failure_.empty()) failure_ = e.what();
  }
  return false;
}

bool GltfFileAccess::read(std::string& bytes, const std::string& joined) {
  std::string uri;
  if (!uriOf(joined, uri)) return false;
  try {
    const fs::path file = resolveGltfUri(uri, gltfPath_);
    bytes = readFileBytes(file.string(), "glTF buffer or image");
    return true;
  } catch (const InputError& e) {
    if (failure_.empty()) failure_ = gltfPath_ + ": uri " + quotedToken(uri) + ": " + e.what();
    return false;
  }
}

}  // namespace hermite
