#pragma once
// Pieces shared by the mesh and point-set readers (io_off, io_obj, io_ply, io_gltf): reading a
// whole file into memory, rejecting text that is not ASCII / UTF-8, parsing numbers without
// locale or allocation, and the checks every reader's result must pass. Every error is an
// InputError whose message starts with the file name.

#include <cstdint>
#include <optional>
#include <utility>
#include <string>
#include <string_view>

#include "core/mesh/tri_mesh.h"

namespace hermite {

// The whole file (readInputFile: regular files only, within the size cap). InputError also when
// it is empty (`what` names the format in the messages, e.g. "PLY").
std::string readFileBytes(const std::string& path, std::string_view what);

// InputError when `bytes` look like UTF-16 or UTF-32 text (a byte-order mark, or NUL bytes in
// the first kilobyte) instead of ASCII / UTF-8, which is all the text formats accept. `what`
// names the text in the message: "OBJ files", "a PLY header".
void requireSingleByteText(std::string_view bytes, const std::string& path, std::string_view what);

// Strict number parsing of one whole token (no leading '+' except before a digit or '.', no
// trailing characters). Return false when the token is not of that form; a double may be
// non-finite ("nan", "inf") — the caller decides whether that is allowed.
bool parseDouble(std::string_view token, double& value);
bool parseInteger(std::string_view token, std::int64_t& value);

// The lines of a text, one at a time: a UTF-8 byte-order mark at the start and a trailing '\r'
// (CRLF files) are dropped. With `bareCrEndsLine`, a '\r' not followed by '\n' ends a line too
// (old Mac files), as tinyobjloader reads them. No copies; the views point into the text.
class TextLines {
 public:
  explicit TextLines(std::string_view text, std::size_t start = 0, bool bareCrEndsLine = false);
  // False at the end of the text; otherwise `line` is the next line (without its '\n').
  bool next(std::string_view& line);
  // 1-based number of the line `next` returned last (counting from `start`'s line as 1).
  long number() const { return number_; }
  // Byte offset just past the line `next` returned last (its '\n' included).
  std::size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_;
  long number_ = 0;
  bool bareCrEndsLine_;
};

// The blank-separated tokens of one line (blanks: space, tab, '\r', '\v', '\f').
class Tokens {
 public:
  explicit Tokens(std::string_view line) : line_(line) {}
  bool next(std::string_view& token);
  // Everything not yet consumed.
  std::string_view rest() const { return line_.substr(pos_); }

 private:
  std::string_view line_;
  std::size_t pos_ = 0;
};

bool isBlankChar(char c);

// Checks and completes what every reader returns, so a caller can rely on it:
//  - every vertex coordinate finite ("vertex I has a non-finite coordinate");
//  - every triangle index in [0, V) ("triangle T refers to vertex I, but there are V vertices");
//  - normals: 3 × V or 3 × 0; each finite, then normalised to unit length. A zero normal is what
//    `zero` says: a reader keeps it as a zero column (the file gives no direction for that vertex;
//    readMeshFileSamples completes it), a writer refuses it ("the normal of vertex I is zero").
enum class ZeroNormals { Keep, Reject };
void checkAndNormalizeMesh(TriMesh& mesh, const std::string& path, ZeroNormals zero);

// The first coordinate (column, row) of `points` (3 × N) that a float cannot hold (its float
// rounding is infinite: |v| ≥ about 3.4028236e38); nullopt when all fit.
std::optional<std::pair<Eigen::Index, int>> firstBeyondFloatRange(const Eigen::Matrix3Xd& points);

// Largest element count a reader accepts in one file (TriMesh indexes with int).
constexpr std::int64_t kMaxMeshElements = 2'000'000'000;

}  // namespace hermite
