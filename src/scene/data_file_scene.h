#pragma once
// A data file opened where a scene is expected (`hermite-lab FILE`, `fit FILE`, the GUI's Open
// box and dropped files; docs/scene-format.md, "Data files as scenes"): the file is read once,
// and a default scene is built around it:
//   mode       implicit2d for .xyn, implicit3d for every other point or mesh file
//   data.file  the path as given
//   fit        hrbf, cubic kernel (scale-free: no radius to tune), linear polynomial, partition
//              "auto" (dense while small, else partition of unity); fit.radius is set to 4 × the
//              mean sample spacing, the scale a kernel with a radius starts from
//   view       the default view; view.bounds null (the samples' box grown by 25 %)
// --set overrides apply to that scene as to a scene file's.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "scene/scene_file.h"

namespace hermite {

// The extensions `hermite-lab` opens: a scene (.json), a point file or a mesh file.
inline constexpr const char* kOpenableExtensions =
    ".json (a scene); .xyz, .pwn, .xyzn, .xyn (point files); .ply, .obj, .gltf, .glb, .off (meshes and point sets)";

// True for a scene file (.json), false for a point or mesh file; InputError naming the accepted
// extensions for anything else.
bool isSceneFilePath(const std::string& path);

// The default scene around a data file and what reading it found: the samples' box (2·Dim
// numbers, min then max, as view.bounds) for framing the view, their count and mean spacing, and
// the loader's warnings (estimated normals, merged duplicates). Reading or validating the file
// throws its InputError.
struct DataFileScene {
  Scene scene;
  std::vector<double> samplesBox;
  Eigen::MatrixXd points;  // Dim × N: the samples' positions (the GUI draws them while the fit runs)
  int samples = 0;
  double spacing = 0;
  std::vector<std::string> warnings;
};
DataFileScene dataFileScene(const std::string& path, const std::vector<std::string>& overrides = {});

// The scene with data.file and holefill.mesh rewritten relative to `directory` (absolute paths
// are kept absolute when the two share no root): what a scene saved into `directory` names.
Scene withPathsRelativeTo(Scene scene, const std::string& directory);

}  // namespace hermite
