#include "render/gl/offscreen.h"

#include <algorithm>
#include <cstring>

#include "core/base/errors.h"

namespace hermite::render {

OffscreenTarget::OffscreenTarget(int width, int height, bool with_depth) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (width <= 0 || height <= 0 || width > max_size || height > max_size) {
    throw EnvironmentError("offscreen size " + std::to_string(width) + "x" + std::to_string(height) +
                           " is outside 1.." + std::to_string(max_size) + " of this GL context");
  }
  framebuffer_ = Framebuffer(width, height, with_depth);
}

void OffscreenTarget::bind() const { framebuffer_.bind(); }

ImageRgba8 OffscreenTarget::read() const {
  ImageRgba8 image(width(), height());
  const std::size_t row_bytes = static_cast<std::size_t>(image.width) * 4;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glNamedFramebufferReadBuffer(framebuffer_.id(), GL_COLOR_ATTACHMENT0);
  GLint previous = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id());
  glReadPixels(0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous));
  checkGl("glReadPixels");
  // GL's row 0 is the bottom one.
  std::vector<std::uint8_t> swap(row_bytes);
  for (int top = 0, bottom = image.height - 1; top < bottom; ++top, --bottom) {
    std::uint8_t* a = image.pixels.data() + static_cast<std::size_t>(top) * row_bytes;
    std::uint8_t* b = image.pixels.data() + static_cast<std::size_t>(bottom) * row_bytes;
    std::memcpy(swap.data(), a, row_bytes);
    std::memcpy(a, b, row_bytes);
    std::memcpy(b, swap.data(), row_bytes);
  }
  return image;
}

}  // namespace hermite::render
