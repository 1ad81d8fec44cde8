#include "scene/data_file_scene.h"

#include <filesystem>

#include "core/base/errors.h"
#include "io/mesh_file.h"
#include "io/point_file.h"
#include "scene/loaded_samples_handoff.h"
#include "scene/scene_fit.h"

namespace hermite {

namespace {

namespace fs = std::filesystem;

// The samples' spacing and box, read through the scene (normals estimated where missing).
template <int Dim>
void measureSamples(const Scene& scene, DataFileScene& out) {
  const HermiteSamples<Dim> s = sceneSamples<Dim>(scene, out.warnings);
  keepLoadedSamples<Dim>(scene.data.resolvedFile, PointFileOptions{scene.data.orientNormals}, s, out.warnings);
  out.samples = s.size();
  out.spacing = meanSampleSpacing<Dim>(s.points);
  out.points = s.points;
  const Vec<Dim> lo = s.points.rowwise().minCoeff(), hi = s.points.rowwise().maxCoeff();
  out.samplesBox.assign(lo.data(), lo.data() + Dim);
  out.samplesBox.insert(out.samplesBox.end(), hi.data(), hi.data() + Dim);
}

// `file` as a path from `directory`, when both can be made absolute and relative to each other.
std::string relativePath(const std::string& file, const fs::path& directory) {
  std::error_code ec;
  const fs::path target = fs::absolute(file, ec).lexically_normal();
  if (ec) return file;
  const fs::path rel = target.lexically_relative(directory);
  return rel.empty() ? file : rel.generic_string();
}

}  // namespace

bool isSceneFilePath(const std::string& path) {
  const std::string ext = lowercaseExtension(path);
  if (ext == ".json") return true;
  if (ext == ".xyz" || ext == ".pwn" || ext == ".xyzn" || ext == ".xyn" || isMeshFileExtension(path)) return false;
  throw InputError(path + ": unknown file type '" + ext + "' (hermite-lab opens " + kOpenableExtensions + ")");
}

DataFileScene dataFileScene(const std::string& path, const std::vector<std::string>& overrides) {
  const int dim = dataFileDimension(path);
  nlohmann::json doc = {{"version", 1},
                        {"mode", dim == 2 ? "implicit2d" : "implicit3d"},
                        {"data", {{"file", path}}},
                        {"fit", {{"method", "hrbf"}, {"kernel", "cubic"}, {"polynomial", "linear"}}}};
  DataFileScene out;
  const Scene plain = parseScene(doc, path, "");
  if (dim == 2) measureSamples<2>(plain, out);
  else measureSamples<3>(plain, out);
  if (out.spacing > 0) doc["fit"]["radius"] = 4 * out.spacing;
  for (const std::string& o : overrides) applySetOverride(doc, o);
  out.scene = parseScene(doc, path, "");
  return out;
}

Scene withPathsRelativeTo(Scene scene, const std::string& directory) {
  std::error_code ec;
  const fs::path dir = fs::absolute(directory.empty() ? "." : directory, ec).lexically_normal();
  if (ec) return scene;
  if (!scene.data.file.empty())
    scene.data.file = relativePath(scene.data.resolvedFile.empty() ? scene.data.file : scene.data.resolvedFile, dir);
  if (!scene.holefill.mesh.empty())
    scene.holefill.mesh =
        relativePath(scene.holefill.resolvedMesh.empty() ? scene.holefill.mesh : scene.holefill.resolvedMesh, dir);
  return scene;
}

}  // namespace hermite
