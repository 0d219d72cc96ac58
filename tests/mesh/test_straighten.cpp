// straighten_inverted_tets (mesh/scene_mesher.hpp): a second-order tet folded by a misplaced
// mid-edge node is found by its Jacobian and made straight-edged, after which every tet of the
// mesh has a positive Jacobian; a valid mesh is left as it is.
#include <algorithm>
#include <vector>

#include <gmsh.h>
#include <gtest/gtest.h>

#include "mesh/gmsh_session.hpp"
#include "mesh/scene_mesher.hpp"

namespace needlefem {
namespace {

constexpr int kTet10 = 11;

// Smallest Jacobian determinant of each TET10 at its nodes and a degree-6 rule.
std::vector<double> smallest_jacobians() {
  std::string name;
  int dim = 0, order = 0, nodes = 0, vertices = 0;
  std::vector<double> points, gauss, weights, jacobians, determinants, coordinates;
  gmsh::model::mesh::getElementProperties(kTet10, name, dim, order, nodes, points, vertices);
  gmsh::model::mesh::getIntegrationPoints(kTet10, "Gauss6", gauss, weights);
  points.insert(points.end(), gauss.begin(), gauss.end());
  gmsh::model::mesh::getJacobians(kTet10, points, jacobians, determinants, coordinates);
  const std::size_t per_tet = points.size() / 3;
  std::vector<double> smallest;
  for (std::size_t i = 0; i < determinants.size(); i += per_tet)
    smallest.push_back(*std::min_element(determinants.begin() + i, determinants.begin() + i + per_tet));
  return smallest;
}

TEST(Straighten, FoldedTetBecomesValidAndValidMeshIsKept) {
  GmshSession::guarded([] {
    GmshSession session("straighten");
    gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
    gmsh::model::occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.5);
    gmsh::option::setNumber("Mesh.ElementOrder", 2);
    gmsh::model::mesh::generate(3);
    const auto valid = smallest_jacobians();
    ASSERT_GT(valid.size(), 4u);
    ASSERT_GT(*std::min_element(valid.begin(), valid.end()), 0.0);
    EXPECT_EQ(straighten_inverted_tets(), 0u);

    // Fold tet 0: move the mid-node of its edge 0-1 past the opposite vertex 3.
    std::vector<std::size_t> tags, nodes;
    gmsh::model::mesh::getElementsByType(kTet10, tags, nodes);
    std::vector<double> x3, mid, parametric;
    gmsh::model::mesh::getNode(nodes[3], x3, parametric);
    gmsh::model::mesh::getNode(nodes[4], mid, parametric);
    std::vector<double> folded(3);
    for (int k = 0; k < 3; ++k) folded[k] = mid[k] + 1.5 * (x3[k] - mid[k]);
    gmsh::model::mesh::setNode(nodes[4], folded, {});
    const auto before = smallest_jacobians();
    const auto inverted = std::count_if(before.begin(), before.end(), [](double j) { return j <= 0; });
    ASSERT_GE(inverted, 1);

    const std::size_t straightened = straighten_inverted_tets();
    EXPECT_GE(straightened, static_cast<std::size_t>(inverted));
    EXPECT_LE(straightened, 12u);  // the folded tet and at most the tets around its edges
    const auto after = smallest_jacobians();
    EXPECT_GT(*std::min_element(after.begin(), after.end()), 0.0);
  });
}

}  // namespace
}  // namespace needlefem
