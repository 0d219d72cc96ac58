// Element partitioning for MPI ranks with METIS (METIS_PartMeshDual on the corner nodes,
// elements adjacent when they share a face), and the measure that says whether it earns its
// place: the number of interface nodes (nodes touched by elements of two or more parts), which
// sets the halo exchange volume of a distributed assembly, against the naive split of the
// elements into contiguous blocks in file order.
#pragma once

#include <vector>

#include "model/tet_mesh.hpp"

namespace needlefem {

struct Partition {
  int parts = 1;
  std::vector<int> tet_part;          // part of each tet
  std::size_t interface_nodes = 0;    // with METIS
  std::size_t naive_interface_nodes = 0;  // contiguous blocks in file order
  long edge_cut = 0;                  // METIS objective: cut dual-graph edges
  double max_imbalance = 1;           // largest part / mean part size
};

// Throws std::runtime_error if METIS fails.
Partition partition_tets(const TetMesh& mesh, int parts);

}  // namespace needlefem
