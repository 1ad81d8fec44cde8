#pragma once
// How thick a point cloud's surface is, for telling a noisy scan from a sampled surface
// (docs/maths.md, "Noisy clouds"): at probes spread over the cloud, the root-mean-square
// distance of the k nearest other points from their best-fit hyperplane (√ of the least
// eigenvalue of their covariance), relative to their mean distance from the probe; the median
// over the probes. Sampled surfaces give under 0.1 (their curvature across a neighbourhood:
// 0.01–0.07 on CGAL's closed meshes and clean scans); points scattered through a volume — noise
// as large as the spacing or larger — about 0.4.

#include "core/base/geometry.h"

namespace hermite {

struct LayerThicknessOptions {
  int neighbours = 12;      // k ≥ Dim
  int maxProbes = 2000;     // probes, evenly strided over the cloud
  int maxTree = 50000;      // above this many points the neighbours come from an evenly strided
                            // subset of this size (a coarser scale: the check stays ~10 ms)
};

struct LayerThickness {
  double median = 0;  // the relative thickness (0 for fewer than k + 1 points)
  int probes = 0;     // how many probes it is the median of
};

template <int Dim>
LayerThickness layerThickness(const Points<Dim>& points, const LayerThicknessOptions& options = {});

// A cloud this thick (median relative thickness) is noise rather than a surface: an interpolating
// fit follows it into a rough surface with many handles.
inline constexpr double kNoisyLayer = 0.3;

}  // namespace hermite
