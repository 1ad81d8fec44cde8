#pragma once
// What the glTF reader may read besides the .gltf / .glb itself: buffer and image URIs that,
// after percent-decoding, name a regular file inside the glTF file's own folder (or a subfolder).
// Absolute paths, `file:` and every other scheme, and `..` that leaves the folder (also through
// a symlink: canonical paths are compared) are refused with an InputError naming the glTF file
// and the URI. data: URIs are decoded by tinygltf and never reach this code. The file is read by
// readInputFile (regular files only, size cap).

#include <filesystem>
#include <string>
#include <string_view>

namespace tinygltf {
class TinyGLTF;
}

namespace hermite {

// The file `decodedUri` names for the glTF file at `gltfPath`; InputError when the policy
// above refuses it. The file itself need not exist.
std::filesystem::path resolveGltfUri(std::string_view decodedUri, const std::string& gltfPath);

// File callbacks for one load of `gltfPath`. tinygltf looks a URI up in the base directory it
// is given and then in the working directory: baseDirectory() is a marker that the callbacks
// recognise, so they see the URI exactly as decoded and never search the working directory.
class GltfFileAccess {
 public:
  explicit GltfFileAccess(std::string gltfPath) : gltfPath_(std::move(gltfPath)) {}
  GltfFileAccess(const GltfFileAccess&) = delete;
  GltfFileAccess& operator=(const GltfFileAccess&) = delete;

  // Installs the callbacks on `loader`; this object must outlive every load through it.
  void install(tinygltf::TinyGLTF& loader);
  static const std::string& baseDirectory();

  // Throws the first refusal or read error of the load (tinygltf only warns about an image it
  // cannot read, and words its own errors without the reason).
  void throwIfFailed() const;

  // Callback bodies (public for the C callbacks in the .cpp).
  bool exists(const std::string& joined);
  bool read(std::string& bytes, const std::string& joined);

 private:
  std::string gltfPath_;
  std::string failure_;  // first refusal or read error, a whole message
};

}  // namespace hermite
