#include "physics/mechanics/dof_map.hpp"

namespace needlefem::mechanics {

DofMap tissue_dof_map(const TetMesh& mesh) {
  DofMap map;
  std::vector<bool> in_tissue(mesh.nodes.size(), false);
  const int needle = mesh.region_index("needle");
  for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
    if (mesh.tet_region[e] == needle) continue;
    map.tissue_tets.push_back(e);
    for (int a = 0; a < mesh.nodes_per_tet; ++a) in_tissue[mesh.tet(e)[a]] = true;
  }
  map.node_dof.assign(mesh.nodes.size(), -1);
  for (std::size_t node = 0; node < mesh.nodes.size(); ++node)
    if (in_tissue[node]) {
      map.node_dof[node] = map.dof_count;
      map.dof_count += 3;
    }
  return map;
}

}  // namespace needlefem::mechanics
