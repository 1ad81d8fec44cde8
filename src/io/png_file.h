#pragma once
// RGBA8 images as PNG files (stb_image / stb_image_write).

#include <string>

#include "core/trace/image.h"

namespace hermite {

// PNG bytes of the image (stb_image_write). EnvironmentError if encoding fails.
std::string encodePng(const ImageRgba8& image);
// Writes a PNG through writeFileAtomically; InputError for a path not ending in .png (any case),
// EnvironmentError naming the path on failure.
void writePng(const std::string& path, const ImageRgba8& image);
// Reads any PNG as RGBA8. EnvironmentError naming the path when it cannot be read or decoded.
ImageRgba8 readPng(const std::string& path);

// writePng(path, diffImage(a, b, tolerance)).
void writeDiffImage(const std::string& path, const ImageRgba8& a, const ImageRgba8& b, int tolerance);

}  // namespace hermite
