#pragma once
// Hermite data: points with unit outward normals (the side where an implicit fit is f > 0), validated.

#include <string>
#include <vector>

#include "core/base/geometry.h"

namespace hermite {

template <int Dim>
struct HermiteSamples {
  Points<Dim> points;   // Dim × N
  Points<Dim> normals;  // Dim × N, unit length after validateSamples
  int size() const { return static_cast<int>(points.cols()); }
};

// The samples without sample i, in their order (leave-one-out, a drag's other samples).
template <int Dim>
HermiteSamples<Dim> withoutSample(const HermiteSamples<Dim>& samples, int i);

// Validates and cleans samples in place:
//  - a non-finite coordinate or normal → InputError naming the sample index (0-based);
//  - a zero normal → InputError naming the index;
//  - normals are normalised;
//  - exact duplicate points with the same normal (after normalisation, to 1e-12) are merged,
//    with a warning appended to `warnings`; duplicates with conflicting normals → InputError.
// `source` (a file name or "inline data") prefixes every message. `order`, when given, is the
// points' lexicographicOrder (lexicographic_order.h), which a caller that sorted them already
// passes instead of having them sorted again.
template <int Dim>
void validateSamples(HermiteSamples<Dim>& samples, std::vector<std::string>& warnings,
                     const std::string& source = "samples", const std::vector<Eigen::Index>* order = nullptr);

// Mean distance from each sample to its nearest other sample (0 for fewer than two samples).
// Used to express r in units of the sample spacing.
template <int Dim>
double meanSampleSpacing(const Points<Dim>& points);

}  // namespace hermite
