// Meshing of the compliant tip alone; see tip_mesh.hpp.
#include "prbm_check/tip_mesh.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

#include <gmsh.h>

#include "mesh/gmsh_session.hpp"
#include "mesh/scene_mesher.hpp"

namespace needlefem::prbm {

namespace {

constexpr double kMmPerM = 1e3;
constexpr int kGmshTet10 = 11;

// Element size field: neck_element inside the neck slab widened by one neck diameter on both
// sides (the shoulders' re-entrant corners concentrate the bending stress on the shaft and head
// sides too), element elsewhere.
void set_size_field(const CompliantTip& tip, const TipMeshSizes& sizes) {
  const int neck = gmsh::model::mesh::field::add("Box");
  gmsh::model::mesh::field::setNumber(neck, "VIn", sizes.neck_element_m * kMmPerM);
  gmsh::model::mesh::field::setNumber(neck, "VOut", sizes.element_m * kMmPerM);
  const double reach = 2.0 * tip.radius * kMmPerM;
  gmsh::model::mesh::field::setNumber(neck, "XMin", -reach);
  gmsh::model::mesh::field::setNumber(neck, "XMax", reach);
  gmsh::model::mesh::field::setNumber(neck, "YMin", -reach);
  gmsh::model::mesh::field::setNumber(neck, "YMax", reach);
  const double margin = tip.neck_diameter;
  gmsh::model::mesh::field::setNumber(neck, "ZMin", std::max(0.0, tip.shaft - margin) * kMmPerM);
  gmsh::model::mesh::field::setNumber(neck, "ZMax", (tip.shaft + tip.neck_length + margin) * kMmPerM);
  gmsh::model::mesh::field::setAsBackgroundMesh(neck);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.RandomSeed", 1);
  gmsh::option::setNumber("Mesh.ElementOrder", 2);
  gmsh::option::setNumber("Mesh.SecondOrderLinear", 0);
}

// The 10-node tets of the model, numbering only the nodes they use (gmsh also keeps nodes of
// CAD points that no tet touches).
TetMesh extract_mesh(const CompliantTip& tip) {
  std::vector<std::size_t> node_tags;
  std::vector<double> coordinates, parametric;
  gmsh::model::mesh::getNodes(node_tags, coordinates, parametric, -1, -1, true, false);
  std::map<std::size_t, std::size_t> position;
  for (std::size_t i = 0; i < node_tags.size(); ++i) position[node_tags[i]] = i;
  std::vector<std::size_t> element_tags, element_nodes;
  gmsh::model::mesh::getElementsByType(kGmshTet10, element_tags, element_nodes);
  if (element_tags.empty()) throw std::runtime_error("gmsh: the compliant tip mesh has no 10-node tetrahedra");

  TetMesh mesh;
  mesh.nodes_per_tet = 10;
  mesh.region_names = {"shaft", "neck", "head"};
  std::map<std::size_t, int> index;
  for (std::size_t e = 0; e < element_tags.size(); ++e) {
    double centroid_z = 0.0;
    for (int a = 0; a < 10; ++a) {
      const std::size_t tag = element_nodes[10 * e + a];
      auto [it, added] = index.try_emplace(tag, static_cast<int>(mesh.nodes.size()));
      if (added) {
        const std::size_t i = position.at(tag);
        mesh.nodes.push_back({coordinates[3 * i] / kMmPerM, coordinates[3 * i + 1] / kMmPerM,
                              coordinates[3 * i + 2] / kMmPerM});
      }
      mesh.tet_nodes.push_back(it->second);
      if (a < 4) centroid_z += 0.25 * mesh.nodes[it->second][2];
    }
    mesh.tet_region.push_back(centroid_z < tip.shaft ? 0 : centroid_z <= tip.shaft + tip.neck_length ? 1 : 2);
  }
  return mesh;
}

}  // namespace

TetMesh mesh_compliant_tip(const CompliantTip& tip, const TipMeshSizes& sizes) {
  TetMesh mesh;
  GmshSession session("compliant_tip");
  GmshSession::guarded([&] {
    add_compliant_tip(tip);
    gmsh::model::occ::synchronize();
    set_size_field(tip, sizes);
    gmsh::model::mesh::generate(3);
    optimise_high_order();
    mesh = extract_mesh(tip);
  });
  return mesh;
}

}  // namespace needlefem::prbm
