// Equations: dirichlet.hpp.
#include "physics/mechanics/dirichlet.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "case/case.hpp"
#include "geometry/needle_motion.hpp"

namespace needlefem::mechanics {

namespace {

// Collects conditions so that a dof constrained again takes the latest field.
class ConditionBuilder {
 public:
  ConditionBuilder(const TetMesh& mesh, const DofMap& map) : mesh_(mesh), map_(map) {}

  int add_field(DisplacementField field) {
    conditions_.fields.push_back(std::move(field));
    return static_cast<int>(conditions_.fields.size()) - 1;
  }

  void constrain_surface(const std::string& surface, const std::vector<int>& components, int field) {
    const auto faces = mesh_.surface_faces.find(surface);
    if (faces == mesh_.surface_faces.end()) throw std::runtime_error("the mesh has no surface '" + surface + "'");
    for (int node : faces->second) {
      if (map_.node_dof[node] < 0) continue;
      for (int c : components) by_dof_[map_.dof(node, c)] = PrescribedDof{map_.dof(node, c), node, c, field};
    }
  }

  DirichletConditions finish() {
    for (const auto& [dof, prescribed] : by_dof_) conditions_.dofs.push_back(prescribed);
    return std::move(conditions_);
  }

 private:
  const TetMesh& mesh_;
  const DofMap& map_;
  DirichletConditions conditions_;
  std::map<int, PrescribedDof> by_dof_;
};

// F - I of a row-major F.
std::array<double, 9> minus_identity(const std::array<double, 9>& F) {
  std::array<double, 9> displacement_gradient{};
  for (int n = 0; n < 9; ++n) displacement_gradient[n] = F[n] - (n % 4 == 0 ? 1.0 : 0.0);
  return displacement_gradient;
}

const DisplacementField kZeroField = [](const Point3&, double) { return Point3{0.0, 0.0, 0.0}; };

// The coordinate axis a surface group is normal to (all its nodes share that coordinate to 1e-9
// of the mesh's extent), or none.
std::optional<int> normal_axis(const TetMesh& mesh, const std::string& surface) {
  Point3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300}, mesh_lo = lo, mesh_hi = hi;
  for (const Point3& X : mesh.nodes)
    for (int c = 0; c < 3; ++c) mesh_lo[c] = std::min(mesh_lo[c], X[c]), mesh_hi[c] = std::max(mesh_hi[c], X[c]);
  for (int node : mesh.surface_faces.at(surface))
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], mesh.nodes[node][c]), hi[c] = std::max(hi[c], mesh.nodes[node][c]);
  const double extent = std::max({mesh_hi[0] - mesh_lo[0], mesh_hi[1] - mesh_lo[1], mesh_hi[2] - mesh_lo[2]});
  for (int c = 0; c < 3; ++c)
    if (hi[c] - lo[c] <= 1e-9 * extent) return c;
  return std::nullopt;
}

}  // namespace

std::optional<double> block_inversion_time_s(const BlockSpec& block) {
  const std::array<double, 9>& F = block.applied_gradient;
  bool full = false;                     // a "displacement" face imposes all of F
  std::array<bool, 3> normal{};          // a "normal-displacement" face imposes F's diagonal on its axis
  for (int f = 0; f < 6; ++f) {
    full = full || block.faces[f] == FaceCondition::displacement;
    if (block.faces[f] == FaceCondition::normal_displacement) normal[f / 2] = true;
  }
  // The largest value that must stay positive: det F(s) when all of F is imposed, else the
  // stretch 1 + s (F_ii - 1) of each axis whose faces are pushed (at 0 a face meets its opposite).
  auto inverted = [&](double s) {
    std::array<double, 9> a{};
    for (int n = 0; n < 9; ++n) a[n] = (n % 4 == 0 ? 1.0 : 0.0) + s * (F[n] - (n % 4 == 0 ? 1.0 : 0.0));
    if (full)
      return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
                 a[2] * (a[3] * a[7] - a[4] * a[6]) <= 0.0;
    for (int i = 0; i < 3; ++i)
      if (normal[i] && a[4 * i] <= 0.0) return true;
    return false;
  };
  // det(I + s G) is a cubic in s, 1 at s = 0: scan for the first sign change, then bisect
  // (1e3 slices step over only a root pair closer than 1e-3 of the ramp, a field that all but
  // inverts the block anyway).
  constexpr int slices = 1000;
  double below = 0.0, above = -1.0;
  for (int k = 1; k <= slices && above < 0.0; ++k) {
    const double s = static_cast<double>(k) / slices;
    (inverted(s) ? above : below) = s;
  }
  if (above < 0.0) return std::nullopt;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (below + above);
    (inverted(mid) ? above : below) = mid;
  }
  return block.ramp_s > 0.0 ? above * block.ramp_s : 0.0;
}

DirichletConditions block_conditions(const BlockSpec& block, const TetMesh& mesh, const DofMap& map) {
  const std::array<double, 9> displacement_gradient = minus_identity(block.applied_gradient);
  const double ramp_s = block.ramp_s;

  ConditionBuilder builder(mesh, map);
  const int zero = builder.add_field(kZeroField);
  const int affine = builder.add_field([displacement_gradient, ramp_s](const Point3& X, double t) {
    const double s = ramp_then_hold(t, ramp_s);
    Point3 u{};
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) u[i] += s * displacement_gradient[3 * i + J] * X[J];
    return u;
  });
  for (int f = 0; f < 6; ++f) {
    const std::string& face = block_face_names()[f];
    const int axis = f / 2;
    if (block.faces[f] == FaceCondition::fixed) builder.constrain_surface(face, {0, 1, 2}, zero);
    if (block.faces[f] == FaceCondition::roller) builder.constrain_surface(face, {axis}, zero);
    if (block.faces[f] == FaceCondition::normal_displacement) builder.constrain_surface(face, {axis}, affine);
    if (block.faces[f] == FaceCondition::displacement) builder.constrain_surface(face, {0, 1, 2}, affine);
  }
  return builder.finish();
}

DirichletConditions brain_tip_conditions(const std::optional<MotionSpec>& tied_cavity_motion, const TetMesh& mesh,
                                         const DofMap& map) {
  ConditionBuilder builder(mesh, map);
  builder.constrain_surface("fixed", {0, 1, 2}, builder.add_field(kZeroField));
  if (!tied_cavity_motion) return builder.finish();
  const NeedleMotion motion = needle_motion_from_spec(*tied_cavity_motion);
  builder.constrain_surface("cavity", {0, 1, 2}, builder.add_field([motion](const Point3& X, double t) {
                              const double elapsed = motion.elapsed(t);
                              const double angle = motion.rotation_speed * elapsed;
                              const double c = std::cos(angle), s = std::sin(angle);
                              return Point3{c * X[0] - s * X[1] - X[0], s * X[0] + c * X[1] - X[1],
                                            motion.insertion_speed * elapsed};
                            }));
  return builder.finish();
}

DirichletConditions mesh_scene_conditions(const MeshSceneGroupsSpec& groups, const LoadingSpec& loading,
                                          const TetMesh& mesh, const DofMap& map) {
  ConditionBuilder builder(mesh, map);
  const int zero = builder.add_field(kZeroField);
  for (const auto& group : groups.fixed) builder.constrain_surface(group, {0, 1, 2}, zero);
  for (const auto& group : groups.roller) {
    const std::optional<int> axis = normal_axis(mesh, group);
    if (!axis)
      throw case_error(groups.origin, "groups.roller",
                       fmt::format("group '{}' of {} is not a plane x, y or z = const, and a roller holds the normal "
                                   "component of such a plane only", group, groups.mesh_file.string()));
    builder.constrain_surface(group, {*axis}, zero);
  }
  const std::array<double, 9> displacement_gradient = minus_identity(groups.displacement_gradient);
  const int displaced = builder.add_field([displacement_gradient, history = LoadHistory::from_spec(loading)](
                                              const Point3& X, double t) {
    const double s = history.factor(t);
    Point3 u = history.translation(t);
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) u[i] += s * displacement_gradient[3 * i + J] * X[J];
    return u;
  });
  for (const auto& group : groups.displaced) builder.constrain_surface(group, {0, 1, 2}, displaced);
  return builder.finish();
}

DirichletConditions scene_conditions(const BoundarySpec& boundary, const TetMesh& mesh, const DofMap& map) {
  if (boundary.scene_kind == SceneKind::block) return block_conditions(boundary.block, mesh, map);
  if (boundary.scene_kind == SceneKind::mesh)
    return mesh_scene_conditions(boundary.groups, boundary.loading, mesh, map);
  return brain_tip_conditions(boundary.tied_cavity_motion, mesh, map);
}

}  // namespace needlefem::mechanics
