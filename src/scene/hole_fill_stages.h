#pragma once
// The hole-filling pipeline stopped at a chosen stage, for the GUI's `holefill` mode and its
// headless renders (each stage visible on its own): the input mesh, its holes, and
// per hole the patch as that stage leaves it, plus the ring samples the implicit was fitted to.
// Built-in holed meshes (`holefill.preset`) let a class start without a file.

#include <functional>
#include <string>
#include <vector>

#include "core/mesh/hole_fill.h"
#include "core/base/enum_names.h"

namespace hermite {

inline constexpr EnumName<HoleFillStage> kHoleFillStageNames[] = {{"holes", HoleFillStage::Holes},
                                                                  {"front", HoleFillStage::Front},
                                                                  {"fair", HoleFillStage::Fair},
                                                                  {"fit", HoleFillStage::Fit},
                                                                  {"project", HoleFillStage::Project}};
std::string_view holeFillStageName(HoleFillStage s);
inline constexpr EnumName<HoleImplicitKind> kHoleImplicitNames[] = {{"rbf-offset", HoleImplicitKind::RbfOffset},
                                                                    {"hrbf", HoleImplicitKind::Hrbf}};

struct HoleFillSpec {
  std::string mesh;           // a mesh file as written in the scene ("" = the preset)
  std::string resolvedMesh;   // resolved against the scene file's directory
  std::string preset = "torus";  // torus | sphere: built-in meshes with holes cut
  HoleFillStage stage = HoleFillStage::Project;
  HoleImplicitKind implicit = HoleImplicitKind::RbfOffset;
  int rings = 2;
  bool operator==(const HoleFillSpec&) const = default;
};

const std::vector<std::pair<std::string, std::string>>& holeFillPresets();
// The preset's closed surface with holes cut (InputError for an unknown name).
TriMesh holeFillPresetMesh(const std::string& name);

struct HoleFillStageHole : HoleOutcome {
  BoundaryLoop loop;
};

struct HoleFillStages {
  TriMesh input;                            // as mended by repairMesh
  std::vector<std::string> repairMessages;  // what was mended or found there
  std::vector<HoleFillStageHole> holes;
  TriMesh result;            // input + every patch at the stage (for export)
  int trianglesAdded = 0;
  int unconverged = 0;
  double maxAbsF = 0;        // after projection
  double ms = 0;
};

// Runs the pipeline up to `spec.stage` on `mesh` (the spec's file or preset when null).
// `progress` (optional) receives the fraction done (holes in turn, each through its stages);
// false from it stops: the hole being filled and the rest are left open with reason "cancelled".
HoleFillStages runHoleFillStages(const HoleFillSpec& spec, const std::function<bool(double)>& progress = {});

}  // namespace hermite
