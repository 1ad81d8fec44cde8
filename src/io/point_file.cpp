#include "io/point_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>

#include "core/base/errors.h"
#include "core/points/layer_thickness.h"
#include "core/points/lexicographic_order.h"
#include "core/points/normal_estimation.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "io/mesh_file.h"
#include "io/number_lines.h"

namespace hermite {

namespace {

// The whole file in memory (readInputFile), then a pointer walk over the lines.
std::string readWholeFile(const std::string& path) { return readInputFile(path, "point file"); }

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string columnNames(int dim, bool withNormals) {
  if (dim == 2) return withNormals ? "x y nx ny" : "x y";
  return withNormals ? "x y z nx ny nz" : "x y z";
}

// The normal estimation of a noisy cloud (layer_thickness.h): over 40 nearest neighbours instead of
// 10, whose PCA lines follow the noise, and as one sheet — noise as large as the spacing puts
// neighbours off each other's planes, so the two-sheet fits and the reversal across a gap misread
// it. sphere_20k.xyz: 48° from the true lines on average and half the normals inward with the
// defaults; 15° and 0.2 % inward so, in 0.2 s (the two-sheet fits over 40 neighbours took 26 s).
NormalEstimationOptions noisyCloudEstimation() {
  NormalEstimationOptions o;
  o.neighbours = 40;
  o.sheetBand = 100;     // every neighbour within the band: PCA lines, one sheet
  o.acrossCosine = 2.0;  // |nᵢ·nⱼ| never reaches it: no edge crosses a gap
  return o;
}

// Estimates the zero columns of `normals` (all of them for a file without normals) by PCA and
// orients them consistently with the given ones (normal_estimation.h), with a warning saying how
// many; `why` says why they are missing ("3 columns"; empty: zero in the file); `noisy`: as
// noisyCloudEstimation says. Returns how many.
template <int Dim>
int fillMissingNormals(const Points<Dim>& points, Points<Dim>& normals, const std::string& path,
                       const std::string& why, bool noisy, std::vector<std::string>& warnings) {
  if (points.cols() < 2 && normals.isZero(0))
    throw InputError(path + ": has no normals and a single point; normals cannot be estimated");
  const NormalEstimationOptions estimation = noisy ? noisyCloudEstimation() : NormalEstimationOptions{};
  const int estimated = completeNormals<Dim>(points, normals, estimation);
  if (estimated == 0) return 0;
  const std::string what = !why.empty() ? "has no normals (" + why + ")"
                                        : std::to_string(estimated) + " of " + std::to_string(points.cols()) +
                                              " normals are zero";
  const std::string which = estimated == points.cols() ? "all " + std::to_string(estimated) + " samples"
                                                       : "those " + std::to_string(estimated);
  warnings.push_back(path + ": " + what + ": normals estimated for " + which + " by PCA over " +
                     std::to_string(estimation.neighbours) + " nearest neighbours" +
                     (noisy ? " (the cloud is noisy, see below: as one sheet)" : "") +
                     " and oriented by propagation over a minimum spanning tree" +
                     (estimated == points.cols() ? ", outward at each part's extreme point"
                                                 : ", consistently with the given normals") +
                     "; check their direction (flip if inside out)");
  return estimated;
}

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g %%", 100 * fraction);
  return text;
}

// Re-orients the normals a file gives when they are not consistently oriented (GivenNormals in
// the header); `estimated` says how many fillMissingNormals estimated (all of them: nothing was
// given, and the estimate is oriented already).
template <int Dim>
void orientGivenNormals(const Points<Dim>& points, Points<Dim>& normals, int estimated, const std::string& path,
                        const PointFileOptions& options, std::vector<std::string>& warnings) {
  const Eigen::Index n = points.cols();
  if (options.orient == GivenNormals::Never || estimated == n || n < 2) return;
  if (options.orient == GivenNormals::Auto && n < 50) return;  // a hand-made file: its normals are meant
  const double disagreement = options.orient == GivenNormals::Auto ? orientationDisagreement<Dim>(points, normals) : 1.0;
  if (disagreement <= 0.005) return;
  Points<Dim> oriented = normals;
  const int changed = orientNormalLines<Dim>(points, oriented);
  const std::string pairs = percent(disagreement) + " of the neighbour pairs along the surface point opposite ways";
  const std::string turned = std::to_string(changed) + " of " + std::to_string(n);
  if (options.orient == GivenNormals::Auto && 20 * static_cast<Eigen::Index>(changed) < n) {
    warnings.push_back(path + ": " + pairs + "; the normals are kept as given (re-orienting them would turn only " +
                       turned + ": scattered, not a region inside out); set data.orient_normals to true to "
                       "re-orient them anyway");
    return;
  }
  if (changed == 0) return;
  normals = oriented;
  warnings.push_back(path + ": " + (options.orient == GivenNormals::Auto
                                        ? "normals are not consistently oriented (" + pairs + "): "
                                        : std::string()) +
                     "re-oriented " + turned + " normals (their lines kept) by propagation over a minimum spanning "
                     "tree, outward at each part's extreme point; set data.orient_normals to false to keep them as "
                     "given");
}

// Warns when the points lie in a layer as thick as their spacing (layer_thickness.h): a noisy
// scan, which an interpolating fit follows into a rough surface with many handles.
void warnIfNoisy(const LayerThickness& t, const std::string& path, std::vector<std::string>& warnings) {
  if (t.median < kNoisyLayer) return;
  char text[64];
  std::snprintf(text, sizeof text, "%.2f", t.median);
  warnings.push_back(path + ": the samples look noisy: they lie in a layer " + text +
                     " of their neighbourhood's radius thick (the median over " + std::to_string(t.probes) +
                     " points of the spread of their " + std::to_string(LayerThicknessOptions{}.neighbours) +
                     " nearest neighbours off a common plane; a sampled surface "
                     "gives under 0.1), so the interpolating fit follows the noise into a rough surface with "
                     "many handles; fit.smoothing (e.g. 0.1) with larger boxes (fit.partition.max_points_per_box "
                     "60) trades interpolation for a smoother surface");
}

// Whether every complete line of `text` reads "x y c nx ny 0" with the first line's c (exactly:
// what a 2D exporter writes). `whole`: the text is the whole file; otherwise its last line may be
// cut and is not read. A line that does not parse answers false (the loader then reports it).
bool linesInPlaneZ(std::string_view text, bool whole, const std::string& path) {
  if (!whole) {
    const std::size_t lastEnd = text.rfind('\n');
    text = text.substr(0, lastEnd == std::string_view::npos ? 0 : lastEnd + 1);
  }
  LineReader lines(text);
  std::string_view line;
  long number = 0;
  double values[6], plane = 0;
  bool first = true;
  while (lines.next(line, number)) {
    try {
      if (parseNumbers(line, values, 6, path, number) != 6 || values[5] != 0) return false;
    } catch (const InputError&) {
      return false;
    }
    if (first) plane = values[2];
    if (values[2] != plane) return false;
    first = false;
  }
  return !first;
}

// `fileDim` 3 with Dim 2 reads a planar 3D file as 2D data (isPlanarCurveText): x y and nx ny of
// each "x y z nx ny nz" line.
template <int Dim>
HermiteSamples<Dim> parseSamples(std::string_view text, const std::string& path, std::vector<std::string>& warnings,
                                 const PointFileOptions& options, int fileDim = Dim) {
  const int kColumns = 2 * fileDim;
  const NumberLines parsed = parseNumberLines(text, kColumns, path);
  // Dim × N column-major: coordinates of consecutive samples are consecutive.
  std::vector<double> points, normals;
  points.reserve(parsed.counts.size() * Dim);
  normals.reserve(parsed.counts.size() * Dim);
  // The first data line decides: 2·Dim columns (points and normals) or Dim (positions only:
  // normals are estimated below). Every other line must have the same columns.
  int columns = 0;
  long firstLine = 0;
  for (std::size_t l = 0; l < parsed.counts.size(); ++l) {
    const int count = parsed.counts[l];
    const long lineNumber = parsed.numbers[l];
    const double* values = parsed.values.data() + l * static_cast<std::size_t>(kColumns);
    if (columns == 0 && (count == kColumns || count == fileDim)) {
      columns = count;
      firstLine = lineNumber;
    }
    if (count != columns || columns == 0) {
      const bool withNormals = columns != fileDim;
      throw InputError(path + ":" + std::to_string(lineNumber) + ": expected " +
                       std::to_string(withNormals ? kColumns : fileDim) + " numbers (" +
                       columnNames(fileDim, withNormals) + ")" +
                       (columns != fileDim ? std::string() : " like line " + std::to_string(firstLine)) + ", got " +
                       std::to_string(count));
    }
    points.insert(points.end(), values, values + Dim);
    if (columns == kColumns) normals.insert(normals.end(), values + fileDim, values + fileDim + Dim);
  }
  if (parsed.error) std::rethrow_exception(parsed.error);  // the first line that is not numbers
  if (points.empty()) throw InputError(path + ": no points");
  const Eigen::Index count = static_cast<Eigen::Index>(points.size() / Dim);
  if (columns == fileDim) normals.assign(points.size(), 0.0);  // every normal missing: estimated below
  Points<Dim> N = Eigen::Map<const Points<Dim>>(normals.data(), Dim, count);
  const Eigen::Map<const Points<Dim>> P(points.data(), Dim, count);
  const LayerThickness layer = layerThickness<Dim>(P);
  const int estimated =
      fillMissingNormals<Dim>(P, N, path, columns == fileDim ? std::to_string(fileDim) + " columns" : std::string(),
                              layer.median >= kNoisyLayer, warnings);
  orientGivenNormals<Dim>(P, N, estimated, path, options, warnings);
  warnIfNoisy(layer, path, warnings);
  normals.assign(N.data(), N.data() + N.size());

  HermiteSamples<Dim> samples;
  const Eigen::Index n = static_cast<Eigen::Index>(points.size() / Dim);
  samples.points = Eigen::Map<const Points<Dim>>(points.data(), Dim, n);
  samples.normals = Eigen::Map<const Points<Dim>>(normals.data(), Dim, n);
  validateSamples(samples, warnings, path);
  return samples;
}

template <int Dim>
HermiteSamples<Dim> loadSamples(const std::string& path, std::vector<std::string>& warnings,
                                const PointFileOptions& options) {
  const int fileDim = pointFileDimension(path);
  if (fileDim == 3 && Dim == 2 && isPlanarCurveText(path)) {
    std::vector<std::string> own;
    HermiteSamples<Dim> samples = parseSamples<Dim>(readWholeFile(path), path, own, options, 3);
    warnings.push_back(path + ": every sample lies in one plane z = constant with its normal in that plane: read as "
                              "2D curve data (x y nx ny)");
    warnings.insert(warnings.end(), own.begin(), own.end());
    return samples;
  }
  if (fileDim != Dim)
    throw InputError(path + ": a " + std::to_string(fileDim) + "D point file (" + lowercaseExtension(path) +
                     (lowercaseExtension(path) == ".xyz" ? fileDim == 2 ? " with 2 or 4 numbers per line" : "" : "") +
                     ") cannot be used in a " + std::to_string(Dim) + "D scene; use " +
                     (Dim == 2 ? ".xyn (x y nx ny)" : ".xyz, .pwn or .xyzn (x y z nx ny nz)"));
  return parseSamples<Dim>(readWholeFile(path), path, warnings, options);
}

template <int Dim>
Points<Dim> parseProbes(std::string_view text, const std::string& path) {
  std::vector<double> coords;
  coords.reserve((static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1) * Dim);
  LineReader lines(text);
  std::string_view line;
  long lineNumber = 0;
  double values[Dim];
  while (lines.next(line, lineNumber)) {
    const int count = parseNumbers(line, values, Dim, path, lineNumber);
    if (count != Dim)
      throw InputError(path + ":" + std::to_string(lineNumber) + ": expected " + std::to_string(Dim) +
                       " numbers (" + columnNames(Dim, false) + "), got " + std::to_string(count));
    coords.insert(coords.end(), values, values + Dim);
  }
  if (coords.empty()) throw InputError(path + ": no points");
  return Eigen::Map<const Points<Dim>>(coords.data(), Dim, static_cast<Eigen::Index>(coords.size() / Dim));
}

template <int Dim>
void writeSamples(const std::string& path, const HermiteSamples<Dim>& samples) {
  if (samples.points.cols() != samples.normals.cols())
    throw InputError(path + ": cannot save " + std::to_string(samples.points.cols()) + " points with " +
                     std::to_string(samples.normals.cols()) + " normals");
  for (Eigen::Index i = 0; i < samples.points.cols(); ++i)
    if (!samples.points.col(i).allFinite() || !samples.normals.col(i).allFinite())
      throw InputError(path + ": cannot save point " + std::to_string(i) + ": it has a non-finite coordinate or normal");
  AtomicFileWriter writer(path);
  // Shortest representation that reads back to the same double (as exact as %.17g, shorter).
  char line[2 * Dim * 32];
  for (Eigen::Index i = 0; i < samples.points.cols(); ++i) {
    char* p = line;
    for (int c = 0; c < 2 * Dim; ++c) {
      const double v = c < Dim ? samples.points(c, i) : samples.normals(c - Dim, i);
      if (c > 0) *p++ = ' ';
      p = std::to_chars(p, line + sizeof(line), v).ptr;
    }
    *p++ = '\n';
    writer.write(std::string_view(line, static_cast<std::size_t>(p - line)));
  }
  writer.commit();
}

// Per vertex, the area-weighted mean of the face normals about its position, over the faces of
// every vertex there (`root`: coincidentVertexRoots), oriented by the faces' winding; zero on no
// face. With no repeated position this is vertexNormals of the mesh itself.
Eigen::Matrix3Xd faceNormalsAtPositions(const TriMesh& mesh, const std::vector<int>& root) {
  TriMesh welded;
  welded.vertices = mesh.vertices;
  welded.triangles = mesh.triangles;
  for (Eigen::Index t = 0; t < welded.triangles.cols(); ++t)
    for (int c = 0; c < 3; ++c) welded.triangles(c, t) = root[static_cast<std::size_t>(welded.triangles(c, t))];
  Eigen::Matrix3Xd normals = vertexNormals(welded, NormalWeighting::Area);
  for (Eigen::Index v = 0; v < normals.cols(); ++v) normals.col(v) = normals.col(root[static_cast<std::size_t>(v)]);
  return normals;  // a root is the smallest id at its position: its column is read before any write
}

// Replaces the zero columns of a mesh file's vertex normals (3 × V, zero where the file's normal
// is zero) by the face normals there (`faces()`, faceNormalsAtPositions), with a warning saying how
// many; vertices on no face stay zero (estimated from their neighbours afterwards).
template <class Faces>
void completeFromFaces(Points<3>& normals, Faces&& faces, const std::string& path, std::vector<std::string>& warnings) {
  int taken = 0, zero = 0;
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    if (!normals.col(i).isZero(0)) continue;
    ++zero;
    normals.col(i) = faces().col(i);
    if (!normals.col(i).isZero(0)) ++taken;
  }
  if (taken > 0)
    warnings.push_back(path + ": " + std::to_string(zero) + " of " + std::to_string(normals.cols()) +
                       " vertex normals are zero: " + std::to_string(taken) +
                       " taken from the area-weighted face normals (oriented by the faces' winding)");
}

// Given normals of vertices at exactly one position (a mesh split at hard edges, seams or
// patches: exporters repeat them) that differ are replaced by their unit mean (a warning says how
// many), or, where they cancel, by the face normal there (`faces()`; zero without faces: estimated
// later). validateSamples then merges the copies into one sample.
template <class Faces>
void averageRepeatedNormals(const std::vector<int>& root, Points<3>& normals, Faces&& faces, const std::string& path,
                            std::vector<std::string>& warnings) {
  const auto rootOf = [&](Eigen::Index v) { return static_cast<Eigen::Index>(root[static_cast<std::size_t>(v)]); };
  Eigen::Matrix3Xd sum = Eigen::Matrix3Xd::Zero(3, normals.cols());
  std::vector<char> differs(static_cast<std::size_t>(normals.cols()), 0);
  for (Eigen::Index v = 0; v < normals.cols(); ++v) {
    const double len = normals.col(v).norm();
    if (len > 0) sum.col(rootOf(v)) += normals.col(v) / len;
    if (normals.col(v) != normals.col(rootOf(v))) differs[static_cast<std::size_t>(rootOf(v))] = 1;
  }
  long averaged = 0;
  for (Eigen::Index v = 0; v < normals.cols(); ++v) {
    const Eigen::Index r = rootOf(v);
    if (!differs[static_cast<std::size_t>(r)]) continue;
    averaged += r != v;
    normals.col(v) = sum.col(r).norm() > 1e-6 ? Vec<3>(sum.col(r).normalized()) : Vec<3>(faces().col(r));
  }
  if (averaged > 0)
    warnings.push_back(path + ": " + std::to_string(averaged) +
                       " vertices repeat the position of another with a different normal (a mesh split at hard "
                       "edges or seams): one sample there, with the mean of their normals");
}

// The vertices and vertex normals of a mesh or point-set file (.ply, .obj, .gltf, .glb, .off),
// faces ignored: PLY nx ny nz, OBJ v + vn, glTF POINTS / TRIANGLES with NORMAL, NOFF. Vertices the
// file repeats at exactly one position (Stanford's dragon_vrip.ply repeats 2 100) get one normal,
// from all the faces about the position, and become one sample.
HermiteSamples<3> readMeshFileSamples(const std::string& path, std::vector<std::string>& warnings,
                                      const PointFileOptions& options) {
  TriMesh mesh = loadMeshFile(path);
  if (mesh.vertexCount() == 0) throw InputError(path + ": no points");
  // One sort of the positions serves the repeated vertices here and the duplicates in validateSamples.
  const std::vector<Eigen::Index> order = lexicographicOrder<3>(mesh.vertices);
  const std::vector<int> root = coincidentVertexRoots(mesh, order);
  std::optional<Eigen::Matrix3Xd> fromFaces;  // built on first use
  const auto faces = [&]() -> const Eigen::Matrix3Xd& {
    if (!fromFaces) fromFaces = mesh.triangleCount() > 0 ? faceNormalsAtPositions(mesh, root)
                                                         : Eigen::Matrix3Xd::Zero(3, mesh.vertexCount());
    return *fromFaces;
  };
  HermiteSamples<3> samples;
  const bool given = mesh.hasNormals();
  if (given) {
    samples.normals = std::move(mesh.normals);
    if (mesh.triangleCount() > 0) completeFromFaces(samples.normals, faces, path, warnings);
    averageRepeatedNormals(root, samples.normals, faces, path, warnings);
  } else if (mesh.triangleCount() > 0) {
    // Vertices on no face stay zero and are estimated from their neighbours below.
    samples.normals = faces();
    warnings.push_back(path + ": has no vertex normals: " + std::to_string(mesh.vertexCount()) +
                       " normals are the area-weighted means of the face normals (oriented by the faces' winding)");
  } else {
    samples.normals = Points<3>::Zero(3, mesh.vertexCount());
  }
  samples.points = std::move(mesh.vertices);
  // A point set (no faces) may be a noisy scan; a mesh's vertices are not measured.
  const LayerThickness layer = mesh.triangleCount() == 0 ? layerThickness<3>(samples.points) : LayerThickness{};
  const int estimated =
      fillMissingNormals<3>(samples.points, samples.normals, path,
                            given || mesh.triangleCount() > 0 ? std::string() : std::string("positions only"),
                            layer.median >= kNoisyLayer, warnings);
  orientGivenNormals<3>(samples.points, samples.normals, estimated, path, options, warnings);
  warnIfNoisy(layer, path, warnings);
  validateSamples(samples, warnings, path, &order);  // the positions are the mesh's, unchanged
  return samples;
}

// Blank-separated fields of the first data line of a text file (read from its first 64 KiB; 0
// when there is none or the file cannot be read — a missing file, a FIFO, which is never opened
// for reading: the loader then reports the problem).
int xyzColumns(const std::string& path) {
  std::string head;
  try {
    head = readInputFileHead(path, std::size_t{1} << 16);
  } catch (const InputError&) {
    return 0;
  }
  LineReader lines(head);
  std::string_view line;
  long number = 0;
  if (!lines.next(line, number)) return 0;
  int fields = 0;
  for (std::size_t i = 0; i < line.size(); ++i)
    if (!isBlank(line[i]) && (i == 0 || isBlank(line[i - 1]))) ++fields;
  return fields;
}

}  // namespace

int pointFileDimension(const std::string& path) {
  const std::string ext = lowercaseExtension(path);
  if (ext == ".xyz") {
    const int columns = xyzColumns(path);
    return columns == 2 || columns == 4 ? 2 : 3;
  }
  if (ext == ".pwn" || ext == ".xyzn") return 3;
  if (ext == ".xyn") return 2;
  if (isMeshFileExtension(path)) return 3;
  throw InputError(path + ": unsupported point file extension '" + ext +
                   "' (supported: .xyz, .pwn, .xyzn with x y z nx ny nz per line; .xyn with x y nx ny; .ply, .obj, "
                   ".gltf, .glb, .off with vertex normals)");
}

bool isPlanarCurveText(const std::string& path) {
  const std::string ext = lowercaseExtension(path);
  if (ext != ".pwn" && ext != ".xyzn" && !(ext == ".xyz" && xyzColumns(path) == 6)) return false;
  std::string text;
  try {
    text = readInputFileHead(path, std::size_t{1} << 16);
    if (!linesInPlaneZ(text, false, path)) return false;
    text = readWholeFile(path);
  } catch (const InputError&) {
    return false;
  }
  return linesInPlaneZ(text, true, path);
}

int dataFileDimension(const std::string& path) {
  const int dim = pointFileDimension(path);
  return dim == 3 && isPlanarCurveText(path) ? 2 : dim;
}

HermiteSamples<2> loadPointFile2d(const std::string& path, std::vector<std::string>& warnings,
                                  const PointFileOptions& options) {
  return loadSamples<2>(path, warnings, options);
}

HermiteSamples<3> loadPointFile3d(const std::string& path, std::vector<std::string>& warnings,
                                  const PointFileOptions& options) {
  if (isMeshFileExtension(path)) return readMeshFileSamples(path, warnings, options);
  return loadSamples<3>(path, warnings, options);
}

Points<2> loadProbePoints2d(const std::string& path) { return parseProbes<2>(readWholeFile(path), path); }
Points<3> loadProbePoints3d(const std::string& path) { return parseProbes<3>(readWholeFile(path), path); }

HermiteSamples<2> parsePointText2d(std::string_view text, const std::string& path, std::vector<std::string>& warnings,
                                   const PointFileOptions& options) {
  return parseSamples<2>(text, path, warnings, options);
}

HermiteSamples<3> parsePointText3d(std::string_view text, const std::string& path, std::vector<std::string>& warnings,
                                   const PointFileOptions& options) {
  return parseSamples<3>(text, path, warnings, options);
}

Points<3> parseProbeText3d(std::string_view text, const std::string& path) { return parseProbes<3>(text, path); }

void savePointFile(const std::string& path, const HermiteSamples<3>& samples) { writeSamples<3>(path, samples); }
void savePointFile(const std::string& path, const HermiteSamples<2>& samples) { writeSamples<2>(path, samples); }

}  // namespace hermite
