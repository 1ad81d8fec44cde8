#include "io/png_file.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>

#include "core/base/errors.h"
#include "io/atomic_file.h"
#include "io/mesh_file.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace hermite {

namespace {

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}

}  // namespace

std::string encodePng(const ImageRgba8& image) {
  if (image.width < 1 || image.height < 1 || image.pixels.size() != std::size_t(image.width) * image.height * 4)
    throw EnvironmentError("PNG encoding: image is empty or its pixel buffer has the wrong size");
  std::string bytes;
  const int ok = stbi_write_png_to_func(appendBytes, &bytes, image.width, image.height, 4, image.pixels.data(),
                                        image.width * 4);
  if (!ok) throw EnvironmentError("PNG encoding failed");
  return bytes;
}

void writePng(const std::string& path, const ImageRgba8& image) {
  if (lowercaseExtension(path) != ".png")
    throw InputError(path + ": cannot write an image with the extension '" + lowercaseExtension(path) +
                     "' (supported: .png)");
  std::string bytes;
  try {
    bytes = encodePng(image);
  } catch (const EnvironmentError& e) {
    throw EnvironmentError(path + ": " + e.what());
  }
  writeFileAtomically(path, bytes);  // EnvironmentError names the path
}

ImageRgba8 readPng(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw EnvironmentError(path + ": cannot open PNG for reading");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h,
                                        &channels, 4);
  if (!data) throw EnvironmentError(path + ": not a readable PNG (" + std::string(stbi_failure_reason()) + ")");
  ImageRgba8 image(w, h);
  std::copy(data, data + std::size_t(w) * h * 4, image.pixels.begin());
  stbi_image_free(data);
  return image;
}

void writeDiffImage(const std::string& path, const ImageRgba8& a, const ImageRgba8& b, int tolerance) {
  writePng(path, diffImage(a, b, tolerance));
}

}  // namespace hermite
