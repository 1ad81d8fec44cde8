#include <doctest/doctest.h>

#include "core/base/errors.h"
#include "render/gl/offscreen.h"
#include "render/gl/shader_library.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

namespace {

bool pixelIs(const ImageRgba8& image, int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
  const std::uint8_t* p = image.at(x, y);
  return p[0] == r && p[1] == g && p[2] == b && p[3] == a;
}

int countPixels(const ImageRgba8& image, int y0, int y1, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  int count = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = 0; x < image.width; ++x) count += pixelIs(image, x, y, r, g, b, 255) ? 1 : 0;
  }
  return count;
}

}  // namespace

TEST_CASE("clear colour reads back as exact bytes, row 0 = top") {
  for (const char* backend : {"osmesa", "egl"}) {
    if (std::string(backend) == "egl" && testing::skipEgl()) continue;
    CAPTURE(backend);
    auto context = testing::makeTestContext(backend);
    OffscreenTarget target(16, 12);
    target.bind();
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    // Top half red: in GL's bottom-left coordinates that is y in [6, 12).
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 6, 16, 6);
    glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    const ImageRgba8 image = target.read();
    REQUIRE(image.width == 16);
    REQUIRE(image.height == 12);
    REQUIRE(image.pixels.size() == 16u * 12u * 4u);
    CHECK(countPixels(image, 0, 6, 255, 0, 0) == 16 * 6);
    CHECK(countPixels(image, 6, 12, 0, 0, 255) == 16 * 6);
    CHECK(pixelIs(image, 0, 0, 255, 0, 0, 255));
    CHECK(pixelIs(image, 15, 11, 0, 0, 255, 255));
  }
}

TEST_CASE("a fullscreen triangle with a solid colour gives exact bytes") {
  auto context = testing::makeTestContext();
  OffscreenTarget target(20, 10);
  Program program = buildProgram({"fullscreen.vert", "solid_color.frag"});
  VertexArray empty;
  target.bind();
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  // 51/255 = 0.2 and 153/255 = 0.6 are exact in 8 bits.
  program.setUniform("u_color", glm::vec4(51.0f / 255.0f, 153.0f / 255.0f, 1.0f, 1.0f));
  program.use();
  empty.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  checkGl("fullscreen triangle");
  const ImageRgba8 image = target.read();
  CHECK(countPixels(image, 0, 10, 51, 153, 255) == 20 * 10);

  SUBCASE("geometry in the top half lands in rows 0..H/2") {
    glClear(GL_COLOR_BUFFER_BIT);
    glViewport(0, 5, 20, 5);  // GL y up: the top five rows
    glDrawArrays(GL_TRIANGLES, 0, 3);
    const ImageRgba8 half = target.read();
    CHECK(countPixels(half, 0, 5, 51, 153, 255) == 20 * 5);
    CHECK(countPixels(half, 5, 10, 0, 0, 0) == 20 * 5);
  }
}

TEST_CASE("the same drawing on osmesa and egl gives the same bytes") {
  if (testing::skipEgl()) return;
  ImageRgba8 images[2];
  int i = 0;
  for (const char* backend : {"osmesa", "egl"}) {
    auto context = testing::makeTestContext(backend);
    OffscreenTarget target(8, 8);
    Program program = buildProgram({"fullscreen.vert", "solid_color.frag"});
    VertexArray empty;
    target.bind();
    glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    program.setUniform("u_color", glm::vec4(0.0f, 0.4f, 0.8f, 1.0f));
    program.use();
    empty.bind();
    glViewport(2, 2, 4, 4);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    images[i++] = target.read();
  }
  CHECK(images[0] == images[1]);
}

TEST_CASE("an offscreen target larger than the GL limit is an environment error") {
  auto context = testing::makeTestContext();
  CHECK_THROWS_AS(OffscreenTarget(1 << 20, 4), EnvironmentError);
  CHECK_THROWS_AS(OffscreenTarget(0, 4), EnvironmentError);
}
