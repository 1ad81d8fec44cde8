#include <doctest/doctest.h>

#include <string>

#include "core/base/errors.h"
#include "io/obj_file.h"

using hermite::InputError;

namespace {

// Replaces every "\n" of `text` by `end`.
std::string withLineEnds(const std::string& text, const std::string& end) {
  std::string out;
  for (char c : text) out += c == '\n' ? end : std::string(1, c);
  return out;
}

const std::string kQuad =
    "# quad\nv 0 0 0\nv 1 0 0.1\nv 1 1 0.2\nv 0 1 0.3\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n"
    "f 1//1 2//2 3//3 4//4\n";

}  // namespace

TEST_CASE("obj_file: LF, CRLF and bare CR line ends read the same mesh") {
  const hermite::TriMesh lf = hermite::readObj(kQuad, "quad.obj");
  REQUIRE(lf.vertexCount() == 4);
  REQUIRE(lf.triangleCount() == 2);
  for (const char* end : {"\r\n", "\r"}) {
    CAPTURE(end[1] == '\n' ? "CRLF" : "CR");
    const hermite::TriMesh other = hermite::readObj(withLineEnds(kQuad, end), "quad.obj");
    CHECK(other.vertices == lf.vertices);
    CHECK(other.normals == lf.normals);
    CHECK(other.triangles == lf.triangles);
  }
  // A byte-order mark does not hide the first vertex from either parser.
  CHECK(hermite::readObj("\xEF\xBB\xBF" + withLineEnds(kQuad, "\r"), "quad.obj").vertices == lf.vertices);
}

TEST_CASE("obj_file: a bad number is named with its line whatever the line ends") {
  for (const char* end : {"\n", "\r\n", "\r"}) {
    CHECK_THROWS_WITH_AS(hermite::readObj(withLineEnds("v 0 0 0\nv abc 1 0\nv 0 1 0\nf 1 2 3\n", end), "a.obj"),
                         "a.obj:2: 'abc' is not a number", InputError);
    CHECK_THROWS_WITH_AS(hermite::readObj(withLineEnds("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", end), "a.obj"),
                         "a.obj:2: 'v' has 2 numbers, expected 3 (x y z)", InputError);
  }
}

TEST_CASE("obj_file: a line tinyobjloader would skip or read differently is an error, never a silent 0") {
  CHECK_THROWS_WITH_AS(hermite::readObj("v 0 0 0\nv\v1 0 0\nv 0 1 0\nf 1 2 3\n", "a.obj"),
                       "a.obj:2: 'v' must start the line (after spaces or tabs) and be followed by a space or a tab", InputError);
  CHECK_THROWS_WITH_AS(hermite::readObj("v 0 0 0\n\fvn 1 0 0\n", "a.obj"),
                       "a.obj:2: 'vn' must start the line (after spaces or tabs) and be followed by a space or a tab", InputError);
  const std::string huge(1'000'000, '9');
  CHECK_THROWS_WITH_AS(hermite::readObj("v 0 0 " + huge + "x\n", "a.obj"),
                       ("a.obj:1: '" + std::string(60, '9') + "…' (1000001 bytes) is not a number").c_str(), InputError);
}
