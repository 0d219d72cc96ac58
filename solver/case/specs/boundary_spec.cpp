#include "case/specs/boundary_spec.hpp"

#include <algorithm>
#include <utility>

#include "case/case.hpp"
#include "case/specs/choice.hpp"
#include "case/specs/contact_spec.hpp"
#include "case/specs/mesh_spec.hpp"

namespace needlefem {

namespace {

// block.x_min ... block.z_max's choices (schema.cpp) with their enumerators.
const std::array kFaceConditions{std::pair{"free", FaceCondition::free}, std::pair{"fixed", FaceCondition::fixed},
                                 std::pair{"roller", FaceCondition::roller},
                                 std::pair{"normal-displacement", FaceCondition::normal_displacement},
                                 std::pair{"displacement", FaceCondition::displacement}};

std::array<double, 9> matrix(const Case& c, const std::string& key) {
  const std::vector<double> v = c.reals(key);  // the schema gives these keys nine entries
  std::array<double, 9> m{};
  std::copy(v.begin(), v.end(), m.begin());
  return m;
}

BlockSpec parse_block_spec(const Case& c) {
  BlockSpec spec{
      .applied_gradient = matrix(c, "block.applied_gradient"), .faces = {}, .ramp_s = c.real("loading.ramp_s")};
  for (std::size_t f = 0; f < spec.faces.size(); ++f)
    spec.faces[f] = parse_choice(c, "block." + block_face_names()[f], kFaceConditions);
  return spec;
}

}  // namespace

const std::array<std::string, 6>& block_face_names() {
  static const std::array<std::string, 6> names{"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
  return names;
}

BoundarySpec parse_boundary_spec(const Case& c, const MeshSpec& mesh, const LoadingSpec& loading,
                                 ContactMode contact_mode) {
  BoundarySpec spec{.scene_kind = mesh.scene_kind,
                    .block = parse_block_spec(c),
                    .groups = {.origin = c.origin(),
                               .fixed = c.texts("groups.fixed"),
                               .roller = c.texts("groups.roller"),
                               .displaced = c.texts("groups.displaced"),
                               .displacement_gradient = matrix(c, "displacement.gradient"),
                               .mesh_file = mesh.scene_mesh_file},
                    .loading = loading,
                    .tied_cavity_motion = std::nullopt};
  if (spec.scene_kind == SceneKind::brain_tip && contact_mode == ContactMode::tied)
    spec.tied_cavity_motion = parse_motion_spec(c);
  return spec;
}

}  // namespace needlefem
