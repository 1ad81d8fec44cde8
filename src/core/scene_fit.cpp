#include "core/scene_fit.h"

#include <chrono>
#include <cmath>
#include <cstdint>

#include "core/errors.h"
#include "core/io_points.h"
#include "core/presets.h"

namespace hermite {

namespace {

template <int Dim>
HermiteSamples<Dim> loadFile(const std::string& path, std::vector<std::string>& warnings) {
  if constexpr (Dim == 2)
    return loadPointFile2d(path, warnings);
  else
    return loadPointFile3d(path, warnings);
}

template <int Dim>
HermiteSamples<Dim> makePreset(const std::string& name, int count) {
  if constexpr (Dim == 2)
    return makePreset2d(name, count);
  else
    return makePreset3d(name, count);
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

template <int Dim>
HermiteSamples<Dim> sceneSamples(const Scene& scene, std::vector<std::string>& warnings) {
  const DataSpec& d = scene.data;
  if (!d.preset.empty()) {
    try {
      return makePreset<Dim>(d.preset, d.count);
    } catch (const InputError& e) {
      throw InputError(scene.sourceName + ": data.preset: " + e.what());
    }
  }
  if (!d.file.empty()) {
    if (pointFileDimension(d.resolvedFile) != Dim)
      throw InputError(scene.sourceName + ": data.file: '" + d.file + "' holds " +
                       std::to_string(pointFileDimension(d.resolvedFile)) + "D points, the scene's mode '" +
                       std::string(sceneModeName(scene.mode)) + "' needs " + std::to_string(Dim) + "D");
    return loadFile<Dim>(d.resolvedFile, warnings);
  }
  HermiteSamples<Dim> s;
  const int n = static_cast<int>(d.points.size());
  s.points.resize(Dim, n);
  s.normals.resize(Dim, n);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < Dim; ++k) {
      s.points(k, i) = d.points[i][k];
      s.normals(k, i) = d.normals[i][k];
    }
  validateSamples(s, warnings, scene.sourceName + ": data");
  if (n == 0) throw InputError(scene.sourceName + ": data.points: no points");
  return s;
}

template <int Dim>
Similarity<Dim> sceneSimilarity(const TransformSpec& spec) {
  Similarity<Dim> T;
  T.q = spec.scale;
  for (int k = 0; k < Dim && k < static_cast<int>(spec.translate.size()); ++k) T.t(k) = spec.translate[k];
  if constexpr (Dim == 2) {
    const double a = spec.rotateDeg * M_PI / 180.0;  // counter-clockwise
    T.R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  } else {
    const Eigen::Vector3d axis(spec.rotateAxisAngleDeg[0], spec.rotateAxisAngleDeg[1], spec.rotateAxisAngleDeg[2]);
    const double a = spec.rotateAxisAngleDeg[3] * M_PI / 180.0;  // right-hand rule about the axis
    if (axis.norm() > 0) T.R = Eigen::AngleAxisd(a, axis.normalized()).toRotationMatrix();
  }
  return T;
}

template <int Dim>
SceneFit<Dim> fitScene(const Scene& scene) {
  if (scene.dimension() != Dim || (scene.mode != SceneMode::Implicit2d && scene.mode != SceneMode::Implicit3d))
    throw InputError(scene.sourceName + ": mode: '" + std::string(sceneModeName(scene.mode)) +
                     "' scenes have no implicit fit");
  if (scene.fit.partition.enabled)
    throw InputError(scene.sourceName +
                     ": fit.partition.enabled: partition of unity is not available in this version; "
                     "set it to false");
  SceneFit<Dim> out;
  out.samples = sceneSamples<Dim>(scene, out.warnings);
  const FitSpec& f = scene.fit;
  auto fitOn = [&](const HermiteSamples<Dim>& s, double scale, FitReport* rep) -> std::unique_ptr<RadialSum<Dim>> {
    const Kernel kernel{f.kernel, f.radius * scale};
    if (f.method == FitMethod::Hrbf)
      return std::make_unique<HrbfModel<Dim>>(fitHrbf<Dim>(s, {kernel, f.polynomial, f.smoothing, f.solver}, rep));
    return std::make_unique<RbfOffsetModel<Dim>>(
        fitRbfOffset<Dim>(s, {kernel, f.polynomial, f.smoothing, f.shift * scale, f.solver}, rep));
  };
  out.model = fitOn(out.samples, 1.0, &out.report);
  out.warnings.insert(out.warnings.end(), out.report.warnings.begin(), out.report.warnings.end());
  if (!scene.transform.isIdentity()) {
    const Similarity<Dim> T = sceneSimilarity<Dim>(scene.transform);
    TransformReport& tr = out.transform;
    auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<RadialSum<Dim>> updated;
    if (auto* h = dynamic_cast<const HrbfModel<Dim>*>(out.model.get()))
      updated = std::make_unique<HrbfModel<Dim>>(transformModel<Dim>(*h, T));
    else
      updated = std::make_unique<RbfOffsetModel<Dim>>(
          transformModel<Dim>(static_cast<const RbfOffsetModel<Dim>&>(*out.model), T));
    tr.updateMs = msSince(t0);
    const HermiteSamples<Dim> moved = transformSamples(out.samples, T);
    t0 = std::chrono::steady_clock::now();
    FitReport rep;
    std::unique_ptr<RadialSum<Dim>> resolved = fitOn(moved, T.q, &rep);
    tr.resolveMs = msSince(t0);
    // Probes: the transformed samples and fixed pseudo-random points in their box grown by 25 %.
    Box<Dim> box = boundingBox<Dim>(moved.points);
    const Vec<Dim> grow = Vec<Dim>::Constant(0.25 * box.extent().maxCoeff());
    box.lo -= grow;
    box.hi += grow;
    Points<Dim> probes(Dim, moved.size() + 256);
    probes.leftCols(moved.size()) = moved.points;
    std::uint64_t state = 0x9E3779B97F4A7C15ull;
    for (Eigen::Index i = moved.size(); i < probes.cols(); ++i)
      for (int k = 0; k < Dim; ++k) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const double u = double(state >> 11) * 0x1.0p-53;
        probes(k, i) = box.lo(k) + u * (box.hi(k) - box.lo(k));
      }
    Eigen::VectorXd fu, fr;
    Points<Dim> gu, gr;
    updated->evaluateBatch(probes, fu, &gu);
    resolved->evaluateBatch(probes, fr, &gr);
    tr.probes = static_cast<int>(probes.cols());
    tr.maxAbsDf = (fu - fr).cwiseAbs().maxCoeff();
    tr.maxGradDiff = (gu - gr).colwise().norm().maxCoeff();
    std::string why;
    tr.exact = coefficientUpdateIsExact(Kernel{f.kernel, f.radius}, f.polynomial, f.smoothing, &why);
    tr.method = tr.exact ? "coefficient-update" : "re-solve";
    if (!tr.exact) out.warnings.push_back("transform: " + why);
    out.model = tr.exact ? std::move(updated) : std::move(resolved);
    out.transformed = true;
    out.data = moved;
  } else {
    out.data = out.samples;
  }
  return out;
}

template <int Dim>
FitResiduals fitResiduals(const SceneFit<Dim>& fit) {
  FitResiduals r;
  if (fit.data.size() == 0) return r;
  Eigen::VectorXd f;
  Points<Dim> G;
  fit.model->evaluateBatch(fit.data.points, f, &G);
  r.maxAbsF = f.cwiseAbs().maxCoeff();
  r.maxGradError = (G - fit.data.normals).colwise().norm().maxCoeff();
  return r;
}

template HermiteSamples<2> sceneSamples<2>(const Scene&, std::vector<std::string>&);
template HermiteSamples<3> sceneSamples<3>(const Scene&, std::vector<std::string>&);
template Similarity<2> sceneSimilarity<2>(const TransformSpec&);
template Similarity<3> sceneSimilarity<3>(const TransformSpec&);
template FitResiduals fitResiduals<2>(const SceneFit<2>&);
template FitResiduals fitResiduals<3>(const SceneFit<3>&);
template SceneFit<2> fitScene<2>(const Scene&);
template SceneFit<3> fitScene<3>(const Scene&);

}  // namespace hermite
