// A quadratic-tetrahedron mesh of paper 000's compliant needle tip alone (shaft, neck, head; the
// geometry of mesh/scene_mesher's compliant tip), for the structural FEM of the hinge
// (prbm_check/tip_statics.hpp). Element size: `neck_element` in the slab of the neck and one neck
// diameter d beyond it (s - d <= z <= s + l + d: the neck gets several elements across and the
// shoulders' corners are resolved on both sides), `element` elsewhere;
// mid-side nodes on the curved CAD faces (gmsh high-order optimisation), because the bending
// stiffness of a faceted neck is off by twice its area error.
#pragma once

#include "geometry/needle_tip.hpp"
#include "model/tet_mesh.hpp"

namespace needlefem::prbm {

struct TipMeshSizes {
  double element_m = 0.25e-3;       // shaft and head
  double neck_element_m = 0.05e-3;  // neck slab
};

// Regions of the returned mesh, by element centroid: "shaft" (z < s), "neck" (s <= z <= s + l),
// "head" (z > s + l). Coordinates in metres, TET10 in gmsh node order; no surface groups.
// Throws std::runtime_error when gmsh fails (inverted elements are caught by CompliantTipStatics).
TetMesh mesh_compliant_tip(const CompliantTip& tip, const TipMeshSizes& sizes);

}  // namespace needlefem::prbm
