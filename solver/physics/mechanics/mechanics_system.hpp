// Quasi-static tissue mechanics with Prony viscoelasticity as a DAE F(t, y, y') = 0 for IDA.
//
// State y = (u, p): nodal displacements u (tissue dofs, dof_map.hpp), then, for the mixed
// (mean-dilatation) TET10, one pressure p_e per tissue element (pressure_offset()).
//
//   F_u = f_int(u, p; history, t - t_n) - f_ext    (algebraic; f_ext = 0 in these scenes)
//       + Σ r_s(t, u, u')                          (registered surface loads, surface_load.hpp)
//   F_u = u - ū(t)                                 on prescribed dofs (dirichlet.hpp)
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
// The Prony internal variables Q_i are not unknowns: every quadrature point keeps its history
// (Q_i and S⁰_iso at the last accepted step t_n, material::prony_history_size), a residual at t
// takes the stress at the end of Simo's recursive step of length t - t_n from it
// (material::PronyStep: S_iso = a S⁰_iso(C) - H), and each accepted step advances the histories
// (step_accepted). So the state is a tenth of what it is with the Q_i in it (docs/speed.md,
// "Prony variables out of IDA's state").
//
// Newton matrix J = ∂F/∂y + c_j ∂F/∂y' in blocks (per quadrature point q, weight w_q, B_q and
// D⁰_q as in physics/elements/tet_element.hpp):
//   J_uu = K with D⁰ scaled by a(t - t_n),   J_up = a_e,   J_pu = -(U''/V_e) a_eᵀ,   J_pp = 1.
// The Newton-matrix setup condenses p element by element (Schur complement):
//   K̂ = J_uu - Σ J_up J_pp⁻¹ J_pu = J_uu with the volumetric part
//       p_e ∂²v_e/∂u² + (U''/V_e) a_e a_eᵀ (tet_element.hpp, with the state's p_e),
// assembles K̂ into a PETSc AIJ matrix of block size 3 (prescribed rows replaced by identity
// rows); the integration stage factors it (CondensedDaeSystem, condensed_dae_system.hpp: how,
// by integration.linear_solver and its fallbacks, newton_matrix_factor.hpp). A solve condenses
// the right-hand side onto u, and expands the solution of K̂ back:
//   K̂ x_u = b_u - Σ_e a_e b_p,e     (free rows only),   x_p,e = b_p,e + (U''/V_e) a_eᵀ x_u.
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
  PetscInt local_size() const override { return displacement_dofs() + pressure_dofs(); }
  // Rest at t0: u = ū(t0) on prescribed dofs and 0 elsewhere, p = 0, y' = 0, every history zero
  // at t0 (consistent when ū(t0) = 0, as in both scenes at t0 = 0).
  void initial_state(double t0, Vec y, Vec ydot) override;
  void differential_mask(Vec id) override;  // u, p algebraic
  // IDA's absolute tolerances per unknown: metres for displacements, pascals for the element
  // pressures p. One scalar for both would be wrong by the ratio of their scales (~1e7 for brain
  // tissue: p ~ kPa against u ~ 0.1 mm).
  void absolute_tolerances(Vec atol, double displacement_m, double pressure_pa) const;
  DaeStatus residual(double t, Vec y, Vec ydot, Vec F) override;
  // With no rate-dependent surface load, the Newton matrix changes with the step only through
  // the Prony step's elastic fraction a(Δt) (material::PronyStep). Asked for IDA's first step,
  // an order-1 step of Δt = 1/c_j: it serves if a changes by less than 1e-3.
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
  PetscInt pressure_dofs() const { return pressure_unknowns() ? static_cast<PetscInt>(assembly_.elements()) : 0; }
  PetscInt pressure_offset() const { return displacement_dofs(); }
  // Prony history values kept for all quadrature points (not unknowns; see above).
  std::size_t viscous_history_size() const { return viscous_history_.size(); }
  // The viscous step of a tissue element at the last accepted step itself (Δt = 0: S_iso =
  // S⁰_iso - Σ Q_i of the stored histories), for output fields of the accepted state; nullptr
  // for a law without Prony terms.
  const elements::ViscousStep* accepted_viscous_state(std::size_t tissue_element, elements::ViscousStep& view) const;
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
  // Internal force f_int (all displacement dofs) at the end of `step` from the stored histories
  // and, when f_p is given, the pressure rows F_p. Returns false for an inverted element.
  bool assemble_internal(const double* y, const material::PronyStep& step, double* f_u, double* f_p,
                         double* energy) const;
  // The Prony step from the last accepted step t_n to t.
  material::PronyStep prony_step_to(double t) const;
  // The viscous step of a tissue element, or nullptr for a law without Prony terms.
  const elements::ViscousStep* viscous_step(std::size_t tissue_element, const material::PronyStep& step,
                                            elements::ViscousStep& view) const;
  // --- CondensedDaeSystem: K̂ and the condensation onto u ------------------------------------
  std::vector<char> condensed_prescribed() const override { return prescribed_; }
  DaeStatus assemble_condensed(double t, Vec y, Vec ydot, double cj, NewtonMatrix form, Mat& matrix) override;
  void condense(Vec b, double cj, Vec condensed_rhs) override;
  void expand(Vec b, Vec condensed_solution, double cj, Vec x) override;
  // Advances every point's history to the accepted state (Simo's recursion), then the surface
  // loads'.
  void step_accepted(double t, Vec y, Vec ydot) override;
  // K̂ at the state y at time t into the matrix's values, before surface loads and prescribed
  // rows; keeps the condensation's data for condense and expand. Returns false for an inverted
  // element.
  bool assemble_condensed_matrix(const double* y, double t);
  // The mixed element keeps its pressures in the state.
  bool pressure_unknowns() const { return kernel_.formulation() == elements::Formulation::mean_dilatation; }

  const TetMesh& mesh_;
  DofMap dofs_;
  DirichletConditions conditions_;
  elements::TetElementKernel kernel_;
  // Tissue elements (in dofs_.tissue_tets order) over blocks = nodes' first dof / 3: geometry,
  // the Newton matrix's fixed pattern and the threaded element loops.
  TetAssembly assembly_;
  // Prony histories of all points (element-major, then point; material::prony_history_size
  // values each) at the last accepted step t_n.
  std::size_t history_per_element_ = 0;
  std::vector<double> viscous_history_;
  double history_time_ = 0.0;
  material::PronyStep accepted_step_;  // of length 0: the stress of the stored histories
  // Mixed element: a_e and U''/V_e of each element at the last setup, for condense and expand.
  std::vector<std::array<double, elements::kMaxElementDofs>> pressure_gradient_;
  std::vector<double> pressure_stiffness_;
  std::vector<char> prescribed_;  // per displacement dof
  std::vector<std::shared_ptr<SurfaceLoad>> surface_loads_;
  Rejections rejections_;
};

}  // namespace needlefem::mechanics
