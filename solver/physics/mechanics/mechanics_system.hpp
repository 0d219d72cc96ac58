// Quasi-static tissue mechanics with Prony viscoelasticity as a DAE F(t, y, y') = 0 for IDA.
//
// State y = (u, Q, p): nodal displacements u (tissue dofs, dof_map.hpp), then the Prony
// internal variables Q_i at every quadrature point of every tissue element (element-major, then
// point, then term, 6 Voigt components 11 22 33 23 13 12; viscous_offset()), then, for the
// mixed (mean-dilatation) TET10, one pressure p_e per tissue element (pressure_offset()).
//
//   F_u = f_int(u, Q, p) - f_ext                   (algebraic; f_ext = 0 in these scenes)
//       + Σ r_s(t, u, u')                          (registered surface loads, surface_load.hpp)
//   F_u = u - ū(t)                                 on prescribed dofs (dirichlet.hpp)
//   F_Q = Q_i' - dQ_i/dt                           (differential; dQ_i/dt = (g_i S⁰_iso(C) - Q_i)/τ_i from
//                                                   the material's PronyTerm::rate, viscoelastic.hpp)
//   F_p = p_e - U'(θ_e),  θ_e = v_e / V_e          (algebraic, mixed element only)
// with f_int's volumetric part p_e a_e, a_e = ∂v_e/∂u (tet_element.hpp): the two-field u-p
// form of the mean-dilatation element (Simo, Taylor & Pister 1985), whose solution is the one of
// p = U'(θ) condensed inside the element, but whose Newton matrix stays a good preconditioner
// for longer. Why: with p condensed, a Newton matrix from an earlier step is wrong by about
// K ε against the shear stiffness μ (ε a step's strain increment; K/μ = 10⁴ for brain), so
// every step of the brain-tip runs needed a fresh factorisation; with p an unknown, a stale
// a_e perturbs the u-p system by ε only, so a factorisation serves many steps (the effect on
// the brain-tip benchmarks: docs/speed.md, "Element pressures as unknowns").
//
// Newton matrix J = ∂F/∂y + c_j ∂F/∂y' in blocks (per quadrature point q, term i, weight w_q,
// B_q and D⁰_q as in physics/elements/tet_element.hpp):
//   J_uu = K (tangent at fixed Q),   J_uQ = -w_q B_qᵀ,
//   J_Qu = -(g_i/τ_i) D⁰_q B_q,      J_QQ = (c_j + 1/τ_i) I   (diagonal: Q_i is local),
//   J_up = a_e,   J_pu = -(U''/V_e) a_eᵀ,   J_pp = 1            (per element).
// The Newton-matrix setup condenses Q and p element by element (Schur complement):
//   K̂ = J_uu - Σ J_uQ J_QQ⁻¹ J_Qu - Σ J_up J_pp⁻¹ J_pu
//     = K with D⁰ scaled by 1 - Σ_i g_i/(1 + c_j τ_i) and the volumetric part
//       p_e ∂²v_e/∂u² + (U''/V_e) a_e a_eᵀ (tet_element.hpp, with the state's p_e),
// assembles K̂ into a PETSc AIJ matrix of block size 3 (prescribed rows replaced by identity
// rows); the integration stage factors it (CondensedDaeSystem, condensed_dae_system.hpp: how,
// by integration.linear_solver and its fallbacks, newton_matrix_factor.hpp). A solve condenses
// the right-hand side onto u, and expands the solution of K̂ back:
//   K̂ x_u = b_u + Σ_q w_q B_qᵀ Σ_i b_Qi / (c_j + 1/τ_i) - Σ_e a_e b_p,e     (free rows only),
//   x_Qi = (b_Qi + (g_i/τ_i) D⁰_q B_q x_u) / (c_j + 1/τ_i),
//   x_p,e = b_p,e + (U''/V_e) a_eᵀ x_u.
// A non-positive det F anywhere gives DaeStatus::recoverable (IDA cuts the step). One rank:
// PETSc objects live on PETSC_COMM_SELF; the element loops of residuals, Newton matrices and
// the condensation run on the OpenMP threads (OMP_NUM_THREADS).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "case/specs/mechanics_spec.hpp"
#include "integration/condensed_dae_system.hpp"
#include "model/tet_mesh.hpp"
#include "physics/elements/tet_element.hpp"
#include "physics/material/material.hpp"
#include "physics/mechanics/dirichlet.hpp"
#include "physics/mechanics/dof_map.hpp"
#include "physics/mechanics/surface_load.hpp"
#include "physics/mechanics/tet_assembly.hpp"

namespace needlefem::mechanics {

class MechanicsSystem final : public CondensedDaeSystem {
 public:
  // `mesh` must outlive the system. PETSc must be initialised. Throws std::runtime_error on
  // PETSc failures and for inverted reference elements.
  MechanicsSystem(const TetMesh& mesh, const material::Material& material, elements::Formulation formulation,
                  DirichletConditions conditions);
  ~MechanicsSystem() override;
  MechanicsSystem(const MechanicsSystem&) = delete;
  MechanicsSystem& operator=(const MechanicsSystem&) = delete;

  // The case's material, element formulation and conditions of its scene (parse_mechanics_spec).
  static std::unique_ptr<MechanicsSystem> from_spec(const MechanicsSpec& spec, const TetMesh& mesh);

  // --- DaeSystem -------------------------------------------------------------------------
  PetscInt local_size() const override { return displacement_dofs() + viscous_dofs() + pressure_dofs(); }
  // Rest at t0: u = ū(t0) on prescribed dofs and 0 elsewhere, Q = 0, p = 0, y' = 0 (consistent when
  // ū(t0) = 0, as in both scenes at t0 = 0).
  void initial_state(double t0, Vec y, Vec ydot) override;
  void differential_mask(Vec id) override;  // Q differential; u, p algebraic
  // IDA's absolute tolerances per unknown: metres for displacements, pascals for the viscous
  // stresses Q and the element pressures p. One scalar for all would be wrong by the ratio of
  // their scales (~1e7 for brain tissue: Q ~ kPa against u ~ 0.1 mm), and an atol of 1e-8 "Pa"
  // forces steps far smaller than the loading needs while Q is still near zero.
  void absolute_tolerances(Vec atol, double displacement_m, double viscous_stress_pa, double pressure_pa) const;
  DaeStatus residual(double t, Vec y, Vec ydot, Vec F) override;
  // With no rate-dependent surface load, c_j enters the Newton matrix only through the condensed
  // Prony terms, 1 - Σ g_i/(1 + c_j τ_i) (material::condensed_fraction): it serves if that factor changes by
  // less than 1e-3.
  bool newton_matrix_serves(double factored_cj, double cj) const override;
  // Why callbacks asked IDA for a smaller step (DaeStatus::recoverable), counted; the failed
  // factorisations and solves: CondensedDaeSystem::factor_failures().
  struct Rejections {
    long inverted_residuals = 0;  // an element with det F <= 0 in a residual evaluation
    long inverted_jacobians = 0;  // ... in a Newton-matrix setup
  };
  const Rejections& rejections() const { return rejections_; }

  // Adds a surface's terms (contact, tractions; surface_load.hpp) to residual and Jacobian.
  void add_surface_load(std::shared_ptr<SurfaceLoad> load) { surface_loads_.push_back(std::move(load)); }

  // --- layout and results ------------------------------------------------------------------
  PetscInt displacement_dofs() const { return dofs_.dof_count; }
  PetscInt viscous_dofs() const { return viscous_per_element_ * static_cast<PetscInt>(dofs_.tissue_tets.size()); }
  PetscInt viscous_offset(std::size_t tissue_element) const {
    return displacement_dofs() + viscous_per_element_ * static_cast<PetscInt>(tissue_element);
  }
  PetscInt pressure_dofs() const { return pressure_unknowns() ? static_cast<PetscInt>(assembly_.elements()) : 0; }
  PetscInt pressure_offset() const { return displacement_dofs() + viscous_dofs(); }
  // Element k's pressure in the state y, or nullptr where the element has none (p = U'(θ)).
  const double* element_pressure(const double* y, std::size_t tissue_element) const {
    return pressure_unknowns() ? y + pressure_offset() + static_cast<PetscInt>(tissue_element) : nullptr;
  }
  const DofMap& dof_map() const { return dofs_; }
  const DirichletConditions& conditions() const { return conditions_; }
  const elements::TetElementKernel& kernel() const { return kernel_; }
  const elements::ElementGeometry& geometry(std::size_t tissue_element) const {
    return assembly_.geometry(tissue_element);
  }
  // A tissue element's nodal values (3 per node) out of an array laid out like the state's
  // displacements (y, y', or a field of the same layout).
  void gather(std::size_t tissue_element, const double* values, double* element_values) const {
    assembly_.gather(tissue_element, values, element_values);
  }

  // Force (N) the supports exert on the nodes of a named surface: the sum of the internal
  // nodal forces there (equilibrium holds at free nodes, so these are the reactions).
  Point3 reaction_force(Vec y, const std::string& surface) const;
  // Instantaneous elastic energy of the tissue (J), viscous stresses not counted.
  double elastic_energy(Vec y) const;
  // Both of the above from one assembly of the internal forces: the reaction on each of
  // `surfaces`, in order, and the elastic energy.
  struct Resultants {
    std::vector<Point3> reactions;
    double elastic_energy = 0.0;
  };
  Resultants resultants(Vec y, const std::vector<std::string>& surfaces) const;

 private:
  // Internal force f_int (all displacement dofs) and, when rates are given, the viscous rows
  // F_Q. Returns false for an inverted element.
  bool assemble_internal(const double* y, const double* ydot, double* f_u, double* f_q, double* energy) const;
  // --- CondensedDaeSystem: K̂ and the condensation onto u ------------------------------------
  std::vector<char> condensed_prescribed() const override { return prescribed_; }
  DaeStatus assemble_condensed(double t, Vec y, Vec ydot, double cj, NewtonMatrix form, Mat& matrix) override;
  void condense(Vec b, double cj, Vec condensed_rhs) override;
  void expand(Vec b, Vec condensed_solution, double cj, Vec x) override;
  void step_accepted(double t, Vec y, Vec ydot) override;
  // Per Prony term i at c_j: J_QQ⁻¹ = 1 / (c_j - ∂rate/∂Q) and ∂rate/∂S⁰ (PronyTerm).
  struct ViscousSolveFactors {
    std::vector<double> relaxation, rate_gain;
  };
  ViscousSolveFactors viscous_solve_factors(double cj) const;
  // Elements with unknowns condensed out of K̂ (all with Prony terms or pressures, else none).
  std::size_t condensed_elements() const;
  // K̂ at the state y and c_j into the matrix's values, before surface loads and prescribed rows;
  // keeps the condensation's data for condense and expand. Returns false for an inverted element.
  bool assemble_condensed_matrix(const double* y, double cj);
  // The mixed element keeps its pressures in the state.
  bool pressure_unknowns() const { return kernel_.formulation() == elements::Formulation::mean_dilatation; }

  const TetMesh& mesh_;
  DofMap dofs_;
  DirichletConditions conditions_;
  elements::TetElementKernel kernel_;
  // Tissue elements (in dofs_.tissue_tets order) over blocks = nodes' first dof / 3: geometry,
  // the Newton matrix's fixed pattern and the threaded element loops.
  TetAssembly assembly_;
  PetscInt viscous_per_element_ = 0;
  // Mixed element: a_e and U''/V_e of each element at the last setup, for condense and expand.
  std::vector<std::array<double, elements::kMaxElementDofs>> pressure_gradient_;
  std::vector<double> pressure_stiffness_;
  std::vector<char> prescribed_;  // per displacement dof
  std::vector<std::shared_ptr<SurfaceLoad>> surface_loads_;
  Rejections rejections_;

  // The condensation of the last assembly, for condense and expand (viscous only).
  std::vector<elements::CondensationElement> condensation_;
};

}  // namespace needlefem::mechanics
