#include "model/partition.hpp"

#include <algorithm>
#include <stdexcept>

#include <metis.h>

namespace needlefem {

namespace {

std::size_t count_interface_nodes(const TetMesh& mesh, const std::vector<int>& tet_part) {
  std::vector<int> first_part(mesh.nodes.size(), -1);
  std::vector<char> shared(mesh.nodes.size(), 0);
  for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
    const int* t = mesh.tet(e);
    for (int k = 0; k < mesh.nodes_per_tet; ++k) {
      int& p = first_part[t[k]];
      if (p < 0) p = tet_part[e];
      else if (p != tet_part[e]) shared[t[k]] = 1;
    }
  }
  return static_cast<std::size_t>(std::count(shared.begin(), shared.end(), 1));
}

}  // namespace

Partition partition_tets(const TetMesh& mesh, int parts) {
  Partition out;
  out.parts = parts;
  const std::size_t n = mesh.tet_count();
  out.tet_part.assign(n, 0);
  if (parts <= 1) return out;

  std::vector<idx_t> eptr(n + 1), eind(4 * n);
  for (std::size_t e = 0; e <= n; ++e) eptr[e] = static_cast<idx_t>(4 * e);
  for (std::size_t e = 0; e < n; ++e)
    for (std::size_t k = 0; k < 4; ++k) eind[4 * e + k] = mesh.tet(e)[k];
  idx_t ne = static_cast<idx_t>(n), nn = static_cast<idx_t>(mesh.nodes.size()), ncommon = 3, nparts = parts,
        objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;  // deterministic
  std::vector<idx_t> epart(n), npart(mesh.nodes.size());
  const int status = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &nparts,
                                        nullptr, options, &objval, epart.data(), npart.data());
  if (status != METIS_OK) throw std::runtime_error("METIS_PartMeshDual failed with status " + std::to_string(status));
  std::copy(epart.begin(), epart.end(), out.tet_part.begin());
  out.edge_cut = objval;
  out.interface_nodes = count_interface_nodes(mesh, out.tet_part);

  std::vector<int> naive(n);
  for (std::size_t e = 0; e < n; ++e) naive[e] = static_cast<int>(e * static_cast<std::size_t>(parts) / n);
  out.naive_interface_nodes = count_interface_nodes(mesh, naive);

  std::vector<std::size_t> sizes(static_cast<std::size_t>(parts), 0);
  for (int p : out.tet_part) ++sizes[static_cast<std::size_t>(p)];
  out.max_imbalance = static_cast<double>(*std::max_element(sizes.begin(), sizes.end())) * parts / static_cast<double>(n);
  return out;
}

}  // namespace needlefem
