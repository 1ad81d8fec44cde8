#include "io/mesh_format_common.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/base/errors.h"
#include "io/input_file.h"

namespace hermite {

std::string readFileBytes(const std::string& path, std::string_view what) {
  std::string bytes = readInputFile(path, what);
  if (bytes.empty()) throw InputError(path + ": the file is empty (expected " + std::string(what) + " data)");
  return bytes;
}

void requireSingleByteText(std::string_view bytes, const std::string& path, std::string_view what) {
  auto starts = [&](std::string_view prefix) { return bytes.substr(0, prefix.size()) == prefix; };
  const bool utf32Bom = starts(std::string_view("\xFF\xFE\0\0", 4)) || starts(std::string_view("\0\0\xFE\xFF", 4));
  const bool utf16Bom = starts("\xFF\xFE") || starts("\xFE\xFF");
  const std::string_view head = bytes.substr(0, 1024);
  const bool hasNul = head.find('\0') != std::string_view::npos;
  if (utf32Bom || utf16Bom || hasNul)
    throw InputError(path + ": looks like " + (utf32Bom ? "UTF-32" : utf16Bom ? "UTF-16" : "UTF-16 or binary") +
                     " data, but " + std::string(what) + " must be ASCII or UTF-8 text; re-save it as UTF-8");
}

TextLines::TextLines(std::string_view text, std::size_t start, bool bareCrEndsLine)
    : text_(text), pos_(start), bareCrEndsLine_(bareCrEndsLine) {
  if (pos_ == 0 && text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

bool TextLines::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const std::string_view ends = bareCrEndsLine_ ? std::string_view("\r\n") : std::string_view("\n");
  const std::size_t eol = text_.find_first_of(ends, pos_);
  const std::size_t end = eol == std::string_view::npos ? text_.size() : eol;
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  std::size_t after = eol == std::string_view::npos ? text_.size() : eol + 1;
  if (eol != std::string_view::npos && text_[eol] == '\r' && after < text_.size() && text_[after] == '\n') ++after;
  pos_ = after;
  ++number_;
  return true;
}

bool isBlankChar(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

bool Tokens::next(std::string_view& token) {
  while (pos_ < line_.size() && isBlankChar(line_[pos_])) ++pos_;
  if (pos_ == line_.size()) return false;
  const std::size_t begin = pos_;
  while (pos_ < line_.size() && !isBlankChar(line_[pos_])) ++pos_;
  token = line_.substr(begin, pos_ - begin);
  return true;
}

bool parseDouble(std::string_view token, double& value) {
  const char* b = token.data();
  const char* e = b + token.size();
  if (b == e) return false;
  if (*b == '+' && e - b > 1 && (std::isdigit(static_cast<unsigned char>(b[1])) || b[1] == '.')) ++b;
  const auto r = std::from_chars(b, e, value);
  if (r.ptr != e) return false;
  if (r.ec == std::errc::invalid_argument) return false;
  if (r.ec == std::errc::result_out_of_range) {
    // from_chars reports both overflow and underflow; strtod tells them apart (underflow → 0,
    // overflow → ±inf, which the finiteness checks then reject).
    const std::string copy(b, e);
    value = std::strtod(copy.c_str(), nullptr);
  }
  return true;
}

bool parseInteger(std::string_view token, std::int64_t& value) {
  const char* b = token.data();
  const char* e = b + token.size();
  if (b == e) return false;
  if (*b == '+' && e - b > 1) ++b;
  const auto r = std::from_chars(b, e, value);
  return r.ec == std::errc() && r.ptr == e;
}

void checkAndNormalizeMesh(TriMesh& mesh, const std::string& path, ZeroNormals zero) {
  const Eigen::Index vertexCount = mesh.vertices.cols();
  for (Eigen::Index i = 0; i < vertexCount; ++i)
    if (!mesh.vertices.col(i).allFinite())
      throw InputError(path + ": vertex " + std::to_string(i) + " has a non-finite coordinate (NaN or infinity)");
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int index = mesh.triangles(k, t);
      if (index < 0 || index >= vertexCount)
        throw InputError(path + ": triangle " + std::to_string(t) + " refers to vertex " + std::to_string(index) +
                         ", but there are " + std::to_string(vertexCount) + " vertices");
    }
  if (mesh.normals.cols() == 0) return;
  if (mesh.normals.cols() != vertexCount)
    throw InputError(path + ": " + std::to_string(mesh.normals.cols()) + " normals for " +
                     std::to_string(vertexCount) + " vertices");
  for (Eigen::Index i = 0; i < vertexCount; ++i) {
    auto n = mesh.normals.col(i);
    if (!n.allFinite())
      throw InputError(path + ": the normal of vertex " + std::to_string(i) + " is not finite (NaN or infinity)");
    // Scale by the largest component first so neither tiny nor huge normals under/overflow.
    const double largest = n.cwiseAbs().maxCoeff();
    if (largest == 0) {
      if (zero == ZeroNormals::Keep) continue;
      throw InputError(path + ": the normal of vertex " + std::to_string(i) + " is zero");
    }
    n /= largest;
    n.normalize();
  }
}

std::optional<std::pair<Eigen::Index, int>> firstBeyondFloatRange(const Eigen::Matrix3Xd& points) {
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    for (int c = 0; c < 3; ++c)
      if (std::isinf(static_cast<float>(points(c, i)))) return std::make_pair(i, c);
  return std::nullopt;
}

}  // namespace hermite
