#pragma once
// Drawing into an offscreen framebuffer and reading it back with row 0 = top (docs/maths.md, Conventions).

#include "core/trace/image.h"
#include "render/gl/gl_objects.h"

namespace hermite::render {

// A width x height RGBA8 (+ depth) framebuffer object. Works in every context, including the
// surfaceless ones that have no default framebuffer.
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height, bool with_depth = true);

  // Binds the framebuffer for drawing and sets the viewport to all of it.
  void bind() const;
  // Waits for drawing to finish and reads the colour attachment, flipped so row 0 = top.
  ImageRgba8 read() const;

  int width() const { return framebuffer_.width(); }
  int height() const { return framebuffer_.height(); }
  const Framebuffer& framebuffer() const { return framebuffer_; }

 private:
  Framebuffer framebuffer_;
};

}  // namespace hermite::render
