// Frictional contact between the tissue cavity and the needle of the brain-tip scene (paper 001's
// rigid bevel, a CAD tip, or paper 000's hinged compliant tip), and the quantities `needlefem run`
// reports about it.
//
// Contact law: penalty_contact.hpp (penalty normal ε_N = c μ₀/h_face, slip-velocity-regularised
// Coulomb friction μ, at the surface quadrature points of the "cavity" faces). Obstacle:
// needle_obstacle.hpp (bevel or rounded tip, insertion v t' e_z and rotation ω t' about z), or
// hinged_needle.hpp (the compliant tip, its head also turned about the neck).
// Gaps are measured from each quadrature point's own gap at t = 0 (reference_gap_offset): the
// cavity is meshed from the needle's shape and its nodes moved onto the rounded needle
// (round_cavity_to_needle), so the undeformed tissue touches the needle and only the faceting of
// its curved faces (initial_gap(), reported) separates the two. A user's
// mesh (scene.mesh_file) is checked for that before its cavity is rounded: a cavity vertex off the
// needle's (unrounded) surface by more than r/1000 stops the run with one line naming it.
// contact.mode = "tied" keeps the earlier model instead (cavity nodes moved rigidly with the
// needle by Dirichlet conditions, physics/mechanics/dirichlet.hpp) for comparison.
//
// Resultants on the needle (Newton's third law on penalty_contact's tractions t on the tissue):
//   F = -∫ t dA₀,   M = -∫ (x - x_ref(t)) × t dA₀,   x_ref = centre of the rear face = v t' e_z;
// axial force F·e_z (negative = the tissue resists insertion along +z), torque about the axis
// M·e_z (opposes the rotation ω when friction drags the tissue).
// Surface fields, evaluated at each cavity node a with the same law (visualisation; the forces
// use the quadrature points):
//   pressure p_a = p_N(⟨ō_a - g(x_a)⟩) of penalty_contact.hpp with ε̄_a, the mean penalty of the
//            cavity faces around a (and δ_a = s μ₀/ε̄_a), and ō_a the mean multiplier offset of
//            those faces' points (augmented enforcement; 0 with the plain penalty),
//   slip     s_a = |(I - n nᵀ)(x_a - χ(X_a, t))|, χ(X_a, t) = where the needle point that touched
//            X_a at t = 0 (zero initial gap) is now: the tangential displacement of the tissue
//            relative to the needle since t = 0 (0 for a tied cavity).
#pragma once

#include <memory>
#include <vector>

#include "case/specs/mesh_spec.hpp"
#include "case/specs/motion_spec.hpp"
#include "model/cavity_rounding.hpp"
#include "model/tet_mesh.hpp"
#include "physics/contact/hinged_needle.hpp"
#include "physics/contact/needle_obstacle.hpp"
#include "physics/contact/penalty_contact.hpp"
#include "physics/mechanics/dof_map.hpp"

namespace needlefem::contact {

// What the case's needle is built from: the mesh spec (parse_mesh_spec: the needle in contact is
// the one the scene was meshed around), with its tip, the tissue cube a CAD tip's rules check it
// against, its edge rounding (needle.edge_radius_um) and, for a user's mesh, the cavity's check
// (scene.mesh_file); and its motion (parse_motion_spec).
struct NeedleSpecs {
  MeshSpec mesh;
  MotionSpec motion;
};

// The needle of the specs: the analytic bevel (needle_obstacle.hpp), a CAD tip
// (NeedleKind::cad, cad_needle.hpp), or the compliant tip, its head turned by `tilt`
// (NeedleKind::compliant, hinged_needle.hpp; null: not turned). Throws CaseError for a CAD file
// that breaks a rule (mesh/cad_tip.hpp). `sharp` (optional): also the same needle without its
// edge rounding (a CAD tip's from the same triangulation).
std::shared_ptr<const Needle> needle_from_spec(const NeedleSpecs& specs, std::shared_ptr<const Needle>* sharp = nullptr,
                                               std::shared_ptr<const HeadTilt> tilt = nullptr);

// For the needle in contact (the brain-tip scene with contact.mode = "frictional"): moves the
// mesh's cavity onto the rounded needle of the specs at t = 0 (model/cavity_rounding.hpp), a
// user's mesh (specs.mesh.scene_mesh_file) once its cavity has been checked against the sharp
// needle (CaseError naming the largest offset); a CaseError naming needle.edge_radius_um when the
// rounding moves the cavity by more than four edge radii (a point sharper than the radius can
// round). Returns what moved and the needle, to be the needle in contact too: a CAD tip's
// triangulation and core are then built once.
struct RoundedCavity {
  std::shared_ptr<const Needle> needle;
  CavityRounding rounding;
};
RoundedCavity round_cavity_to_needle(const NeedleSpecs& specs, TetMesh& mesh);

struct NeedleLoad {
  Point3 force{};   // on the needle, N
  Point3 moment{};  // on the needle about the centre of its rear face, N m
  double contact_area = 0.0;  // reference area of the cavity where g <= 0, m²
  double axial_force() const { return force[2]; }
  double torque() const { return moment[2]; }
};

struct GapRange {
  double min = 0.0, max = 0.0;  // m
};

class NeedleContact {
 public:
  // `needle` (needle_from_spec: the case's [needle] and [motion]) pressed into the cavity of `mesh`
  // (which must outlive this) with the [contact] law (contact_parameters_from_spec), its gaps
  // measured from those at t = 0.
  NeedleContact(ContactParameters parameters, const TetMesh& mesh, std::shared_ptr<const Needle> needle);

  std::shared_ptr<mechanics::SurfaceLoad> surface_load() const { return contact_; }
  const Needle& needle() const { return *needle_; }
  // The compliant tip's two bodies; null for a rigid needle.
  const HingedNeedle* hinged_needle() const { return dynamic_cast<const HingedNeedle*>(needle_.get()); }
  const PenaltyContact& contact() const { return *contact_; }

  // y, ydot: displacement parts of the state (dof numbering of `dofs`).
  NeedleLoad load_on_needle(double t, const double* y, const double* ydot, const mechanics::DofMap& dofs) const;
  // The compliant tip: the load on its head alone, the moment about the pivot (hinged_needle.hpp).
  NeedleLoad load_on_head(double t, const double* y, const double* ydot, const mechanics::DofMap& dofs) const;

  struct SurfaceFields {
    std::vector<double> pressure;  // Pa, per mesh node, 0 off the cavity
    std::vector<double> slip;      // m, per mesh node, 0 off the cavity
  };
  SurfaceFields surface_fields(double t, const double* y, const mechanics::DofMap& dofs) const;

  // The force the tissue exerts on the needle at each cavity node, r_a = -∫ N_a t dA₀ (the
  // contact's residual there), rotated into the needle's body frame (its pose at t = 0); zero at
  // every other mesh node. The loads of the deformable-needle check (needle_elasticity.hpp).
  std::vector<Point3> nodal_loads_in_needle_frame(double t, const double* y, const double* ydot,
                                                   const mechanics::DofMap& dofs) const;

  // Gap of the undeformed cavity against the needle at t = 0 at the cavity nodes (which the
  // mesher puts on the shape) and at the face centroids (off it by the faces' interpolation
  // error): zero up to the mesh's geometric accuracy, since both come from one shape.
  struct InitialGap {
    GapRange nodes, centroids;
  };
  InitialGap initial_gap() const;

 private:
  const TetMesh& mesh_;
  std::shared_ptr<const Needle> needle_;
  std::shared_ptr<PenaltyContact> contact_;
  std::vector<int> cavity_nodes_;
  std::vector<double> node_penalty_;  // ε̄_a per cavity node (same order)
  double smoothing_pressure_ = 0.0;   // s μ₀: δ_a = s μ₀ / ε̄_a
};

}  // namespace needlefem::contact
