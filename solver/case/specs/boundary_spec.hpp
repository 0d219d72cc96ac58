// What a scene prescribes on its boundary, parsed: the block's faces ([block]), a mesh scene's
// surface groups ([groups], [displacement]), and a tied needle's cavity (brain-tip): the input of
// physics/mechanics/dirichlet.hpp.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "case/specs/contact_spec.hpp"
#include "case/specs/loading_spec.hpp"
#include "case/specs/motion_spec.hpp"
#include "case/specs/scene_kind.hpp"

namespace needlefem {

class Case;
struct MeshSpec;

// The block's faces, two per axis (face f is normal to axis f / 2): the names of their keys
// (block.x_min, ...) and of their surface groups.
const std::array<std::string, 6>& block_face_names();

enum class FaceCondition { free, fixed, roller, normal_displacement, displacement };

struct BlockSpec {
  std::array<double, 9> applied_gradient;  // F, row-major
  std::array<FaceCondition, 6> faces;      // in the order of block_face_names()
  double ramp_s;                           // loading.ramp_s: F is reached by then
};

struct MeshSceneGroupsSpec {
  std::string origin;  // the case's, for the CaseError of a roller group that is not a plane
  std::vector<std::string> fixed, roller, displaced;
  std::array<double, 9> displacement_gradient;  // displacement.gradient, row-major
  std::filesystem::path mesh_file;              // the mesh spec's scene.mesh_file, named in errors
};

struct BoundarySpec {
  SceneKind scene_kind;
  BlockSpec block;
  MeshSceneGroupsSpec groups;
  LoadingSpec loading;
  // A brain-tip scene with contact.mode = "tied": the motion its cavity follows (parsed, and so
  // checked, only then).
  std::optional<MotionSpec> tied_cavity_motion;
};

// The scene's kind and file from `mesh` (parse_mesh_spec, which parses scene.kind and
// scene.mesh_file), its loading and contact.mode from the specs parsed from the same case.
BoundarySpec parse_boundary_spec(const Case& c, const MeshSpec& mesh, const LoadingSpec& loading,
                                 ContactMode contact_mode);

}  // namespace needlefem
