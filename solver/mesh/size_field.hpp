// The brain-tip scene's element size field, inside a GmshSession after the scene's geometry is
// synchronised: the core and outer sizes, the compliant tip's neck annulus, and the grading
// towards the needle's sharp edges and its surface that mesh.refinement_level halves per level.
// Internal to mesh/ (it speaks gmsh's tags); scene_mesher.cpp is its user.
#pragma once

#include <set>
#include <vector>

#include <gmsh.h>

#include "mesh/scene_mesher.hpp"

namespace needlefem {

struct MeshSpec;
struct NeedleTip;

// 2^-L for mesh.refinement_level L: the factor every refined size carries.
double refinement_size_factor(const MeshSpec& spec);

// Adds the element size field of a brain-tip scene with cube edge `edge` and core width `core`
// (mm) whose cavity surfaces are `cavity`, and returns its tag (for setAsBackgroundMesh). Fills
// the sizes aimed at in `grading` and the cavity's sharp curves, which the edge grading follows,
// in `edges`.
int add_size_field(const MeshSpec& spec, const NeedleTip& tip, double edge, double core, const std::vector<int>& cavity,
                   NeedleGrading& grading, std::vector<int>& edges);

// Size statistics of the tissue tets with a corner node on the given entities (after meshing).
ElementSizeStats element_sizes_touching(const std::set<int>& tissue_volumes, const gmsh::vectorpair& entities);

}  // namespace needlefem
