#include "io/ply_file.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/base/errors.h"
#include "io/mesh_format_common.h"
#include "io/quoted_token.h"

namespace hermite {

// The binary reader swaps bytes for big-endian files and the writer copies floats as they are:
// both assume a little-endian host (x86-64, AArch64 Linux).
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ && sizeof(float) == 4);

namespace {

enum class Scalar : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;  // the item type for a list
  bool list = false;
  Scalar countType = Scalar::UInt8;
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> properties;
  long line = 0;  // header line, for messages
};

enum class Format { Ascii, BinaryLittle, BinaryBig };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t bodyOffset = 0;
};

bool parseScalarName(std::string_view name, Scalar& type) {
  static constexpr std::array<std::pair<std::string_view, Scalar>, 16> kNames = {{
      {"char", Scalar::Int8},     {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},
      {"uint8", Scalar::UInt8},   {"short", Scalar::Int16},     {"int16", Scalar::Int16},
      {"ushort", Scalar::UInt16}, {"uint16", Scalar::UInt16},   {"int", Scalar::Int32},
      {"int32", Scalar::Int32},   {"uint", Scalar::UInt32},     {"uint32", Scalar::UInt32},
      {"float", Scalar::Float32}, {"float32", Scalar::Float32}, {"double", Scalar::Float64},
      {"float64", Scalar::Float64},
  }};
  for (const auto& [n, t] : kNames)
    if (n == name) {
      type = t;
      return true;
    }
  return false;
}

std::size_t scalarSize(Scalar type) {
  switch (type) {
    case Scalar::Int8:
    case Scalar::UInt8: return 1;
    case Scalar::Int16:
    case Scalar::UInt16: return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
  }
  return 1;
}

bool isInteger(Scalar type) { return type != Scalar::Float32 && type != Scalar::Float64; }

bool isIndexList(const Property& p) { return p.list && (p.name == "vertex_indices" || p.name == "vertex_index"); }

// "format KIND VERSION" (after the keyword): ascii or binary of either byte order, version 1.0.
Format parseFormatLine(Tokens& tokens, const std::string& where) {
  std::string_view kind, version;
  if (!tokens.next(kind) || !tokens.next(version))
    throw InputError(where + "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  Format format = Format::Ascii;
  if (kind == "ascii")
    format = Format::Ascii;
  else if (kind == "binary_little_endian")
    format = Format::BinaryLittle;
  else if (kind == "binary_big_endian")
    format = Format::BinaryBig;
  else
    throw InputError(where + "unknown format " + quotedToken(kind) +
                     " (expected ascii, binary_little_endian or binary_big_endian)");
  if (version != "1.0") throw InputError(where + "unsupported PLY version " + quotedToken(version) + " (expected 1.0)");
  return format;
}

// "element NAME COUNT" (after the keyword), appended to the header's elements.
void parseElementLine(Tokens& tokens, long lineNumber, const std::string& where, Header& header) {
  Element element;
  element.line = lineNumber;
  std::string_view name, count;
  if (!tokens.next(name) || !tokens.next(count)) throw InputError(where + "expected 'element NAME COUNT'");
  element.name = std::string(name);
  if (!parseInteger(count, element.count) || element.count < 0)
    throw InputError(where + "element " + quotedToken(element.name) + ": the count " + quotedToken(count) +
                     " is not a non-negative integer");
  if (element.count > kMaxMeshElements)
    throw InputError(where + "element " + quotedToken(element.name) + ": the count " + std::to_string(element.count) +
                     " is larger than this reader supports (" + std::to_string(kMaxMeshElements) + ")");
  for (const Element& e : header.elements)
    if (e.name == element.name) throw InputError(where + "element " + quotedToken(element.name) + " is declared twice");
  header.elements.push_back(std::move(element));
}

// "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE NAME" (after the keyword), appended
// to the last element's properties.
void parsePropertyLine(Tokens& tokens, const std::string& where, Header& header) {
  if (header.elements.empty()) throw InputError(where + "a property before any element");
  Property property;
  std::string_view type;
  if (!tokens.next(type)) throw InputError(where + "expected 'property TYPE NAME'");
  if (type == "list") {
    std::string_view countType, itemType;
    property.list = true;
    if (!tokens.next(countType) || !tokens.next(itemType))
      throw InputError(where + "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
    if (!parseScalarName(countType, property.countType))
      throw InputError(where + "unknown PLY type " + quotedToken(countType));
    if (!isInteger(property.countType))
      throw InputError(where + "a list count type must be an integer type, not " + quotedToken(countType));
    type = itemType;
  }
  if (!parseScalarName(type, property.type))
    throw InputError(where + "unknown PLY type " + quotedToken(type) +
                     " (expected char, uchar, short, ushort, int, uint, float, double or their sized names)");
  std::string_view name;
  if (!tokens.next(name)) throw InputError(where + "a property without a name");
  property.name = std::string(name);
  Element& element = header.elements.back();
  for (const Property& p : element.properties)
    if (p.name == property.name)
      throw InputError(where + "property " + quotedToken(property.name) + " of element " + quotedToken(element.name) +
                       " is declared twice");
  element.properties.push_back(std::move(property));
}

Header parseHeader(std::string_view bytes, const std::string& path) {
  // UTF-16 text would not even show the magic; say so instead of "not a PLY file".
  const std::size_t headerEnd = bytes.find("end_header");
  requireSingleByteText(bytes.substr(0, headerEnd == std::string_view::npos ? 1024 : headerEnd), path, "a PLY header");

  TextLines lines(bytes);
  std::string_view line, token;
  const auto where = [&] { return path + ":" + std::to_string(lines.number()) + ": "; };
  if (!lines.next(line) || line != "ply")
    throw InputError(path + ": not a PLY file (the first line must be 'ply')");

  Header header;
  bool haveFormat = false, ended = false;
  while (!ended && lines.next(line)) {
    Tokens tokens(line);
    if (!tokens.next(token)) continue;  // blank header line: tolerated
    if (token == "comment" || token == "obj_info") continue;
    if (token == "format") {
      header.format = parseFormatLine(tokens, where());
      haveFormat = true;
    } else if (token == "element") {
      parseElementLine(tokens, lines.number(), where(), header);
    } else if (token == "property") {
      parsePropertyLine(tokens, where(), header);
    } else if (token == "end_header") {
      ended = true;
    } else {
      throw InputError(where() + "unknown header keyword " + quotedToken(token) +
                       " (expected format, element, property, comment, obj_info or end_header)");
    }
  }
  if (!ended) throw InputError(path + ": the PLY header has no 'end_header' line");
  if (!haveFormat) throw InputError(path + ": the PLY header has no 'format' line");
  header.bodyOffset = lines.offset();
  return header;
}

// Where the vertex coordinates live: slot 0..5 = x y z nx ny nz, per property (-1: skipped).
struct VertexLayout {
  std::vector<int> slot;
  bool hasNormals = false;
};

VertexLayout vertexLayout(const Element& vertex, const std::string& path) {
  static constexpr std::array<std::string_view, 6> kNames = {"x", "y", "z", "nx", "ny", "nz"};
  VertexLayout layout;
  layout.slot.assign(vertex.properties.size(), -1);
  std::array<bool, 6> found{};
  for (std::size_t p = 0; p < vertex.properties.size(); ++p)
    for (int s = 0; s < 6; ++s)
      if (vertex.properties[p].name == kNames[static_cast<std::size_t>(s)]) {
        if (vertex.properties[p].list)
          throw InputError(path + ":" + std::to_string(vertex.line) + ": vertex property '" +
                           vertex.properties[p].name + "' is a list; expected a scalar");
        layout.slot[p] = s;
        found[static_cast<std::size_t>(s)] = true;
      }
  for (int s = 0; s < 3; ++s)
    if (!found[static_cast<std::size_t>(s)])
      throw InputError(path + ":" + std::to_string(vertex.line) + ": the vertex element has no '" +
                       std::string(kNames[static_cast<std::size_t>(s)]) + "' property");
  const int normals = found[3] + found[4] + found[5];
  if (normals != 0 && normals != 3)
    throw InputError(path + ":" + std::to_string(vertex.line) +
                     ": the vertex element has only some of nx, ny, nz; give all three or none");
  layout.hasNormals = normals == 3;
  return layout;
}

// ---- binary body -------------------------------------------------------------------------------

class BinaryReader {
 public:
  BinaryReader(std::string_view body, bool swap, const std::string& path)
      : p_(reinterpret_cast<const unsigned char*>(body.data())), end_(p_ + body.size()), swap_(swap), path_(path) {}

  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }

  // Throws when fewer than `bytes` remain; `what` says where in the file we are.
  void need(std::size_t bytes, const Element& element, std::int64_t row) const {
    if (bytes > remaining())
      throw InputError(path_ + ": truncated: element " + quotedToken(element.name) + " row " + std::to_string(row) + " of " +
                       std::to_string(element.count) + " needs " + std::to_string(bytes) + " more bytes, the file has " +
                       std::to_string(remaining()) + " left");
  }

  void skip(std::size_t bytes) { p_ += bytes; }

  // The next value of `type` (the caller has checked `need`).
  double real(Scalar type) {
    switch (type) {
      case Scalar::Float32: return load<float>();
      case Scalar::Float64: return load<double>();
      default: return static_cast<double>(integer(type));
    }
  }
  std::int64_t integer(Scalar type) {
    switch (type) {
      case Scalar::Int8: return load<std::int8_t>();
      case Scalar::UInt8: return load<std::uint8_t>();
      case Scalar::Int16: return load<std::int16_t>();
      case Scalar::UInt16: return load<std::uint16_t>();
      case Scalar::Int32: return load<std::int32_t>();
      case Scalar::UInt32: return load<std::uint32_t>();
      default: return 0;  // never reached: the header check allows only integer types here
    }
  }

 private:
  template <class T>
  T load() {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, p_, sizeof(T));
    if (swap_)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    T value;
    std::memcpy(&value, raw, sizeof(T));
    p_ += sizeof(T);
    return value;
  }

  const unsigned char* p_;
  const unsigned char* end_;
  bool swap_;
  const std::string& path_;
};

// ---- ascii body --------------------------------------------------------------------------------

class AsciiReader {
 public:
  AsciiReader(std::string_view body, long firstLine, const std::string& path)
      : text_(body), line_(firstLine), path_(path) {}

  std::string where() const { return path_ + ":" + std::to_string(line_) + ": "; }

  std::string_view token(const Element& element, std::int64_t row) {
    while (pos_ < text_.size() && (isBlankChar(text_[pos_]) || text_[pos_] == '\n')) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ == text_.size())
      throw InputError(path_ + ": the file ends in element " + quotedToken(element.name) + " row " + std::to_string(row) +
                       " of the " + std::to_string(element.count) + " the header announces");
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !isBlankChar(text_[pos_]) && text_[pos_] != '\n') ++pos_;
    return text_.substr(begin, pos_ - begin);
  }
  double real(const Element& element, std::int64_t row) {
    const std::string_view t = token(element, row);
    double value = 0;
    if (!parseDouble(t, value))
      throw InputError(where() + quotedToken(t) + " is not a number (element " + quotedToken(element.name) + " row " +
                       std::to_string(row) + ")");
    return value;
  }
  std::int64_t integer(const Element& element, std::int64_t row) {
    const std::string_view t = token(element, row);
    std::int64_t value = 0;
    if (!parseInteger(t, value))
      throw InputError(where() + quotedToken(t) + " is not an integer (element " + quotedToken(element.name) + " row " +
                       std::to_string(row) + ")");
    return value;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  long line_;
  const std::string& path_;
};

std::string listError(const std::string& where, const Element& element, std::int64_t row, const Property& p,
                      const std::string& what) {
  return where + "element " + quotedToken(element.name) + " row " + std::to_string(row) + " list " + quotedToken(p.name) + ": " + what;
}

// What the body readers fill: the mesh (vertices and normals sized from the header) and the
// fan-triangulated face corners, 3 per triangle.
struct Body {
  TriMesh mesh;
  std::vector<int> corners;
};

// One list property of a binary row: its count, then the items — fan-triangulated onto `corners`
// when it is a face's vertex indices, skipped otherwise.
void readBinaryList(BinaryReader& in, const Element& element, std::int64_t row, const Property& p, bool isFace,
                    const std::string& path, std::vector<int>& corners) {
  in.need(scalarSize(p.countType), element, row);
  const std::int64_t n = in.integer(p.countType);
  if (n < 0) throw InputError(listError(path + ": ", element, row, p, "negative length " + std::to_string(n)));
  const std::size_t itemSize = scalarSize(p.type);
  if (static_cast<std::uint64_t>(n) > in.remaining() / itemSize)
    in.need(static_cast<std::size_t>(n) * itemSize, element, row);
  if (!(isFace && isIndexList(p))) {
    in.skip(static_cast<std::size_t>(n) * itemSize);
    return;
  }
  if (n < 3)
    throw InputError(listError(path + ": ", element, row, p, "a face needs at least 3 vertices, got " + std::to_string(n)));
  std::int64_t first = 0, previous = 0;
  for (std::int64_t k = 0; k < n; ++k) {
    const std::int64_t index = in.integer(p.type);
    if (index < 0 || index > kMaxMeshElements)
      throw InputError(listError(path + ": ", element, row, p, "vertex index " + std::to_string(index) + " is out of range"));
    if (k == 0) first = index;
    if (k >= 2)
      corners.insert(corners.end(), {static_cast<int>(first), static_cast<int>(previous), static_cast<int>(index)});
    previous = index;
  }
}

void readBinaryBody(std::string_view body, const Header& header, const std::string& path, Body& out) {
  BinaryReader in(body, header.format == Format::BinaryBig, path);
  for (const Element& element : header.elements) {
    if (element.properties.empty()) continue;
    const bool isVertex = element.name == "vertex";
    const bool isFace = element.name == "face";
    std::size_t fixedRow = 0;
    bool hasList = false;
    for (const Property& p : element.properties) {
      fixedRow += p.list ? scalarSize(p.countType) : scalarSize(p.type);
      hasList |= p.list;
    }
    if (!isVertex && !isFace && !hasList) {
      // Skipped whole: the size is known from the header.
      in.need(fixedRow * static_cast<std::size_t>(element.count), element, 0);
      in.skip(fixedRow * static_cast<std::size_t>(element.count));
      continue;
    }
    VertexLayout layout;
    if (isVertex) layout = vertexLayout(element, path);
    for (std::int64_t row = 0; row < element.count; ++row) {
      if (!hasList) in.need(fixedRow, element, row);  // one check per row of scalars
      double slots[6] = {0, 0, 0, 0, 0, 0};
      for (std::size_t pi = 0; pi < element.properties.size(); ++pi) {
        const Property& p = element.properties[pi];
        if (p.list) {
          readBinaryList(in, element, row, p, isFace, path, out.corners);
          continue;
        }
        if (hasList) in.need(scalarSize(p.type), element, row);
        if (isVertex && layout.slot[pi] >= 0)
          slots[layout.slot[pi]] = in.real(p.type);
        else
          in.skip(scalarSize(p.type));
      }
      if (isVertex) {
        out.mesh.vertices.col(row) = Eigen::Vector3d(slots[0], slots[1], slots[2]);
        if (layout.hasNormals) out.mesh.normals.col(row) = Eigen::Vector3d(slots[3], slots[4], slots[5]);
      }
    }
  }
}

void readAsciiBody(std::string_view body, long firstLine, const Header& header, const std::string& path, Body& out) {
  AsciiReader in(body, firstLine, path);
  for (const Element& element : header.elements) {
    if (element.properties.empty()) continue;
    const bool isVertex = element.name == "vertex";
    const bool isFace = element.name == "face";
    VertexLayout layout;
    if (isVertex) layout = vertexLayout(element, path);
    for (std::int64_t row = 0; row < element.count; ++row) {
      double slots[6] = {0, 0, 0, 0, 0, 0};
      for (std::size_t pi = 0; pi < element.properties.size(); ++pi) {
        const Property& p = element.properties[pi];
        if (!p.list) {
          if (isVertex && layout.slot[pi] >= 0)
            slots[layout.slot[pi]] = in.real(element, row);
          else if (isInteger(p.type))
            in.integer(element, row);
          else
            in.real(element, row);
          continue;
        }
        const std::int64_t n = in.integer(element, row);
        if (n < 0) throw InputError(listError(in.where(), element, row, p, "negative length " + std::to_string(n)));
        const bool indices = isFace && isIndexList(p);
        if (indices && n < 3)
          throw InputError(listError(in.where(), element, row, p, "a face needs at least 3 vertices, got " + std::to_string(n)));
        std::int64_t first = 0, previous = 0;
        for (std::int64_t k = 0; k < n; ++k) {
          if (!indices) {
            if (isInteger(p.type))
              in.integer(element, row);
            else
              in.real(element, row);
            continue;
          }
          const std::int64_t index = in.integer(element, row);
          if (index < 0 || index > kMaxMeshElements)
            throw InputError(listError(in.where(), element, row, p, "vertex index " + std::to_string(index) + " is out of range"));
          if (k == 0) first = index;
          if (k >= 2)
            out.corners.insert(out.corners.end(),
                               {static_cast<int>(first), static_cast<int>(previous), static_cast<int>(index)});
          previous = index;
        }
      }
      if (isVertex) {
        out.mesh.vertices.col(row) = Eigen::Vector3d(slots[0], slots[1], slots[2]);
        if (layout.hasNormals) out.mesh.normals.col(row) = Eigen::Vector3d(slots[3], slots[4], slots[5]);
      }
    }
  }
}

}  // namespace

TriMesh readPly(std::string_view bytes, const std::string& path) {
  const Header header = parseHeader(bytes, path);
  const std::string_view body = bytes.substr(header.bodyOffset);

  const Element* vertex = nullptr;
  const Element* face = nullptr;
  for (const Element& e : header.elements) {
    if (e.name == "vertex") vertex = &e;
    if (e.name == "face") face = &e;
  }
  if (!vertex) throw InputError(path + ": the PLY header declares no 'vertex' element");
  const VertexLayout layout = vertexLayout(*vertex, path);
  if (face) {
    bool hasIndices = false;
    for (const Property& p : face->properties)
      if (isIndexList(p)) {
        if (!isInteger(p.type))
          throw InputError(path + ":" + std::to_string(face->line) + ": face list " + quotedToken(p.name) +
                           " has a floating-point item type; vertex indices must be integers");
        hasIndices = true;
      }
    if (!hasIndices)
      throw InputError(path + ":" + std::to_string(face->line) +
                       ": the face element has no 'vertex_indices' (or 'vertex_index') list");
  }

  // The smallest body the header's counts need: one byte per value in binary (its size), at
  // least two characters per value in ascii. Checked before anything is allocated, so a header
  // promising 10^12 vertices in a small file is an error, not an allocation.
  const bool ascii = header.format == Format::Ascii;
  std::int64_t needed = 0;
  for (const Element& e : header.elements) {
    std::int64_t perRow = 0;
    for (const Property& p : e.properties)
      perRow += ascii ? 2 : static_cast<std::int64_t>(p.list ? scalarSize(p.countType) : scalarSize(p.type));
    needed += e.count * perRow;
    if (needed > static_cast<std::int64_t>(body.size()) + (ascii ? 1 : 0))
      throw InputError(path + ":" + std::to_string(e.line) + ": the header announces " + std::to_string(e.count) +
                       " " + quotedToken(e.name) + " rows, more than the " + std::to_string(body.size()) +
                       " bytes after the header can hold (truncated file or wrong count)");
  }

  Body out;
  out.mesh.vertices.resize(3, vertex->count);
  if (layout.hasNormals) out.mesh.normals.resize(3, vertex->count);
  if (face) out.corners.reserve(static_cast<std::size_t>(face->count) * 3);
  if (ascii) {
    long firstLine = 1;
    for (std::size_t i = 0; i < header.bodyOffset; ++i) firstLine += bytes[i] == '\n';
    readAsciiBody(body, firstLine, header, path, out);
  } else {
    readBinaryBody(body, header, path, out);
  }
  out.mesh.triangles =
      Eigen::Map<const Eigen::Matrix3Xi>(out.corners.data(), 3, static_cast<Eigen::Index>(out.corners.size() / 3));
  checkAndNormalizeMesh(out.mesh, path, ZeroNormals::Keep);
  return std::move(out.mesh);
}

namespace {

// The vertex rows of the body: x y z [nx ny nz], as T (float, or double where a coordinate lies
// beyond the float range).
template <class T>
char* writeVertexRows(const TriMesh& mesh, bool normals, char* p) {
  const std::size_t vertexBytes = (normals ? 6 : 3) * sizeof(T);
  for (int i = 0; i < mesh.vertexCount(); ++i) {
    T row[6];
    for (int c = 0; c < 3; ++c) row[c] = static_cast<T>(mesh.vertices(c, i));
    if (normals)
      for (int c = 0; c < 3; ++c) row[3 + c] = static_cast<T>(mesh.normals(c, i));
    std::memcpy(p, row, vertexBytes);
    p += vertexBytes;
  }
  return p;
}

}  // namespace

std::string writePly(const TriMesh& mesh) {
  const bool normals = mesh.hasNormals();
  const bool doubles = firstBeyondFloatRange(mesh.vertices).has_value();
  const std::string type = doubles ? "double" : "float";
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by Hermite Lab\n";
  out += "element vertex " + std::to_string(mesh.vertexCount()) + "\n";
  out += "property " + type + " x\nproperty " + type + " y\nproperty " + type + " z\n";
  if (normals) out += "property " + type + " nx\nproperty " + type + " ny\nproperty " + type + " nz\n";
  out += "element face " + std::to_string(mesh.triangleCount()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";

  const std::size_t vertexBytes = (normals ? 6 : 3) * (doubles ? sizeof(double) : sizeof(float));
  const std::size_t headerSize = out.size();
  out.resize(headerSize + static_cast<std::size_t>(mesh.vertexCount()) * vertexBytes +
             static_cast<std::size_t>(mesh.triangleCount()) * (1 + 3 * sizeof(std::int32_t)));
  char* p = out.data() + headerSize;
  p = doubles ? writeVertexRows<double>(mesh, normals, p) : writeVertexRows<float>(mesh, normals, p);
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    *p++ = 3;
    const std::int32_t tri[3] = {mesh.triangles(0, t), mesh.triangles(1, t), mesh.triangles(2, t)};
    std::memcpy(p, tri, sizeof(tri));
    p += sizeof(tri);
  }
  return out;
}

}  // namespace hermite
