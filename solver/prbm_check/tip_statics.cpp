// Static large-rotation FEM of the compliant tip; the formulation is in tip_statics.hpp.
#include "prbm_check/tip_statics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <fmt/core.h>
#include <petscmat.h>
#include <petscsnes.h>
#include <petscvec.h>

#include "integration/ksp_solver.hpp"
#include "integration/petsc_arrays.hpp"
#include "integration/petsc_session.hpp"
#include "model/tet_geometry.hpp"
#include "physics/elements/tet_element.hpp"
#include "physics/material/material.hpp"
#include "physics/mechanics/tet_assembly.hpp"
#include "wall_clock/seconds_since.hpp"

namespace needlefem::prbm {

namespace {

constexpr int kNodes = 10;
constexpr int kElementDofs = 3 * kNodes;
constexpr int kMaxNewtonIterations = 25;
constexpr int kMaxHalvings = 8;
// Converged when ||r_int - f_ext|| <= kResidualTolerance ||f_ext|| on the free dofs, or when the
// Newton correction is below kCorrectionTolerance max|u|: the residual of the co-rotational law has a
// round-off floor (its polar decompositions stop at 1e-15 relative, times E = 200 GPa) that small
// loads reach before the relative residual test.
constexpr double kResidualTolerance = 1e-7;
constexpr double kCorrectionTolerance = 1e-10;

}  // namespace

struct CompliantTipStatics::Impl {
  TetMesh mesh;
  elements::TetElementKernel kernel;
  mechanics::TetAssembly assembly;  // geometry, matrix pattern, element loop and clamp (rear face)
  std::vector<double> load_weight;  // w_a per node, Σ w_a = 1
  std::vector<std::size_t> head_elements;
  double head_volume = 0.0;
  double force_n = 0.0;  // load of the current state
  double tip_length_m = 0.0;
  // u: the current displacement (3 per node), which SNES iterates on; saved: u before a load
  // increment, restored when Newton fails on it.
  Vec rhs = nullptr, step = nullptr, u = nullptr, saved = nullptr;
  KspSolver solver{PETSC_COMM_SELF};  // MUMPS LU (the options prefix nf_), also SNES's
  SNES snes = nullptr;                // Newton with full steps and the tests above (newton())
  // The load SNES's residual is evaluated at, and the time spent assembling in its current solve.
  double snes_force = 0.0;
  LoadKind snes_kind = LoadKind::dead;
  double snes_assembly_seconds = 0.0;

  Impl(TetMesh m, const material::Material& material, std::vector<PetscInt> clamped_dofs)
      : mesh(std::move(m)),
        kernel(material, elements::Formulation::displacement),
        assembly(mesh.nodes_per_tet, mesh.tet_nodes, mesh.nodes, std::move(clamped_dofs)),
        rhs(assembly.create_vector()),
        step(assembly.create_vector()),
        u(assembly.create_vector()),
        saved(assembly.create_vector()) {
    petsc_check(SNESCreate(PETSC_COMM_SELF, &snes), "SNESCreate");
    petsc_check(SNESSetType(snes, SNESNEWTONLS), "SNESSetType");
    SNESLineSearch line_search = nullptr;
    petsc_check(SNESGetLineSearch(snes, &line_search), "SNESGetLineSearch");
    petsc_check(SNESLineSearchSetType(line_search, SNESLINESEARCHBASIC), "SNESLineSearchSetType");
    petsc_check(SNESSetKSP(snes, solver.ksp()), "SNESSetKSP");
    petsc_check(SNESSetFunction(snes, rhs, snes_residual, this), "SNESSetFunction");
    petsc_check(SNESSetJacobian(snes, assembly.matrix(), assembly.matrix(), snes_jacobian, this), "SNESSetJacobian");
    petsc_check(SNESSetConvergenceTest(snes, snes_converged, this, nullptr), "SNESSetConvergenceTest");
    petsc_check(SNESSetTolerances(snes, 0.0, 0.0, 0.0, kMaxNewtonIterations, -1), "SNESSetTolerances");
    petsc_check(SNESSetOptionsPrefix(snes, "nf_tip_"), "SNESSetOptionsPrefix");
    petsc_check(SNESSetFromOptions(snes), "SNESSetFromOptions");
  }
  ~Impl() {
    SNESDestroy(&snes);
    VecDestroy(&rhs);
    VecDestroy(&step);
    VecDestroy(&u);
    VecDestroy(&saved);
  }

  std::size_t dofs() const { return 3 * mesh.nodes.size(); }

  // Rotation of the head: polar factor of its volume-averaged deformation gradient (tip_statics.hpp).
  material::Mat3d head_rotation(const double* displacement) const {
    material::Mat3d mean_f{};
    std::vector<double> element_u(kElementDofs);
    for (std::size_t e : head_elements) {
      assembly.gather(e, displacement, element_u.data());
      const auto& g = assembly.geometry(e);
      for (int q = 0; q < g.points; ++q) {
        const double* G = g.gradient_at(q);
        for (int i = 0; i < 3; ++i)
          for (int J = 0; J < 3; ++J) {
            double f = i == J ? 1.0 : 0.0;
            for (int a = 0; a < kNodes; ++a) f += element_u[3 * a + i] * G[3 * a + J];
            mean_f(i, J) += g.weight[q] * f;
          }
      }
    }
    return material::rotation_of((1.0 / head_volume) * mean_f);
  }

  static double bending_angle(const material::Mat3d& R) { return std::atan2(R(0, 2), R(2, 2)); }

  // Residual r_int - f_ext at `displacement` (free dofs; clamped entries zero) into `out`, and the
  // tangent of r_int (clamped rows and columns replaced by the identity) into matrix when
  // with_tangent. Returns false if an element is inverted.
  bool assemble(Vec displacement, double force, LoadKind kind, bool with_tangent, Vec out) {
    const ReadArray x(displacement);
    const material::Mat3d R = head_rotation(x.data());
    const std::array<double, 3> direction =
        kind == LoadKind::follower ? std::array<double, 3>{R(0, 0), R(1, 0), R(2, 0)} : std::array<double, 3>{1, 0, 0};
    WriteArray residual(out);
    for (std::size_t node = 0; node < mesh.nodes.size(); ++node)
      for (int i = 0; i < 3; ++i) residual.data()[3 * node + i] = -force * load_weight[node] * direction[i];
    return assembly.add_elements(kernel, x.data(), residual.data(), with_tangent);
  }

  // Norm of f_ext for the convergence test: F sqrt(Σ w_a²) (direction is a unit vector).
  double load_norm(double force) const {
    double sum = 0.0;
    for (double w : load_weight) sum += w * w;
    return std::abs(force) * std::sqrt(sum);
  }

  // SNES's residual at x, and the tangent assembled with it (SNES asks for it at the same point
  // next; snes_jacobian has nothing left to do). An inverted element is a domain error, which
  // fails the solve.
  static PetscErrorCode snes_residual(SNES snes, Vec x, Vec f, void* context) {
    Impl& m = *static_cast<Impl*>(context);
    const auto start = WallClock::now();
    const bool valid = m.assemble(x, m.snes_force, m.snes_kind, true, f);
    m.snes_assembly_seconds += seconds_since(start);
    if (!valid) PetscCall(SNESSetFunctionDomainError(snes));
    return 0;
  }
  static PetscErrorCode snes_jacobian(SNES, Vec, Mat, Mat, void*) { return 0; }

  // The tests above: the residual against the load, then the last correction against the largest
  // displacement; at most kMaxNewtonIterations corrections.
  static PetscErrorCode snes_converged(SNES snes, PetscInt iteration, PetscReal, PetscReal, PetscReal residual_norm,
                                       SNESConvergedReason* reason, void* context) {
    const Impl& m = *static_cast<const Impl*>(context);
    *reason = SNES_CONVERGED_ITERATING;
    if (!std::isfinite(residual_norm)) {
      *reason = SNES_DIVERGED_FNORM_NAN;
    } else if (residual_norm <= kResidualTolerance * m.load_norm(m.snes_force)) {
      *reason = SNES_CONVERGED_FNORM_ABS;
    } else if (iteration > 0) {
      Vec x = nullptr, correction = nullptr;
      PetscCall(SNESGetSolution(snes, &x));
      PetscCall(SNESGetSolutionUpdate(snes, &correction));
      PetscReal largest_correction = 0.0, largest_u = 0.0;
      PetscCall(VecNorm(correction, NORM_INFINITY, &largest_correction));
      PetscCall(VecNorm(x, NORM_INFINITY, &largest_u));
      if (largest_correction <= kCorrectionTolerance * largest_u) *reason = SNES_CONVERGED_SNORM_RELATIVE;
    }
    if (*reason == SNES_CONVERGED_ITERATING && iteration >= kMaxNewtonIterations) *reason = SNES_DIVERGED_MAX_IT;
    return 0;
  }

  // Newton (PETSc SNES) from the current u at load `force`. Returns the corrections it took, or -1
  // on failure (u undefined). `linear_seconds` gains the solve's time outside the assembly.
  int newton(double force, LoadKind kind, double& linear_seconds) {
    const auto start = WallClock::now();
    snes_force = force;
    snes_kind = kind;
    snes_assembly_seconds = 0.0;
    petsc_check(SNESSolve(snes, nullptr, u), "SNESSolve");
    linear_seconds += seconds_since(start) - snes_assembly_seconds;
    SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
    PetscInt iterations = 0;
    petsc_check(SNESGetConvergedReason(snes, &reason), "SNESGetConvergedReason");
    petsc_check(SNESGetIterationNumber(snes, &iterations), "SNESGetIterationNumber");
    return reason < 0 ? -1 : static_cast<int>(iterations);
  }
};

CompliantTipStatics::CompliantTipStatics(const CompliantTip& tip, TetMesh mesh, double youngs_modulus_pa,
                                         double poisson_ratio) {
  if (!(youngs_modulus_pa > 0.0) || !(poisson_ratio > -1.0 && poisson_ratio < 0.5))
    throw std::invalid_argument(
        fmt::format("compliant tip FEM: need E > 0 and -1 < nu < 0.5, got E = {} Pa, nu = {}", youngs_modulus_pa,
                    poisson_ratio));
  if (mesh.nodes_per_tet != kNodes) throw std::invalid_argument("compliant tip FEM: needs 10-node tetrahedra");
  // Clamp: every node on the rear face z = 0.
  std::vector<PetscInt> clamped_dofs;
  for (std::size_t a = 0; a < mesh.nodes.size(); ++a)
    if (std::abs(mesh.nodes[a][2]) <= 1e-9 * tip.length())
      for (int i = 0; i < 3; ++i) clamped_dofs.push_back(static_cast<PetscInt>(3 * a + i));
  if (clamped_dofs.empty()) throw std::runtime_error("compliant tip FEM: no node on the rear face z = 0");
  const material::Material steel("needle", material::CorotationalLinear{youngs_modulus_pa, poisson_ratio});
  impl_ = std::make_unique<Impl>(std::move(mesh), steel, std::move(clamped_dofs));
  Impl& m = *impl_;
  m.tip_length_m = tip.length();
  const int head = m.mesh.region_index("head");
  const std::size_t nodes = m.mesh.nodes.size();

  // Head-load weights w_a = ∫_head N_a dV / V_head and the load's resultant.
  m.load_weight.assign(nodes, 0.0);
  std::vector<double> shape(kNodes);
  const auto& quadrature = elements::element_quadrature(kNodes);
  for (std::size_t e = 0; e < m.mesh.tet_count(); ++e) {
    if (m.mesh.tet_region[e] != head) continue;
    const int* element = m.mesh.tet(e);
    const auto& g = m.assembly.geometry(e);
    for (int q = 0; q < g.points; ++q) {
      tet_shape_values(kNodes, quadrature[q].xi, shape.data());
      for (int a = 0; a < kNodes; ++a) m.load_weight[element[a]] += shape[a] * g.weight[q];
    }
    m.head_volume += g.volume;
    m.head_elements.push_back(e);
  }
  if (m.head_elements.empty()) throw std::runtime_error("compliant tip FEM: the mesh has no head elements");
  double load_z = 0.0;
  for (std::size_t a = 0; a < nodes; ++a) {
    m.load_weight[a] /= m.head_volume;
    load_z += m.load_weight[a] * m.mesh.nodes[a][2];
  }
  load_lever_m_ = load_z - (tip.shaft + 0.5 * tip.neck_length);
}

CompliantTipStatics::~CompliantTipStatics() = default;

std::size_t CompliantTipStatics::dofs() const { return impl_->dofs(); }
std::size_t CompliantTipStatics::elements() const { return impl_->mesh.tet_count(); }

void CompliantTipStatics::reset() {
  petsc_check(VecZeroEntries(impl_->u), "VecZeroEntries");
  impl_->force_n = 0.0;
}

TipSolution CompliantTipStatics::solve(double force_n, LoadKind kind) {
  Impl& m = *impl_;
  TipSolution solution;
  double increment = force_n - m.force_n;
  int halvings = 0;
  while (m.force_n != force_n) {
    const double target = std::abs(force_n - m.force_n) <= std::abs(increment) ? force_n : m.force_n + increment;
    petsc_check(VecCopy(m.u, m.saved), "VecCopy");
    const int iterations = m.newton(target, kind, linear_seconds_);
    if (iterations < 0) {
      petsc_check(VecCopy(m.saved, m.u), "VecCopy");
      if (++halvings > kMaxHalvings)
        throw std::runtime_error(fmt::format("compliant tip FEM: Newton fails at a load of {:.4g} N even in steps of {:.3g} N",
                                             target, increment));
      increment *= 0.5;
      continue;
    }
    solution.newton_iterations += iterations;
    ++solution.increments;
    m.force_n = target;
  }
  const ReadArray u(m.u);
  solution.head_rotation_rad = Impl::bending_angle(m.head_rotation(u.data()));
  return solution;
}

double CompliantTipStatics::linear_rotation_per_newton() {
  Impl& m = *impl_;
  // At rest r_int = 0, so the assembled residual is -f_ext for 1 N: one solve gives u_lin per newton.
  petsc_check(VecZeroEntries(m.step), "VecZeroEntries");
  if (!m.assemble(m.step, 1.0, LoadKind::dead, true, m.rhs) || !m.solver.factor(m.assembly.matrix()) ||
      !m.solver.solve(m.rhs, m.step))
    throw std::runtime_error("compliant tip FEM: the linear stiffness matrix could not be factored");
  std::vector<double> linear(m.dofs());
  {
    ReadArray delta(m.step);
    for (std::size_t k = 0; k < linear.size(); ++k) linear[k] = -delta.data()[k];
  }
  // dtheta/dF from the head rotation at eps u_lin, eps small enough that theta is linear in it
  // to round-off (the polar factor's departure from linearity is O(eps^2)).
  double largest = 0.0;
  for (double v : linear) largest = std::max(largest, std::abs(v));
  const double eps = 1e-7 * m.tip_length_m / std::max(largest, 1e-300);
  for (double& v : linear) v *= eps;
  return Impl::bending_angle(m.head_rotation(linear.data())) / eps;
}

double CompliantTipStatics::max_corotated_strain() const {
  const Impl& m = *impl_;
  const ReadArray u(m.u);
  std::vector<double> element_u(kElementDofs);
  double largest = 0.0;
  for (std::size_t e = 0; e < m.mesh.tet_count(); ++e) {
    m.assembly.gather(e, u.data(), element_u.data());
    const auto result = m.kernel.evaluate(m.assembly.geometry(e), element_u.data(), nullptr, false);
    for (const auto& point : result.points) {
      material::Mat3d F{};
      for (int k = 0; k < 9; ++k) F.a[k] = point.deformation_gradient[k];
      const material::Mat3d strain = material::transpose(material::rotation_of(F)) * F - material::Mat3d::identity();
      largest = std::max(largest, std::sqrt(material::double_dot(strain, strain)));
    }
  }
  return largest;
}

}  // namespace needlefem::prbm
