// Prescribed displacements (Dirichlet conditions) of the mechanics scenes.
//
// Block scene (scene.kind = "block"), per face x_min .. z_max (key block.<face>):
//   free                 no condition
//   fixed                u = 0
//   roller               u·n = 0 (n the face's axis)
//   normal-displacement  u·n = ū·n
//   displacement         u = ū
// with the affine field ū(X, t) = s(t) (F - I) X, F = block.applied_gradient and the load factor
// s(t) = min(t / loading.ramp_s, 1) (ramp, then hold). A dof constrained by several faces (an
// edge or corner) takes the condition of the last face in the order x_min, x_max, y_min, y_max,
// z_min, z_max; consistent conditions (all derived from ū) agree there anyway.
//
// Mesh scene (scene.kind = "mesh"), on named surface groups of the user's mesh:
//   groups.fixed      u = 0
//   groups.roller     u·n = 0 with n the group's normal, which must be a coordinate axis (the group
//                     a plane x, y or z = const): symmetry planes, and the end faces of a long body,
//                     which then deforms in plane strain (the generalised plane strain of axially
//                     periodic ends, a free uniform axial stretch, is not offered)
//   groups.displaced  u = ū(X, t) = s(t) (F - I) X + d(t), F = displacement.gradient, s(t) and the
//                     translation d(t) of the loading history (load_history.hpp)
// A dof in several groups takes the condition of the last list in the order fixed, roller, displaced.
//
// Brain-tip scene (scene.kind = "brain-tip", paper 001): the five skull faces ("fixed") are
// fixed; the entry face is free. The needle acts on the cavity through frictional contact
// (physics/contact/needle_contact.hpp, added by the caller as a surface load), unless
// contact.mode = "tied": then the tissue nodes on the needle cavity ("cavity") follow the
// rigid needle: with τ(t) of the needle motion (geometry/needle_motion.hpp: τ = min(t, duration)
// without a start ramp), insertion speed v and rotation speed ω about the needle axis (the z axis
// through the centre of the entry face, pointing into the tissue),
//   x(X, t) = R_z(ω τ) X + v τ e_z,   u = x - X.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "case/specs/boundary_spec.hpp"
#include "model/tet_mesh.hpp"
#include "physics/mechanics/dof_map.hpp"
#include "physics/mechanics/load_history.hpp"

namespace needlefem::mechanics {

// Prescribed displacement u(X, t), metres.
using DisplacementField = std::function<Point3(const Point3& X, double t)>;

struct PrescribedDof {
  int dof = 0;
  int node = 0;
  int component = 0;
  int field = 0;  // index into DirichletConditions::fields
};

struct DirichletConditions {
  std::vector<DisplacementField> fields;
  std::vector<PrescribedDof> dofs;  // each constrained dof once

  double value(const TetMesh& mesh, const PrescribedDof& d, double t) const {
    return fields[d.field](mesh.nodes[d.node], t)[d.component];
  }
};

DirichletConditions block_conditions(const BlockSpec& block, const TetMesh& mesh, const DofMap& map);

// The first time at which the block's applied field F(s) = I + s (F - I), s = ramp_then_hold(t),
// has det F(s) <= 0 (it would turn the block inside out), or none. No elastic state exists past
// it: a run stops there with a clear error instead of IDA shrinking its step to 1e-14 s.
std::optional<double> block_inversion_time_s(const BlockSpec& block);
// The fixed faces, and with a tied needle (BoundarySpec::tied_cavity_motion) the cavity moved with it.
DirichletConditions brain_tip_conditions(const std::optional<MotionSpec>& tied_cavity_motion, const TetMesh& mesh,
                                         const DofMap& map);
// Throws CaseError for a roller group that is not a coordinate plane, and LoadHistory::from_spec's.
DirichletConditions mesh_scene_conditions(const MeshSceneGroupsSpec& groups, const LoadingSpec& loading,
                                          const TetMesh& mesh, const DofMap& map);
// The conditions of the case's scene.kind.
DirichletConditions scene_conditions(const BoundarySpec& boundary, const TetMesh& mesh, const DofMap& map);

}  // namespace needlefem::mechanics
