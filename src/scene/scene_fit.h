#pragma once
// From a parsed Scene to a fitted field: the samples the scene names (preset, file or inline),
// the fit it asks for (HRBF or RBF-offset), and its `transform` (docs/scene-format.md).
//
// The transformed model is the interpolant of the transformed data (points Tpᵢ, normals Rnᵢ,
// radius q·r, shift q·δ), which equals q·f(T⁻¹x) (docs/maths.md, Transforms): obtained by coefficient
// updates (transform.h) and checked against a re-solve; where the update is not exact (λ ≠ 0,
// polynomial below the kernel's order) the re-solve is used, with a warning.

#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "core/base/affine_field.h"
#include "core/mesh/degenerate_field.h"
#include "core/pu/pu_model.h"
#include "core/rbf/hrbf.h"
#include "core/rbf/rbf_offset.h"
#include "core/rbf/similarity_transform.h"
#include "scene/scene_file.h"

namespace hermite {

// The samples of a scene, validated; warnings (merged duplicates, ...) are appended.
template <int Dim>
HermiteSamples<Dim> sceneSamples(const Scene& scene, std::vector<std::string>& warnings);

// The similarity x ↦ scale·R·x + translate of a scene's `transform` key (3D: axis-angle in
// degrees, right-hand rule; 2D: counter-clockwise degrees).
template <int Dim>
Similarity<Dim> sceneSimilarity(const TransformSpec& spec);

// The `transform` object of `fit --json` (docs/cli.md).
struct TransformReport {
  double updateMs = 0;     // coefficient update
  // The comparison with a re-solve, present only when transform.verify asks for it.
  std::optional<double> resolveMs;    // re-solve on the transformed data
  std::optional<double> maxAbsDf;     // max |f_update − f_resolve| over probe points
  std::optional<double> maxGradDiff;  // max ‖∇f_update − ∇f_resolve‖
  int probes = 0;
  bool exact = true;       // the update is the re-solved fit (else the re-solve is used)
  std::string method;      // "coefficient-update" or "re-solve"
};

// What a fitted scene says regardless of its dimension: reports, warnings and the transform.
struct SceneFitReport {
  PuReport puReport;                       // of the PU fit on the untransformed data
  FitReport report;                        // of the fit on the untransformed data
  std::vector<std::string> warnings;       // data + fit warnings, in order
  int dataWarnings = 0;                    // the first of them, about the data file (normals, duplicates)
  bool transformed = false;
  TransformReport transform;
  // checkDegenerateField's verdict (scene/degenerate_check.h); empty until it ran and where it does
  // not apply (kernels that grow with distance).
  std::optional<DegenerateFieldReport> degenerateField;
};

// The fitted model: one global interpolant of fit.method, or a partition of unity
// (fit.partition.enabled, "auto" by size: choosePartition in scene_fit_memory.h). Held on the heap so that compositions wrapping it survive moves.
template <int Dim>
using FittedModel =
    std::variant<std::unique_ptr<HrbfModel<Dim>>, std::unique_ptr<RbfOffsetModel<Dim>>, std::unique_ptr<PuModel<Dim>>>;

// The field of whichever model `m` holds.
template <int Dim>
const ImplicitField<Dim>& fittedField(const FittedModel<Dim>& m) {
  return std::visit([](const auto& p) -> const ImplicitField<Dim>& { return *p; }, m);
}

template <int Dim>
struct SceneFit : SceneFitReport {
  static constexpr int kDim = Dim;
  HermiteSamples<Dim> samples;  // the scene's data, before the transform
  HermiteSamples<Dim> data;     // what the model interpolates: samples, transformed if asked
  FittedModel<Dim> model;       // the fitted (and, by a similarity, transformed) model
  // transform.matrix outside the similarities: the exact composition f(T⁻¹x) of `model`.
  std::unique_ptr<ImplicitField<Dim>> composed;
  // The field with "no data" marked where it has none, or null: a degenerate field's flat
  // regions (scene/degenerate_check.h), and beyond a data file's samples for a global fit
  // (scene/data_reach_mask.h).
  std::unique_ptr<ImplicitField<Dim>> masked;

  // The fitted field, whatever its kind: what evaluation, rendering and meshing consume.
  const ImplicitField<Dim>& field() const {
    if (masked) return *masked;
    return unmaskedField();
  }
  // The field without those masks (what the degenerate check and the r sweep judge).
  const ImplicitField<Dim>& unmaskedField() const {
    if (composed) return *composed;
    return modelField();
  }
  // The model without the composition.
  const ImplicitField<Dim>& modelField() const { return fittedField<Dim>(model); }
  // The partition of unity, or null for a global fit.
  const PuModel<Dim>* pu() const {
    const auto* p = std::get_if<std::unique_ptr<PuModel<Dim>>>(&model);
    return p ? p->get() : nullptr;
  }
};

// Residuals of a fitted scene against the data it interpolates (SceneFit::data).
struct FitResiduals {
  double maxAbsF = 0;       // max |f(pᵢ)|
  double maxGradError = 0;  // max ‖∇f(pᵢ) − nᵢ‖
};
template <int Dim>
FitResiduals fitResiduals(const SceneFit<Dim>& fit);

// The PU options of a scene's `fit` (kernel, polynomial, smoothing, solver, `fit.partition`).
PuOptions scenePuOptions(const FitSpec& fit, const CancelToken* cancel = nullptr);

// Throws InputError for scene settings that cannot be fitted (wrong mode, partition of unity
// with a method other than hrbf) and NumericalError from the solver; Cancelled once `cancel`
// (optional, polled between boxes, phases and factorisation tiles) is set.
template <int Dim>
SceneFit<Dim> fitScene(const Scene& scene, const CancelToken* cancel = nullptr);

}  // namespace hermite
