// The solver's mesh: quadratic (or linear) tetrahedra with named regions and boundary faces.
// Coordinates are in metres (SI inside the code); .msh files are in millimetres.
// Node order inside an element is gmsh's: vertices 0-3, then edge nodes
// (0,1) (1,2) (2,0) (3,0) (3,2) (3,1) for TET10; TRI6 faces are vertices 0-2 then (0,1) (1,2) (2,0).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace needlefem {

using Point3 = std::array<double, 3>;

struct TetMesh {
  int nodes_per_tet = 10;                  // 10 (TET10) or 4 (TET4)
  std::vector<Point3> nodes;               // metres
  std::vector<int> tet_nodes;              // nodes_per_tet entries per tet
  std::vector<int> tet_region;             // index into region_names, per tet
  std::vector<std::string> region_names;   // physical volume names, e.g. "tissue", "needle"

  int nodes_per_face() const { return nodes_per_tet == 10 ? 6 : 3; }
  // Boundary faces per physical surface name ("entry", "fixed", "cavity", "x_min", ...),
  // nodes_per_face() node indices per face, oriented with the outward normal of the region.
  std::map<std::string, std::vector<int>> surface_faces;
  // (tissue node, needle node) pairs that were one node before the cavity was rounded
  // (cavity_rounding.hpp): the needle region keeps the sharp shape on copies of its cavity nodes.
  std::vector<std::array<int, 2>> split_nodes;

  std::size_t tet_count() const { return tet_region.size(); }
  const int* tet(std::size_t e) const { return tet_nodes.data() + e * nodes_per_tet; }
  int region_index(const std::string& name) const;  // -1 when absent
};

}  // namespace needlefem
