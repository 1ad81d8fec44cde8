#include "scene/scene_fit.h"

#include <chrono>
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <limits>

#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "core/shapes/presets.h"
#include "io/point_file.h"
#include "scene/loaded_samples_handoff.h"
#include "scene/scene_fit_memory.h"

namespace hermite {

namespace {

template <int Dim>
HermiteSamples<Dim> loadFile(const std::string& path, std::vector<std::string>& warnings, const PointFileOptions& options) {
  if constexpr (Dim == 2)
    return loadPointFile2d(path, warnings, options);
  else
    return loadPointFile3d(path, warnings, options);
}

template <int Dim>
HermiteSamples<Dim> makePreset(const std::string& name, int count) {
  if constexpr (Dim == 2)
    return makePreset2d(name, count);
  else
    return makePreset3d(name, count);
}

// Fills probes, maxAbsDf and maxGradDiff of `tr`: the transformed samples (at most 20 000 of
// them, evenly strided) and 256 fixed pseudo-random points in their box grown by 25 %.
template <int Dim>
void compareOnProbes(const ImplicitField<Dim>& updated, const ImplicitField<Dim>& resolved, const Points<Dim>& moved,
                     TransformReport& tr) {
  Box<Dim> box = boundingBox<Dim>(moved);
  const Vec<Dim> grow = Vec<Dim>::Constant(0.25 * box.extent().maxCoeff());
  box.lo -= grow;
  box.hi += grow;
  const Eigen::Index stride = std::max<Eigen::Index>(1, (moved.cols() + 19999) / 20000);
  const Eigen::Index nData = (moved.cols() + stride - 1) / stride;
  Points<Dim> probes(Dim, nData + 256);
  for (Eigen::Index i = 0; i < nData; ++i) probes.col(i) = moved.col(i * stride);
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  for (Eigen::Index i = nData; i < probes.cols(); ++i)
    for (int k = 0; k < Dim; ++k) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      const double u = double(state >> 11) * 0x1.0p-53;
      probes(k, i) = box.lo(k) + u * (box.hi(k) - box.lo(k));
    }
  Eigen::VectorXd fu, fr;
  Points<Dim> gu, gr;
  updated.evaluateBatch(probes, fu, &gu);
  resolved.evaluateBatch(probes, fr, &gr);
  tr.probes = static_cast<int>(probes.cols());
  tr.maxAbsDf = (fu - fr).cwiseAbs().maxCoeff();
  tr.maxGradDiff = (gu - gr).colwise().norm().maxCoeff();
}

// Whether the transformed fit uses the coefficient update (else the re-solve): transform.method,
// with `auto` = the update exactly where it is the re-solved interpolant. Records the choice and
// its warning in the report.
template <int Dim>
bool chooseUpdate(const Scene& scene, SceneFit<Dim>& out) {
  const FitSpec& f = scene.fit;
  TransformReport& tr = out.transform;
  std::string why;
  tr.exact = coefficientUpdateIsExact(Kernel{f.kernel, f.radius}, f.polynomial, f.smoothing, &why);
  const TransformMethod m = scene.transform.method;
  const bool update = m == TransformMethod::Update || (m == TransformMethod::Auto && tr.exact);
  tr.method = update ? "coefficient-update" : "re-solve";
  if (!tr.exact && update)
    out.warnings.push_back("transform: the coefficient update (transform.method 'update') is q·f(T⁻¹x), not the "
                           "re-solved interpolant: " + why);
  else if (!tr.exact)
    out.warnings.push_back("transform: " + why);
  return update;
}

// The model a similarity transform keeps: `updated`, or the re-solve that `resolve` makes where
// chooseUpdate says so; with transform.verify the re-solve runs either way and the two are
// compared on probes around the moved samples.
template <int Dim, class Resolve>
FittedModel<Dim> keptModel(const Scene& scene, FittedModel<Dim> updated, const Points<Dim>& moved, SceneFit<Dim>& out,
                           Resolve resolve) {
  const bool update = chooseUpdate(scene, out);
  if (update && !scene.transform.verify) return updated;
  const auto t0 = std::chrono::steady_clock::now();
  FittedModel<Dim> resolved = resolve();
  if (scene.transform.verify) {
    out.transform.resolveMs = msSince(t0);
    compareOnProbes<Dim>(fittedField<Dim>(updated), fittedField<Dim>(resolved), moved, out.transform);
  }
  return update ? std::move(updated) : std::move(resolved);
}

// transform.verify for a composition: the re-solve on the transformed data (radius and shift
// scaled by |det A|^(1/Dim)), compared with the composed field on probes.
template <int Dim>
void verifyAffine(const Scene& scene, const Mat<Dim>& A, const HermiteSamples<Dim>& moved,
                  const ImplicitField<Dim>& composed, SceneFit<Dim>& out, const CancelToken* cancel) {
  TransformReport& tr = out.transform;
  const auto t0 = std::chrono::steady_clock::now();
  Scene re = scene;
  re.transform = TransformSpec{};
  re.transform.translate.assign(Dim, 0.0);
  re.data = DataSpec{};
  for (int i = 0; i < moved.size(); ++i) {
    re.data.points.emplace_back(moved.points.col(i).data(), moved.points.col(i).data() + Dim);
    re.data.normals.emplace_back(moved.normals.col(i).data(), moved.normals.col(i).data() + Dim);
  }
  const double s = std::pow(std::abs(A.determinant()), 1.0 / Dim);
  re.fit.radius *= s;
  re.fit.shift *= s;
  try {
    const SceneFit<Dim> resolved = fitScene<Dim>(re, cancel);
    tr.resolveMs = msSince(t0);
    compareOnProbes<Dim>(composed, resolved.field(), moved.points, tr);
  } catch (const Cancelled&) {
    throw;  // not a failure of the re-solve: the whole fit stops
  } catch (const std::exception& e) {
    out.warnings.push_back(std::string("transform: the re-solve for comparison failed: ") + e.what());
  }
}

// transform.matrix outside the similarities: g(x) = f(A⁻¹(x − b)) with A = M·q·R, b = translate:
// the exact composition, which is not the re-solved interpolant of the transformed data (points
// Apᵢ + b, normals A⁻ᵀnᵢ normalised); transform.verify says how far it is from one.
template <int Dim>
void composeAffine(const Scene& scene, SceneFit<Dim>& out, const CancelToken* cancel) {
  const Similarity<Dim> S = sceneSimilarity<Dim>(scene.transform);
  Mat<Dim> M;
  for (int i = 0; i < Dim; ++i)
    for (int j = 0; j < Dim; ++j) M(i, j) = scene.transform.matrix[std::size_t(i * Dim + j)];
  const Mat<Dim> A = M * (S.q * S.R);
  TransformReport& tr = out.transform;
  auto t0 = std::chrono::steady_clock::now();
  const ImplicitField<Dim>& inner = out.modelField();
  // Non-owning: the wrapped model lives in `out` beside the composition (moves keep it in place).
  auto composed = std::make_unique<AffineComposedField<Dim>>(
      std::shared_ptr<const ImplicitField<Dim>>(&inner, [](const ImplicitField<Dim>*) {}), A, S.t);
  tr.updateMs = msSince(t0);
  HermiteSamples<Dim> moved;
  moved.points = (A * out.samples.points).colwise() + S.t;
  moved.normals = (A.inverse().transpose() * out.samples.normals).colwise().normalized();
  if (scene.transform.verify) verifyAffine(scene, A, moved, *composed, out, cancel);
  tr.exact = false;
  tr.method = "composition";
  out.warnings.push_back(
      "transform: transform.matrix is not a similarity: the field is the composition f(T⁻¹x), not the re-solved "
      "interpolant of the transformed data");
  out.composed = std::move(composed);
  out.transformed = true;
  out.data = moved;
}


// The coefficient update of each model kind under a similarity (transform.h, pu_model.h).
template <int Dim>
FittedModel<Dim> updatedModel(const HrbfModel<Dim>& m, const Similarity<Dim>& T) {
  return std::make_unique<HrbfModel<Dim>>(transformModel<Dim>(m, T));
}
template <int Dim>
FittedModel<Dim> updatedModel(const RbfOffsetModel<Dim>& m, const Similarity<Dim>& T) {
  return std::make_unique<RbfOffsetModel<Dim>>(transformModel<Dim>(m, T));
}
template <int Dim>
FittedModel<Dim> updatedModel(const PuModel<Dim>& m, const Similarity<Dim>& T) {
  return std::make_unique<PuModel<Dim>>(transformPu<Dim>(m, T));
}

// The global model of fit.method on `s`, with radius and shift scaled by `scale`.
template <int Dim>
FittedModel<Dim> fitGlobal(const FitSpec& f, const HermiteSamples<Dim>& s, double scale, FitReport* rep,
                           const CancelToken* cancel) {
  const Kernel kernel{f.kernel, f.radius * scale};
  if (f.method == FitMethod::Hrbf)
    return std::make_unique<HrbfModel<Dim>>(
        fitHrbf<Dim>(s, {kernel, f.polynomial, f.smoothing, f.solver, cancel}, rep));
  return std::make_unique<RbfOffsetModel<Dim>>(
      fitRbfOffset<Dim>(s, {kernel, f.polynomial, f.smoothing, f.shift * scale, f.solver, cancel}, rep));
}

// The partition-of-unity fit of `out.samples` and its report in the scene's FitReport terms.
template <int Dim>
void fitScenePu(const Scene& scene, SceneFit<Dim>& out, const CancelToken* cancel) {
  out.model = std::make_unique<PuModel<Dim>>(fitPu<Dim>(out.samples, scenePuOptions(scene.fit, cancel), &out.puReport));
  const PuReport& pr = out.puReport;
  out.report.nSamples = out.samples.size();
  out.report.nUnknowns = pr.unknowns;
  out.report.solver = "partition-of-unity/" + pr.solver;
  out.report.conditionEstimate = pr.maxConditionEstimate;
  out.report.fitMs = pr.fitMs;
  out.report.assemblyMs = pr.treeMs;  // the tree; the local fits are all "solve"
  out.report.solveMs = pr.fitMs - pr.treeMs;
  out.report.warnings = pr.warnings;
}

// The re-solve on the data moved by T: a global fit with radius and shift scaled by q, or the
// PU construction with its tree built in the frame T (so only the local solves differ).
template <int Dim>
FittedModel<Dim> resolvedModel(const Scene& scene, const SceneFit<Dim>& out, const HermiteSamples<Dim>& moved,
                               const Similarity<Dim>& T, const CancelToken* cancel) {
  if (const PuModel<Dim>* pu = out.pu())
    return std::make_unique<PuModel<Dim>>(
        fitPu<Dim>(moved, scenePuOptions(scene.fit, cancel), nullptr, composeSimilarity<Dim>(T, pu->frame())));
  FitReport rep;
  return fitGlobal<Dim>(scene.fit, moved, T.q, &rep, cancel);
}

// A similarity `transform`: the coefficient update or the re-solve (keptModel).
template <int Dim>
void transformBySimilarity(const Scene& scene, SceneFit<Dim>& out, const CancelToken* cancel) {
  const Similarity<Dim> T = sceneSimilarity<Dim>(scene.transform);
  const auto t0 = std::chrono::steady_clock::now();
  FittedModel<Dim> updated = std::visit([&](const auto& m) { return updatedModel<Dim>(*m, T); }, out.model);
  out.transform.updateMs = msSince(t0);
  const HermiteSamples<Dim> moved = transformSamples(out.samples, T);
  out.model = keptModel<Dim>(scene, std::move(updated), moved.points, out,
                             [&] { return resolvedModel<Dim>(scene, out, moved, T, cancel); });
  out.transformed = true;
  out.data = moved;
}

}  // namespace

PuOptions scenePuOptions(const FitSpec& f, const CancelToken* cancel) {
  PuOptions o;
  o.local = HrbfOptions{Kernel{f.kernel, f.radius}, f.polynomial, f.smoothing, f.solver, cancel};
  o.maxPointsPerBox = f.partition.maxPointsPerBox;
  o.boxSize = f.partition.boxSize;
  o.overlap = f.partition.overlap;
  o.blend = f.partition.blend;
  o.dataReach = f.partition.dataReach;
  return o;
}

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
    // Samples handed off by the default scene's read were read for this dimension already.
    const PointFileOptions options{d.orientNormals};
    if (std::optional<HermiteSamples<Dim>> kept = takeLoadedSamples<Dim>(d.resolvedFile, options, warnings))
      return std::move(*kept);
    const int fileDim = pointFileDimension(d.resolvedFile);
    if (fileDim != Dim && !(Dim == 2 && isPlanarCurveText(d.resolvedFile)))
      throw InputError(scene.sourceName + ": data.file: '" + d.file + "' holds " + std::to_string(fileDim) +
                       "D points, the scene's mode '" + std::string(sceneModeName(scene.mode)) + "' needs " +
                       std::to_string(Dim) + "D");
    return loadFile<Dim>(d.resolvedFile, warnings, options);
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
SceneFit<Dim> fitScene(const Scene& scene, const CancelToken* cancel) {
  if (scene.dimension() != Dim || (scene.mode != SceneMode::Implicit2d && scene.mode != SceneMode::Implicit3d))
    throw InputError(scene.sourceName + ": mode: '" + std::string(sceneModeName(scene.mode)) +
                     "' scenes have no implicit fit");
  if (scene.fit.partition.enabled == PartitionSwitch::On && scene.fit.method != FitMethod::Hrbf)
    throw InputError(scene.sourceName + ": fit.partition.enabled: partition of unity fits method 'hrbf' only (got '" +
                     std::string(fitMethodName(scene.fit.method)) + "')");
  SceneFit<Dim> out;
  out.samples = sceneSamples<Dim>(scene, out.warnings);
  out.dataWarnings = static_cast<int>(out.warnings.size());
  const PartitionChoice choice = choosePartition(scene, out.samples.size());
  if (!choice.message.empty()) out.warnings.push_back(choice.message);
  if (choice.pu)
    fitScenePu(scene, out, cancel);
  else
    out.model = fitGlobal<Dim>(scene.fit, out.samples, 1.0, &out.report, cancel);
  out.warnings.insert(out.warnings.end(), out.report.warnings.begin(), out.report.warnings.end());
  if (scene.transform.isIdentity())
    out.data = out.samples;
  else if (!scene.transform.matrixIsIdentity())
    composeAffine(scene, out, cancel);
  else
    transformBySimilarity(scene, out, cancel);
  return out;
}

template <int Dim>
FitResiduals fitResiduals(const SceneFit<Dim>& fit) {
  FitResiduals r;
  if (fit.data.size() == 0) return r;
  Eigen::VectorXd f;
  Points<Dim> G;
  fit.field().evaluateBatch(fit.data.points, f, &G);
  // maxCoeff may skip a NaN: a non-finite field is reported as NaN explicitly.
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  r.maxAbsF = f.allFinite() ? f.cwiseAbs().maxCoeff() : kNaN;
  r.maxGradError = G.allFinite() ? (G - fit.data.normals).colwise().norm().maxCoeff() : kNaN;
  return r;
}

template HermiteSamples<2> sceneSamples<2>(const Scene&, std::vector<std::string>&);
template HermiteSamples<3> sceneSamples<3>(const Scene&, std::vector<std::string>&);
template Similarity<2> sceneSimilarity<2>(const TransformSpec&);
template Similarity<3> sceneSimilarity<3>(const TransformSpec&);
template FitResiduals fitResiduals<2>(const SceneFit<2>&);
template FitResiduals fitResiduals<3>(const SceneFit<3>&);
template SceneFit<2> fitScene<2>(const Scene&, const CancelToken*);
template SceneFit<3> fitScene<3>(const Scene&, const CancelToken*);

}  // namespace hermite
