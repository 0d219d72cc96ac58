// The deformable-needle check of the brain-tip scene (needle.deflection_check): how far the steel
// tip would deflect under the contact loads of the rigid-needle run, to show with numbers whether
// the rigid needle is enough.
//
// Model: the "needle" region of the scene mesh (meshed conforming on the cavity, so every cavity
// node is also a needle node), linear elastic (small strain; the co-rotational law of
// physics/material/corotational.hpp at u = 0, i.e. Hooke's law with E and ν), TET10 displacement
// elements (physics/elements/tet_element.hpp), clamped on its rear face "needle_rear" (where the
// tip joins the rest of the shaft, which is stiffer than anything in front of it):
//   K u = f,   u = 0 on needle_rear,   K factored once (MUMPS).
// Loads: at an output time t the contact residual of the tissue at cavity node a,
// r_a = -∫ N_a t dA₀ (penalty_contact.hpp), is the force the tissue exerts on the needle there;
// it acts on the needle node at the same place, rotated back into the needle's body frame
// (f_a = R_z(-ω τ(t)) r_a, the mesh being the needle's pose at t = 0). The load point is the
// tissue node's reference position: a tissue point that slid along the needle is off by its slip
// (micrometres to tens of micrometres here), which moves loads within an element.
// One-way coupling: the deflection is not fed back into the contact. If it is far below the
// contact's own resolution (the penalty interpenetration, ~p h/(c μ₀), and the elastic slip s₀),
// feeding it back could not change the tissue's answer: the needle is rigid for this scene.
#pragma once

#include <memory>
#include <vector>

#include "model/tet_mesh.hpp"
#include "physics/contact/rigid_obstacle.hpp"

namespace needlefem::contact {

class NeedleElasticity {
 public:
  // Throws std::runtime_error without a "needle" region of 10-node tets or a "needle_rear"
  // surface, std::invalid_argument for E <= 0 or ν outside (-1, 0.5). PETSc must be initialised.
  NeedleElasticity(const TetMesh& mesh, double youngs_modulus_pa, double poisson_ratio);
  ~NeedleElasticity();
  NeedleElasticity(const NeedleElasticity&) = delete;
  NeedleElasticity& operator=(const NeedleElasticity&) = delete;

  struct Deflection {
    double max_m = 0.0;  // largest |u| over the needle's nodes
    Point3 where{};      // reference position of that node, m
    double elastic_energy_j = 0.0;  // ½ fᵀu
  };
  // Deflection under forces per mesh node (body frame, N; nodes outside the needle must carry 0).
  Deflection deflection(const std::vector<Point3>& nodal_forces) const;

  std::size_t dofs() const;
  std::size_t elements() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace needlefem::contact
