#pragma once
// The hole-filling pipeline stopped at a chosen stage, for the GUI's `holefill` mode and its
// headless renders (issue 8 §3: each stage visible on its own): the input mesh, its holes, and
// per hole the patch as that stage leaves it, plus the ring samples the implicit was fitted to.
// Built-in holed meshes (`holefill.preset`) let a class start without a file.

#include <string>
#include <vector>

#include "core/hole_fill.h"

namespace hermite {

std::string_view holeFillStageName(HoleFillStage s);  // holes, front, fair, fit, project

struct HolefillSpec {
  std::string mesh;           // a mesh file as written in the scene ("" = the preset)
  std::string resolvedMesh;   // resolved against the scene file's directory
  std::string preset = "torus";  // torus | sphere: built-in meshes with holes cut
  HoleFillStage stage = HoleFillStage::Project;
  HoleImplicitKind implicit = HoleImplicitKind::RbfOffset;
  int rings = 2;
  bool operator==(const HolefillSpec&) const = default;
};

const std::vector<std::pair<std::string, std::string>>& holefillPresets();
// The preset's closed surface with holes cut (InputError for an unknown name).
TriMesh holefillPresetMesh(const std::string& name);

struct HolefillStageHole : HoleOutcome {
  BoundaryLoop loop;
};

struct HolefillStages {
  TriMesh input;
  std::vector<HolefillStageHole> holes;
  TriMesh result;            // input + every patch at the stage (for export)
  int trianglesAdded = 0;
  int unconverged = 0;
  double maxAbsF = 0;        // after projection
  double ms = 0;
};

// Runs the pipeline up to `spec.stage` on `mesh` (the spec's file or preset when null).
HolefillStages runHolefillStages(const HolefillSpec& spec);

}  // namespace hermite
