// The mesh-resolution rule (case/mesh_resolution.hpp): a brain-tip case coarser than the setting
// the convergence study found adequate is named key by key; the studied setting and finer ones,
// the block scene and user meshes are not.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "case/case.hpp"
#include "case/mesh_resolution.hpp"
#include "case/specs/mesh_spec.hpp"

using needlefem::Case;
using needlefem::coarse_mesh_warning;
using needlefem::coarser_than_converged;
using needlefem::mesh_resolution_json;
using needlefem::MeshSpec;
using needlefem::parse_mesh_spec;

namespace {
std::vector<std::string> coarser(const std::vector<std::string>& overrides) {
  return coarser_than_converged(parse_mesh_spec(Case::parse("[scene]\nkind = \"brain-tip\"\n", "tip.toml", overrides)));
}
}  // namespace

TEST(MeshResolution, TheStudiedSettingAndFinerOnesAreConverged) {
  EXPECT_TRUE(coarser({}).empty());
  EXPECT_TRUE(coarser({"tissue.core_element_mm=0.2", "tissue.outer_element_mm=1.5"}).empty());
  EXPECT_TRUE(coarser({"mesh.refinement_level=2"}).empty());
  const MeshSpec tip = parse_mesh_spec(Case::parse("[scene]\nkind = \"brain-tip\"\n", "tip.toml"));
  EXPECT_EQ(mesh_resolution_json(tip)["as_converged"], true);
  EXPECT_EQ(coarse_mesh_warning(coarser_than_converged(tip)), "");
}

TEST(MeshResolution, EachCoarserKeyIsNamedWithItsValueAndTheLimit) {
  EXPECT_EQ(coarser({"tissue.core_element_mm=0.41"}), std::vector<std::string>{"tissue.core_element_mm = 0.41 mm > 0.4 mm"});
  // paper001_quick.toml's mesh
  const std::vector<std::string> quick{"tissue.core_element_mm = 1 mm > 0.4 mm", "tissue.outer_element_mm = 3 mm > 2 mm"};
  EXPECT_EQ(coarser({"tissue.core_element_mm=1", "tissue.outer_element_mm=3"}), quick);
  // A finer level refines only near the needle: it does not make a coarse core the studied setting.
  EXPECT_EQ(coarser({"tissue.core_element_mm=1", "tissue.outer_element_mm=3", "mesh.refinement_level=2"}), quick);
  EXPECT_EQ(coarser({"mesh.order=1"}), std::vector<std::string>{"mesh.order = 1 < 2"});
  EXPECT_EQ(coarse_mesh_warning(quick),
            "mesh coarser than the converged setting (tissue.core_element_mm = 1 mm > 0.4 mm, tissue.outer_element_mm = "
            "3 mm > 2 mm): the verdict may change on a finer mesh (docs/accuracy.md section 4)");
}

TEST(MeshResolution, ScenesTheStudyDidNotCoverAreNotJudged) {
  const MeshSpec block = parse_mesh_spec(Case::parse("[scene]\nkind = \"block\"\n", "block.toml", {"mesh.order=1"}));
  EXPECT_TRUE(coarser_than_converged(block).empty());
  EXPECT_TRUE(mesh_resolution_json(block).is_null());
  const MeshSpec user_mesh = parse_mesh_spec(Case::parse("[scene]\nkind = \"brain-tip\"\nmesh_file = \"tip.msh\"\n",
                                                         "tip.toml", {"tissue.core_element_mm=1"}));
  EXPECT_TRUE(coarser_than_converged(user_mesh).empty());
}
