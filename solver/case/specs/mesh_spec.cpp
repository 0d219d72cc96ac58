#include "case/specs/mesh_spec.hpp"

#include "case/case.hpp"
#include "case/schema.hpp"

namespace needlefem {

namespace {

// Keys that only the mesh scene reads: given in another scene, they would be ignored silently.
bool mesh_scene_key(const std::string& key) {
  for (const char* prefix : {"groups.", "displacement.", "pressure.", "obstacle.", "loading.history_"})
    if (key.rfind(prefix, 0) == 0) return true;
  return false;
}

std::vector<std::string> mesh_scene_keys_given(const Case& c) {
  std::vector<std::string> given;
  for (const auto& spec : case_schema())
    if (mesh_scene_key(spec.key) && c.given(spec.key)) given.push_back(spec.key);
  return given;
}

}  // namespace

MeshSpec parse_mesh_spec(const Case& c) {
  const std::vector<double> block = c.reals("block.size_mm");  // the schema gives it three entries
  return {.origin = c.origin(),
          .scene_kind = parse_scene_kind(c),
          .scene_mesh_file = c.path("scene.mesh_file"),
          .order = c.integer("mesh.order"),
          .optimize_high_order = c.flag("mesh.optimize_high_order"),
          .seed = c.integer("mesh.seed"),
          .refinement_level = c.integer("mesh.refinement_level"),
          .edge_elements_per_radius = c.maybe_integer("mesh.edge_elements_per_radius"),
          .partitions = c.integer("mesh.partitions"),
          .needle_tip = parse_needle_tip_spec(c),
          .tissue = parse_tissue_cube_spec(c),
          .curvature_elements = c.integer("tissue.curvature_elements"),
          .needle_edge_radius_um = c.real("needle.edge_radius_um"),
          .needle_mesh_volume = c.flag("needle.mesh_volume"),
          .needle_export_file = c.path("needle.export_file"),
          .block_size_mm = {block[0], block[1], block[2]},
          .block_element_mm = c.real("block.element_mm"),
          .mesh_scene_keys_given = mesh_scene_keys_given(c)};
}

bool generates_brain_tip_scene(const MeshSpec& spec) {
  return spec.scene_kind == SceneKind::brain_tip && spec.scene_mesh_file.empty();
}

}  // namespace needlefem
