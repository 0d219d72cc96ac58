// edge_elements_per_radius (mesh/scene_mesher.hpp), the edge grading's n: not given, 2 on bevels
// under 15° with edges (the 10° tips), 1 on the rest; a given value stands on any tip.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "case/case.hpp"
#include "case/specs/mesh_spec.hpp"
#include "geometry/needle_tip.hpp"
#include "mesh/scene_mesher.hpp"

namespace needlefem {
namespace {

long edge_elements(const std::vector<std::string>& overrides) {
  const MeshSpec spec = parse_mesh_spec(Case::parse("", "a.toml", overrides));
  return edge_elements_per_radius(spec, needle_tip_from_spec(spec.needle_tip));
}

TEST(EdgeGrading, EdgeElementsPerRadiusFollowsTheBevelAngleUnlessGiven) {
  EXPECT_EQ(edge_elements({"needle.bevel_deg=10"}), 2);
  EXPECT_EQ(edge_elements({"needle.bevel_deg=14.9"}), 2);
  EXPECT_EQ(edge_elements({"needle.bevel_deg=15"}), 1);
  EXPECT_EQ(edge_elements({"needle.bevel_deg=20"}), 1);
  // The rounded end (fillet = radius) has no edges to resolve.
  EXPECT_EQ(edge_elements({"needle.bevel_deg=10", "needle.radius_mm=1.25", "needle.fillet_mm=1.25"}), 1);
  EXPECT_EQ(edge_elements({"needle.bevel_deg=10", "mesh.edge_elements_per_radius=1"}), 1);
  EXPECT_EQ(edge_elements({"needle.bevel_deg=20", "mesh.edge_elements_per_radius=3"}), 3);
  EXPECT_EQ(edge_elements({"needle.kind=compliant", "needle.bevel_deg=10"}), 1);
}

}  // namespace
}  // namespace needlefem
