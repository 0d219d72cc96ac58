// Static large-rotation FEM of paper 000's compliant needle tip in air: the tip (shaft, neck,
// head; prbm_check/tip_mesh.hpp) clamped on its rear face z = 0, loaded by the magnet's pull as a
// uniform body force of total F on the head, normal to the head axis, and the head's turning
// angle measured, for comparison with the pseudo-rigid-body model (steering/hinge.hpp, Eq. 2.7).
//
// Kinematics and material: total-Lagrangian TET10 elements (physics/elements/tet_element.hpp,
// displacement formulation) with the co-rotational linear law (physics/material/corotational.hpp)
//   P = R [2 mu (U - I) + lambda tr(U - I) I],  F = R U,
// exact under rigid rotations of any size and Hooke's law in the co-rotated frame: the right
// model for a steel needle whose strains stay below 1e-2 while its head turns by tens of degrees.
//
// Equilibrium: r_int(u) = f_ext(u) on the free dofs, with f_ext,a = F w_a d, w_a = ∫_head N_a dV / V_head.
// Load direction d:
//   dead      d = e_x, fixed in space (the pull of a magnet whose field does not turn with the head);
//   follower  d = R_head e_x, turning with the head (paper 000's assumption behind Eq. 2.7: "the
//             magnetic force is kept at the same angle phi with the needle head", here phi = 0).
// Newton (PETSc SNES, full steps, MUMPS LU; options prefix nf_tip_, e.g. -nf_tip_snes_monitor) on
// r_int(u) - f_ext(u) with the tangent of r_int only: for the follower load the missing
// load stiffness only tilts the pull by the angle's change within one iteration, which changes the
// moment about the neck to second order, so convergence stays fast. Loads are reached by
// continuation from the last solution, halving the increment when Newton fails.
//
// Head turning angle: the rotation of the head's volume-averaged deformation gradient,
// R_head = polar factor of (1/V_head) ∫_head F dV (exact for a rigid head, and volume-weighted, so
// it does not depend on where the mesh puts its nodes: a node-based best fit leans towards the
// refined shoulder, whose local deformation it would count as head rotation),
// theta = atan2(R_head,13, R_head,33), the rotation about y that carries the axis e_z towards +x.
// The small-displacement (linear) FEM angle is dtheta/dF at u = 0 times F.
#pragma once

#include <memory>
#include <vector>

#include "geometry/needle_tip.hpp"
#include "model/tet_mesh.hpp"

namespace needlefem::prbm {

enum class LoadKind { dead, follower };

struct TipSolution {
  double head_rotation_rad = 0.0;
  int newton_iterations = 0;  // in this call, over all increments
  int increments = 0;         // load increments this call took (1 unless Newton needed halving)
};

class CompliantTipStatics {
 public:
  // PETSc must be initialised (integration/petsc_session.hpp). Throws std::runtime_error for an
  // inverted or degenerate element, std::invalid_argument for bad material constants.
  CompliantTipStatics(const CompliantTip& tip, TetMesh mesh, double youngs_modulus_pa, double poisson_ratio);
  ~CompliantTipStatics();
  CompliantTipStatics(const CompliantTipStatics&) = delete;
  CompliantTipStatics& operator=(const CompliantTipStatics&) = delete;

  // Equilibrium under head load force_n of the given kind, by continuation from the current state
  // (call reset() to start from rest). Throws std::runtime_error when Newton fails even after the
  // increment was halved 8 times.
  TipSolution solve(double force_n, LoadKind kind);
  void reset();

  // Small-displacement FEM: head turning angle per newton of load at rest (rad/N).
  double linear_rotation_per_newton();
  // Axial distance from the neck's centre (z = s + l/2) to the resultant of the head load: the
  // lever of the load in the FEM, to compare with the PRBM's (L + l)/2.
  double load_lever_m() const { return load_lever_m_; }
  std::size_t dofs() const;
  std::size_t elements() const;
  // Largest |U - I| (co-rotated strain) over all quadrature points at the current state: the
  // co-rotational law is Hooke's law in that strain, valid while it stays small.
  double max_corotated_strain() const;
  double seconds_in_linear_solves() const { return linear_seconds_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double load_lever_m_ = 0.0;
  double linear_seconds_ = 0.0;
};

}  // namespace needlefem::prbm
