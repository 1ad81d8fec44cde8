#pragma once
// From a parsed Scene to a fitted field: the samples the scene names (preset, file or inline),
// the fit it asks for (HRBF or RBF-offset), and its `transform` (DESIGN.md §4).
//
// The transformed model is the interpolant of the transformed data (points Tpᵢ, normals Rnᵢ,
// radius q·r, shift q·δ), which equals q·f(T⁻¹x) (DESIGN.md §3). Until coefficient updates
// land (transform issue) it is obtained by re-solving on the transformed data.

#include <memory>
#include <string>
#include <vector>

#include "core/hrbf.h"
#include "core/rbf_offset.h"
#include "core/scene_file.h"

namespace hermite {

// The samples of a scene, validated; warnings (merged duplicates, ...) are appended.
template <int Dim>
HermiteSamples<Dim> sceneSamples(const Scene& scene, std::vector<std::string>& warnings);

// Similarity transform x ↦ q·R·x + t of a scene's `transform` key.
template <int Dim>
struct Similarity {
  Mat<Dim> R = Mat<Dim>::Identity();
  Vec<Dim> t = Vec<Dim>::Zero();
  double q = 1.0;
  Vec<Dim> apply(const Vec<Dim>& x) const { return q * (R * x) + t; }
};
template <int Dim>
Similarity<Dim> sceneSimilarity(const TransformSpec& spec);

// Transformed data: points Tpᵢ, normals Rnᵢ.
template <int Dim>
HermiteSamples<Dim> transformSamples(const HermiteSamples<Dim>& samples, const Similarity<Dim>& T);

struct TransformReport {
  double resolveMs = 0;  // time of the re-solve on the transformed data
};

template <int Dim>
struct SceneFit {
  HermiteSamples<Dim> samples;             // the scene's data, before the transform
  std::unique_ptr<RadialSum<Dim>> model;   // the fitted (and transformed) field
  FitReport report;                        // of the fit on the untransformed data
  std::vector<std::string> warnings;       // data + fit warnings, in order
  bool transformed = false;
  TransformReport transform;
};

// Throws InputError for scene settings that cannot be fitted (wrong mode, partition of unity
// before it exists) and NumericalError from the solver.
template <int Dim>
SceneFit<Dim> fitScene(const Scene& scene);

}  // namespace hermite
