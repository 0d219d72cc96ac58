// Element validity and shape measures of a TetMesh, per region.
//  det J is sampled at the element's nodes and at the degree-5 quadrature points;
//  scaled Jacobian = min det J / max det J over those samples (1 for straight-sided tets);
//  radius ratio = 3 r_in / r_circ of the corner tetrahedron (1 for the regular tet).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "model/tet_mesh.hpp"

namespace needlefem {

struct RegionQuality {
  std::size_t tets = 0, nodes = 0;
  std::size_t inverted = 0;  // tets with any det J <= 0
  double volume_m3 = 0;
  double min_jacobian = 0, max_jacobian = 0;  // det J in m^3 (6 x volume for a straight tet)
  double min_scaled_jacobian = 0;
  double min_radius_ratio = 0, mean_radius_ratio = 0;
};

struct MeshQuality {
  std::map<std::string, RegionQuality> regions;
  std::vector<double> tet_scaled_jacobian;  // per tet
  std::vector<double> tet_radius_ratio;     // per tet
  std::size_t inverted() const;
  double volume_of_regions_starting_with(const std::string& prefix) const;
};

MeshQuality measure_quality(const TetMesh& mesh);
nlohmann::json to_json(const RegionQuality& q);

}  // namespace needlefem
