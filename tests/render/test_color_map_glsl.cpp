// shaders/color_map.glsl holds the diverging map's stops as GLSL constants (uniforms are slower
// on llvmpipe); this keeps them equal to core/trace/color_map.h, the one definition the CPU
// reference, the legend and the tests use.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "core/trace/color_map.h"
#include "render/gl/offscreen.h"
#include "render/gl/shader_library.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

TEST_CASE("the GLSL diverging colour map gives core's colours at every position") {
  auto context = testing::makeTestContext();
  constexpr int kWidth = 256;
  constexpr float kLo = -1.25f, kHi = 1.25f;  // past both ends: the clamp is checked too
  const std::string fragment =
      "#include \"color_map.glsl\"\n"
      "out vec4 colour;\n"
      "void main() {\n"
      "  float t = mix(" + std::to_string(kLo) + ", " + std::to_string(kHi) + ", gl_FragCoord.x / " +
      std::to_string(kWidth) + ".0);\n"
      "  colour = vec4(divergingColorAt(t), 1.0);\n"
      "}\n";
  const Program program = buildProgram(
      {ShaderSource{GL_VERTEX_SHADER, std::string(shaderSource("fullscreen.vert")), "fullscreen.vert"},
       ShaderSource{GL_FRAGMENT_SHADER, fragment, "colour_map_probe.frag"}});
  OffscreenTarget target(kWidth, 1, false);
  target.bind();
  VertexArray empty;
  program.use();
  empty.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  const ImageRgba8 image = target.read();

  int worst = 0;
  for (int i = 0; i < kWidth; ++i) {
    const double t = double(kLo) + (double(kHi) - double(kLo)) * (i + 0.5) / kWidth;  // pixel centre
    const Vec<3> expected = divergingColorAt(t);
    for (int k = 0; k < 3; ++k) {
      const int want = int(std::lround(255.0 * expected(k)));
      worst = std::max(worst, std::abs(int(image.at(i, 0)[k]) - want));
    }
  }
  CHECK(worst <= 1);  // bytes: float rounding of the shader, nothing more
}
