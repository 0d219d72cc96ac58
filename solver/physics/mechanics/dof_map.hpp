// Displacement degrees of freedom of the tissue: three consecutive dofs (x, y, z) per node of a
// tissue tetrahedron, numbered in mesh-node order. Tets of the "needle" region (the optional
// deformable needle) carry no tissue dofs; nodes only they use get none.
#pragma once

#include <cstddef>
#include <vector>

#include "model/tet_mesh.hpp"

namespace needlefem::mechanics {

struct DofMap {
  std::vector<int> node_dof;              // first dof of each mesh node, -1 without dofs
  std::vector<std::size_t> tissue_tets;   // mesh tet indices of the tissue
  int dof_count = 0;

  int dof(int node, int component) const { return node_dof[node] + component; }
};

DofMap tissue_dof_map(const TetMesh& mesh);

}  // namespace needlefem::mechanics
