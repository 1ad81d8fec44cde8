#include "io/off_file.h"

#include <vector>

#include "core/base/errors.h"
#include "io/mesh_format_common.h"
#include "io/quoted_token.h"

namespace hermite {

namespace {

// Data lines of an OFF file: comments ('#' to the end of the line) and blank lines skipped.
class OffLines {
 public:
  OffLines(std::string_view bytes, const std::string& path) : lines_(bytes), path_(path) {}

  bool next(std::string_view& line) {
    while (lines_.next(line)) {
      const std::size_t hash = line.find('#');
      if (hash != std::string_view::npos) line = line.substr(0, hash);
      Tokens probe(line);
      std::string_view token;
      if (probe.next(token)) return true;
    }
    return false;
  }
  std::string where() const { return path_ + ":" + std::to_string(lines_.number()) + ": "; }

 private:
  TextLines lines_;
  const std::string& path_;
};

bool isOffKeyword(std::string_view token, bool& hasNormals, bool& unsupported) {
  // [ST][C][N][4][n]OFF: texture coordinates and colours are skipped, 4D / nD is not 3D.
  if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return false;
  const std::string_view prefix = token.substr(0, token.size() - 3);
  hasNormals = prefix.find('N') != std::string_view::npos;
  unsupported = prefix.find('4') != std::string_view::npos || prefix.find('n') != std::string_view::npos;
  for (char c : prefix)
    if (c != 'S' && c != 'T' && c != 'C' && c != 'N' && c != '4' && c != 'n') return false;
  return true;
}

std::int64_t parseCount(std::string_view token, const OffLines& lines, const char* what) {
  std::int64_t value = 0;
  if (!parseInteger(token, value) || value < 0)
    throw InputError(lines.where() + "the " + std::string(what) + " count " + quotedToken(token) +
                     " is not a non-negative integer");
  if (value > kMaxMeshElements)
    throw InputError(lines.where() + "the " + std::string(what) + " count " + std::to_string(value) +
                     " is larger than this reader supports (" + std::to_string(kMaxMeshElements) + ")");
  return value;
}

// The header: the optional [ST][C][N]OFF keyword and the vertex and face counts (the edge count
// is ignored), checked against what a file of `bytes` can hold.
struct OffHeader {
  std::int64_t vertices = 0, faces = 0;
  bool hasNormals = false;
};

OffHeader readHeader(OffLines& lines, std::size_t bytes, const std::string& path) {
  std::string_view line, token;
  if (!lines.next(line)) throw InputError(path + ": no OFF header or counts (only comments or blank lines)");
  Tokens tokens(line);
  tokens.next(token);
  OffHeader header;
  bool unsupported = false;
  if (isOffKeyword(token, header.hasNormals, unsupported)) {
    if (unsupported)
      throw InputError(lines.where() + quotedToken(token) +
                       " (4D or n-dimensional OFF) is not supported; only 3D OFF, COFF, NOFF, STOFF");
    // The counts may follow the keyword on the same line.
    if (!tokens.next(token)) {
      if (!lines.next(line)) throw InputError(path + ": ends after the OFF keyword; expected 'vertices faces edges'");
      tokens = Tokens(line);
      tokens.next(token);
    }
  }
  header.vertices = parseCount(token, lines, "vertex");
  if (!tokens.next(token)) throw InputError(lines.where() + "expected 'vertices faces [edges]' counts, got only one number");
  header.faces = parseCount(token, lines, "face");
  // A vertex line takes at least "0 0 0\n" (6 bytes), a face line "3 0 0 0\n" (8): a header
  // promising more than the file can hold is rejected before anything is allocated.
  if (header.vertices * 6 + header.faces * 8 > static_cast<std::int64_t>(bytes))
    throw InputError(lines.where() + "the header announces " + std::to_string(header.vertices) + " vertices and " +
                     std::to_string(header.faces) + " faces, more than a " + std::to_string(bytes) +
                     "-byte file can hold");
  return header;
}

// The vertex lines: x y z, and nx ny nz after them in NOFF.
void readVertices(OffLines& lines, const OffHeader& header, TriMesh& mesh, const std::string& path) {
  mesh.vertices.resize(3, header.vertices);
  if (header.hasNormals) mesh.normals.resize(3, header.vertices);
  const int valuesPerVertex = header.hasNormals ? 6 : 3;
  std::string_view line, token;
  for (std::int64_t i = 0; i < header.vertices; ++i) {
    if (!lines.next(line))
      throw InputError(path + ": ends after " + std::to_string(i) + " of the " + std::to_string(header.vertices) +
                       " vertices the header announces");
    Tokens values(line);
    for (int c = 0; c < valuesPerVertex; ++c) {
      double v = 0;
      if (!values.next(token))
        throw InputError(lines.where() + "vertex " + std::to_string(i) + " has " + std::to_string(c) +
                         " numbers, expected " + (header.hasNormals ? "x y z nx ny nz (NOFF)" : "x y z"));
      if (!parseDouble(token, v))
        throw InputError(lines.where() + quotedToken(token) + " is not a number (vertex " +
                         std::to_string(i) + ")");
      if (c < 3)
        mesh.vertices(c, i) = v;
      else
        mesh.normals(c - 3, i) = v;
    }
  }
}

// One face line "n i0 … i(n−1) [colour]", fan-triangulated (i0, ik, ik+1) onto `corners`,
// streamed: a huge n cannot allocate more than the line holds.
void readFace(std::string_view line, std::int64_t f, std::int64_t vertexCount, const OffLines& lines,
              std::vector<int>& corners) {
  Tokens values(line);
  std::string_view token;
  values.next(token);
  std::int64_t n = 0;
  if (!parseInteger(token, n) || n < 3)
    throw InputError(lines.where() + "face " + std::to_string(f) + ": the vertex count " + quotedToken(token) +
                     " is not an integer ≥ 3");
  std::int64_t first = 0, previous = 0;
  for (std::int64_t k = 0; k < n; ++k) {
    std::int64_t index = 0;
    if (!values.next(token))
      throw InputError(lines.where() + "face " + std::to_string(f) + " has " + std::to_string(k) + " of its " +
                       std::to_string(n) + " vertex indices");
    if (!parseInteger(token, index))
      throw InputError(lines.where() + "face " + std::to_string(f) + ": " + quotedToken(token) +
                       " is not an integer vertex index");
    if (index < 0 || index >= vertexCount)
      throw InputError(lines.where() + "face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                       ", but there are " + std::to_string(vertexCount) + " vertices (indices are 0-based)");
    if (k == 0) first = index;
    if (k >= 2) corners.insert(corners.end(), {static_cast<int>(first), static_cast<int>(previous), static_cast<int>(index)});
    previous = index;
  }
  // Anything after the indices is a colour (ignored).
}

}  // namespace

TriMesh readOff(std::string_view bytes, const std::string& path) {
  requireSingleByteText(bytes, path, "OFF files");
  OffLines lines(bytes, path);
  const OffHeader header = readHeader(lines, bytes.size(), path);
  TriMesh mesh;
  readVertices(lines, header, mesh, path);
  std::vector<int> corners;  // triangles, 3 per face for the common case
  corners.reserve(static_cast<std::size_t>(header.faces) * 3);
  std::string_view line;
  for (std::int64_t f = 0; f < header.faces; ++f) {
    if (!lines.next(line))
      throw InputError(path + ": ends after " + std::to_string(f) + " of the " + std::to_string(header.faces) +
                       " faces the header announces");
    readFace(line, f, header.vertices, lines, corners);
  }
  mesh.triangles = Eigen::Map<const Eigen::Matrix3Xi>(corners.data(), 3, static_cast<Eigen::Index>(corners.size() / 3));
  checkAndNormalizeMesh(mesh, path, ZeroNormals::Keep);
  return mesh;
}

}  // namespace hermite
