// Small meshes for the output tests: a cube [0, edge]^3 cut into the 6 Kuhn tetrahedra
// (all share the main diagonal from vertex 0 to vertex 6), with quadratic edge nodes.
#pragma once

#include "model/tet_mesh.hpp"

namespace needlefem::output::testing {

// TET10 (gmsh node order) when quadratic, else TET4. Two regions: tets 0-2 "tissue",
// tets 3-5 "needle". With `quadratic`, named surfaces "bottom" (z = 0, two TRI6 faces) and
// "top" (z = edge). No node is perturbed.
TetMesh kuhn_cube(double edge, bool quadratic);

// Index of the edge node between vertices a and b of kuhn_cube(..., true).
int edge_node(const TetMesh& mesh, int a, int b);

}  // namespace needlefem::output::testing
