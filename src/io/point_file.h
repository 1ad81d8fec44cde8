#pragma once
// Oriented point files (docs/scene-format.md):
//   .xyz / .pwn / .xyzn   x y z nx ny nz per line (3 columns = no normals: estimated)
//   .xyn                  2D: x y nx ny per line (2 columns = no normals: estimated too)
//   .xyz                  also 2D when its first data line has 2 or 4 numbers (x y [nx ny])
//   .ply .obj .gltf .glb .off  3D: the vertices and vertex normals of a mesh or point-set file
//                         (PLY nx ny nz, OBJ v + vn, glTF POINTS/TRIANGLES with NORMAL, NOFF),
//                         read by mesh_io. A mesh without vertex normals gets the area-weighted
//                         means of its face normals; a point set without them estimated ones.
// Missing normals (Dim columns) and zero normals (all or some) are estimated by PCA and oriented
// consistently with the given ones (completeNormals, normal_estimation.h), with a warning that
// says how many.
// Given normals that are not consistently oriented (PointFileOptions, GivenNormals) are
// re-oriented by the same propagation (orientNormalLines), lines kept, with a warning.
// Blank lines and lines starting with '#' are skipped. A malformed line is an InputError
// "FILE:LINE: ..." saying what was expected.

#include <string>
#include <string_view>
#include <vector>

#include "core/points/hermite_samples.h"

namespace hermite {

// What happens to the normals a file gives (docs/scene-format.md, data.orient_normals):
//   Auto    for files of 50 samples or more (smaller ones are hand-made, their normals meant),
//           when more than 0.5 % of the neighbour pairs along a sheet point opposite ways
//           (orientationDisagreement), the signs are re-chosen by propagation; the result is
//           taken when it turns at least 5 % of them (a region inside out, CGAL's cube.pwn),
//           else the file's signs stay (scattered noise, which propagation would not improve);
//           either way a warning says so;
//   Always  re-chosen by propagation (warning when any sign changes);
//   Never   kept as given.
enum class GivenNormals { Auto, Always, Never };

struct PointFileOptions {
  GivenNormals orient = GivenNormals::Auto;
};

// Dimension of a point file: 2 for .xyn and for a .xyz whose first data line has 2 or 4 numbers
// (the file is read for that), 3 otherwise; InputError for an unknown extension, listing the
// supported ones.
int pointFileDimension(const std::string& path);

// Whether a 3D text file with normals (.xyz with 6 numbers per line, .pwn, .xyzn) holds curve
// data: every sample has the same z and every normal has nz exactly 0 (CGAL's point_set_2.xyz).
// Reads the first 64 KiB, and the whole file only while every line so far is in the plane; false
// for anything else, malformed files included (the loader reports those).
bool isPlanarCurveText(const std::string& path);

// The dimension of the scene built around a data file: pointFileDimension, but 2 for curve data
// written as 3D (isPlanarCurveText). loadPointFile2d reads such a file as x y nx ny.
int dataFileDimension(const std::string& path);

// Loads and validates (validateSamples) a point file; warnings are appended.
HermiteSamples<2> loadPointFile2d(const std::string& path, std::vector<std::string>& warnings,
                                  const PointFileOptions& options = {});
HermiteSamples<3> loadPointFile3d(const std::string& path, std::vector<std::string>& warnings,
                                  const PointFileOptions& options = {});

// Reads probe points for `eval --at FILE`: Dim numbers per line (extra columns are an error).
Points<2> loadProbePoints2d(const std::string& path);
Points<3> loadProbePoints3d(const std::string& path);

// The text formats (.xyz / .pwn / .xyzn, .xyn, probe files) parsed from memory; `path` names
// the text in messages. The loaders above read the file and call these.
HermiteSamples<2> parsePointText2d(std::string_view text, const std::string& path, std::vector<std::string>& warnings,
                                   const PointFileOptions& options = {});
HermiteSamples<3> parsePointText3d(std::string_view text, const std::string& path, std::vector<std::string>& warnings,
                                   const PointFileOptions& options = {});
Points<3> parseProbeText3d(std::string_view text, const std::string& path);

// Writes samples as .xyzn / .xyn (temporary + rename).
void savePointFile(const std::string& path, const HermiteSamples<3>& samples);
void savePointFile(const std::string& path, const HermiteSamples<2>& samples);

}  // namespace hermite
