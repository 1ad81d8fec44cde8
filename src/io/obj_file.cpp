#include "io/obj_file.h"

#define TINYOBJLOADER_USE_DOUBLE
#include <tiny_obj_loader.h>

#include <charconv>
#include <cmath>
#include <vector>

#include "core/base/errors.h"
#include "io/mesh_format_common.h"
#include "io/quoted_token.h"

namespace hermite {

namespace {

// How tinyobjloader recognises a `v` / `vn` line: after spaces and tabs, the tag and a space or tab.
bool tinyobjSeesTag(std::string_view line, std::string_view tag) {
  const std::size_t start = line.find_first_not_of(" \t");
  if (start == std::string_view::npos || line.substr(start, tag.size()) != tag) return false;
  const std::size_t after = start + tag.size();
  return after < line.size() && (line[after] == ' ' || line[after] == '\t');
}

// x y z of one `v` / `vn` line into `values`; "FILE:LINE: ..." naming the token otherwise.
void parseCoordinates(Tokens& tokens, bool normal, const std::string& where, std::vector<double>& values) {
  std::string_view token;
  for (int c = 0; c < 3; ++c) {
    double value = 0;
    if (!tokens.next(token))
      throw InputError(where + "'" + (normal ? "vn" : "v") + "' has " + std::to_string(c) + " numbers, expected 3 (" +
                       (normal ? "nx ny nz" : "x y z") + ")");
    if (!parseDouble(token, value)) throw InputError(where + quotedToken(token) + " is not a number");
    if (!std::isfinite(value)) throw InputError(where + quotedToken(token) + " is not a finite number");
    values.push_back(value);
  }
}

// tinyobjloader reads a malformed number as 0 and a missing coordinate as 0 without a word, and
// its own number parser is not correctly rounded: parse every `v` and `vn` line ourselves first
// (from_chars, exact), with line numbers in the errors, splitting lines at LF, CRLF and bare CR
// as tinyobjloader does. x y z of each line go to `vertices` / `normals`.
void parseVertexLines(std::string_view bytes, const std::string& path, std::vector<double>& vertices,
                      std::vector<double>& normals) {
  TextLines lines(bytes, 0, /*bareCrEndsLine=*/true);
  std::string_view line, token;
  while (lines.next(line)) {
    Tokens tokens(line);
    if (!tokens.next(token) || (token != "v" && token != "vn")) continue;
    const bool normal = token == "vn";
    const std::string where = path + ":" + std::to_string(lines.number()) + ": ";
    if (!tinyobjSeesTag(line, token) && !tokens.rest().empty())
      throw InputError(where + "'" + std::string(token) +
                       "' must start the line (after spaces or tabs) and be followed by a space or a tab");
    parseCoordinates(tokens, normal, where, normal ? normals : vertices);
  }
}

// tinyobjloader's faces (fan-triangulated here, with our own index checks); the material text
// is empty, so an `mtllib` line reads nothing from disk.
void parseWithTinyobj(std::string_view bytes, const std::string& path, tinyobj::ObjReader& reader) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  // tinyobjloader does not skip a byte-order mark; TextLines does.
  const std::string_view body = bytes.substr(0, 3) == "\xEF\xBB\xBF" ? bytes.substr(3) : bytes;
  if (!reader.ParseFromString(std::string(body), std::string(), config)) {
    std::string message = reader.Error();
    while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
    throw InputError(path + ": not a valid OBJ file (" + (message.empty() ? "unknown parse error" : message) + ")");
  }
}

// The faces' triangles (fans), and per vertex the sum of the normals its corners name when
// every corner names one.
struct ObjFaces {
  std::vector<int> corners;
  Eigen::Matrix3Xd normalSums;
  bool everyCornerHasNormal = false;
  std::size_t count = 0;
};

ObjFaces collectFaces(const tinyobj::ObjReader& reader, Eigen::Index vertexCount, const std::vector<double>& normals,
                      const std::string& path) {
  const Eigen::Index normalCount = static_cast<Eigen::Index>(normals.size() / 3);
  ObjFaces faces;
  faces.normalSums = Eigen::Matrix3Xd::Zero(3, normalCount > 0 ? vertexCount : 0);
  faces.everyCornerHasNormal = normalCount > 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    std::size_t next = 0;
    for (const auto sides : shape.mesh.num_face_vertices) {
      const std::size_t n = sides;
      const auto face = [&] { return path + ": face " + std::to_string(faces.count); };  // built only to throw
      if (n < 3) throw InputError(face() + " has " + std::to_string(n) + " vertices; a face needs at least 3");
      if (next + n > indices.size()) throw InputError(face() + " has fewer indices than vertices");
      for (std::size_t k = 0; k < n; ++k) {
        const tinyobj::index_t& corner = indices[next + k];
        if (corner.vertex_index < 0 || corner.vertex_index >= vertexCount)
          throw InputError(face() + " refers to vertex " + std::to_string(corner.vertex_index + 1) + ", but there are " +
                           std::to_string(vertexCount) + " 'v' lines");
        if (corner.normal_index < 0) {
          faces.everyCornerHasNormal = false;
        } else if (corner.normal_index >= normalCount) {
          throw InputError(face() + " refers to normal " + std::to_string(corner.normal_index + 1) + ", but there are " +
                           std::to_string(normalCount) + " 'vn' lines");
        } else if (faces.everyCornerHasNormal) {
          faces.normalSums.col(corner.vertex_index) +=
              Eigen::Map<const Eigen::Vector3d>(normals.data() + 3 * corner.normal_index);
        }
        if (k >= 2)
          faces.corners.insert(faces.corners.end(), {indices[next].vertex_index, indices[next + k - 1].vertex_index,
                                                     corner.vertex_index});
      }
      next += n;
      ++faces.count;
    }
  }
  return faces;
}

}  // namespace

TriMesh readObj(std::string_view bytes, const std::string& path) {
  requireSingleByteText(bytes, path, "OBJ files");
  std::vector<double> vertexValues, normalValues;
  parseVertexLines(bytes, path, vertexValues, normalValues);
  tinyobj::ObjReader reader;
  parseWithTinyobj(bytes, path, reader);
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const Eigen::Index vertexCount = static_cast<Eigen::Index>(attrib.vertices.size() / 3);
  const Eigen::Index normalCount = static_cast<Eigen::Index>(attrib.normals.size() / 3);
  if (vertexCount == 0) throw InputError(path + ": no vertices ('v' lines)");

  // Our exactly rounded values; both parsers must have seen the same lines, never a silent mix.
  if (vertexValues.size() != attrib.vertices.size() || normalValues.size() != attrib.normals.size())
    throw InputError(path + ": " + std::to_string(vertexValues.size() / 3) + " 'v' and " +
                     std::to_string(normalValues.size() / 3) + " 'vn' lines, but tinyobjloader saw " +
                     std::to_string(attrib.vertices.size() / 3) + " and " + std::to_string(attrib.normals.size() / 3) +
                     " (control characters or NUL bytes in a line?)");

  TriMesh mesh;
  mesh.vertices = Eigen::Map<const Eigen::Matrix3Xd>(vertexValues.data(), 3, vertexCount);
  ObjFaces faces = collectFaces(reader, vertexCount, normalValues, path);
  mesh.triangles =
      Eigen::Map<const Eigen::Matrix3Xi>(faces.corners.data(), 3, static_cast<Eigen::Index>(faces.corners.size() / 3));
  if (faces.count == 0) {
    // An oriented point set: the i-th vn is the normal of the i-th v.
    if (normalCount > 0 && normalCount != vertexCount)
      throw InputError(path + ": " + std::to_string(vertexCount) + " 'v' lines but " + std::to_string(normalCount) +
                       " 'vn' lines; without faces, each point needs exactly one normal");
    if (normalCount > 0) mesh.normals = Eigen::Map<const Eigen::Matrix3Xd>(normalValues.data(), 3, normalCount);
  } else if (faces.everyCornerHasNormal) {
    // A vertex no face uses, or whose corners name only zero normals, keeps a zero sum: a zero
    // column, as a zero normal of any file (completed by the point loaders).
    mesh.normals = std::move(faces.normalSums);
  }
  checkAndNormalizeMesh(mesh, path, ZeroNormals::Keep);
  return mesh;
}

std::string writeObj(const TriMesh& mesh) {
  std::string out = "# written by Hermite Lab\n";
  out.reserve(out.size() + static_cast<std::size_t>(mesh.vertexCount()) * (mesh.hasNormals() ? 140 : 70) +
              static_cast<std::size_t>(mesh.triangleCount()) * 40);
  char line[256];
  // Shortest text that reads back to the same double.
  auto appendRow = [&](const char* tag, const auto& column) {
    char* p = line;
    for (const char* t = tag; *t; ++t) *p++ = *t;
    for (int c = 0; c < 3; ++c) {
      *p++ = ' ';
      p = std::to_chars(p, line + sizeof(line), column(c)).ptr;
    }
    *p++ = '\n';
    out.append(line, static_cast<std::size_t>(p - line));
  };
  for (int i = 0; i < mesh.vertexCount(); ++i) appendRow("v", mesh.vertices.col(i));
  const bool normals = mesh.hasNormals();
  if (normals)
    for (int i = 0; i < mesh.vertexCount(); ++i) appendRow("vn", mesh.normals.col(i));
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    char* p = line;
    *p++ = 'f';
    for (int k = 0; k < 3; ++k) {
      const int index = mesh.triangles(k, t) + 1;
      *p++ = ' ';
      p = std::to_chars(p, line + sizeof(line), index).ptr;
      if (normals) {
        *p++ = '/';
        *p++ = '/';
        p = std::to_chars(p, line + sizeof(line), index).ptr;
      }
    }
    *p++ = '\n';
    out.append(line, static_cast<std::size_t>(p - line));
  }
  return out;
}

}  // namespace hermite
