#pragma once
// A data file opened as a scene is read for its default scene (dataFileScene: the spacing, the
// box) and again by the fit that follows. The first read leaves its samples here and the second
// takes them, so `hermite-lab mesh FILE` parses a 200 000-point file once (about 0.4 s of a 5 s
// run). One entry, taken once: it is used only when the path, the dimension, the loader options,
// the file's size and its modification time all match; otherwise the file is read again.

#include <optional>
#include <string>
#include <vector>

#include "core/points/hermite_samples.h"
#include "io/point_file.h"

namespace hermite {

// Leaves the samples read from `path` (with `options`) and the warnings that reading gave.
template <int Dim>
void keepLoadedSamples(const std::string& path, const PointFileOptions& options, const HermiteSamples<Dim>& samples,
                       const std::vector<std::string>& warnings);

// The samples left for the unchanged `path` (their warnings appended to `warnings`), removed from
// the hand-off; nullopt when none match.
template <int Dim>
std::optional<HermiteSamples<Dim>> takeLoadedSamples(const std::string& path, const PointFileOptions& options,
                                                     std::vector<std::string>& warnings);

}  // namespace hermite
