// How a Newton matrix J = dF/dy + c_j dF/dy' is factored and solved with: the one place that
// chooses the factorisation, falls back to another where it fails, and holds the policies that
// decide when to try which. The physics assembles J (a SeqAIJ matrix whose prescribed rows are
// identity rows); CondensedDaeSystem (condensed_dae_system.hpp) calls factor() with it at each
// of IDA's setups, then solve() as often as the integrator asks.
//
// integration.linear_solver (NewtonMatrixOptions::method, the LinearSolver the case names)
// selects ("cholmod", the first one's former name, still reads as "cholesky": case/schema.cpp)
//   "cholesky"  : sparse Cholesky of J's symmetric part on the free unknowns (SparseCholesky,
//                 sparse_cholesky.hpp), MUMPS LU (KspSolver) for a setup where that fails:
//                 - integration.newton = "modified" (the solves must be exact): CHOLMOD's
//                   double-precision factor;
//                 - integration.newton = "krylov" (the solves only precondition GMRES): the
//                   single-precision factor on CHOLMOD's symbolic analysis
//                   (single_precision_factor.hpp), by LU with static pivoting where friction
//                   makes J unsymmetric, unless integration.krylov_preconditioner = "symmetric"
//                   (then Cholesky of the symmetric part all the same).
//   "mumps", "gmres-gamg", "gmres-asm": KspSolver's methods of the same names (KspMethod,
//                 ksp_solver.hpp), every setup.
//
// Policies (method "cholesky" only):
// - A symmetric part found indefinite (sliding friction) usually stays so for the next setups:
//   the next kCholeskySkipsAfterIndefinite setups go straight to MUMPS LU rather than pay a
//   failed Cholesky attempt each.
// - From the third setup without an accepted step in between (IDA's Newton failing with fresh
//   matrices, at stick/slip events with steps cut to 1e-10 s), a single-precision factor gives
//   way to MUMPS's double-precision LU until a step is accepted (step_accepted()): at such steps
//   c_j = 1/h puts entries of 1e10 beside the tissue's, beyond what single precision resolves.
//   The default case never triggers it; the study design that needed it: docs/speed.md,
//   "Measurements formerly in code comments".
// - Memory: at the first setup of a pattern, a single-precision factor that would take the LU
//   path weighs the bytes that the LU adds to the Cholesky factor against the memory left
//   (machine_memory.hpp: this process's resident set, kMemoryShare of the machine's or the control
//   group's memory). Where the LU does not fit, every setup factors the symmetric part by
//   Cholesky instead (wants_symmetric_matrix(): the physics then assembles the matrix kept
//   positive definite on purpose, as for integration.krylov_preconditioner = "symmetric"), and a
//   symmetric part found indefinite is factored again with its diagonal raised by
//   kDiagonalShifts in turn, never by MUMPS (whose double-precision LU is larger still). GMRES on
//   the exact Jacobian's action makes up the difference: the answer is the same to the Newton
//   tolerance, the iterations more. Why: level 2 of the r = 0.83 mm, 10° designs (8.4 M unknowns)
//   needs 17 GB with the Cholesky factor and more than 24 GB with the LU (docs/accuracy.md §11).
// When an earlier step's factor may still serve is the integrator's decision (StaleMatrixPolicy,
// ida_integrator.cpp): it sees GMRES's iterations, which this component does not.
//
// A PETSc KSP can use the component as its preconditioner (attach_to: a PCSHELL whose setup
// calls factor() with the KSP's preconditioning matrix and whose apply calls solve()).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <petscmat.h>
#include <petscpc.h>

#include "case/specs/integration_spec.hpp"

namespace needlefem {

class KspSolver;
class SparseCholesky;

struct NewtonMatrixOptions {
  LinearSolver method = LinearSolver::mumps;  // integration.linear_solver
  double relative_tolerance = 1e-10;          // Krylov methods: ||b - J x|| <= rtol ||b||
  // PETSc options prefix of the KSP for command-line overrides (-nf_ksp_type ..., -nf_pc_type ...).
  std::string prefix = "nf_";
  // The solves only precondition an outer iteration (integration.newton = "krylov": IDA's GMRES
  // on the exact Jacobian's action), so "cholesky" may factor and solve in single precision.
  bool preconditioner_only = false;
  // ... and from a symmetric positive definite approximation of the Newton matrix
  // (integration.krylov_preconditioner = "symmetric"; NewtonMatrix in
  // physics/mechanics/surface_load.hpp): the single-precision factor is then Cholesky even where
  // the matrix is unsymmetric.
  bool symmetric_preconditioner = false;
  // The memory the factor may plan to fill, in bytes; 0: the machine's (usable_memory_bytes()).
  std::size_t memory_bytes = 0;
};

class NewtonMatrixFactor {
 public:
  // prescribed[i] != 0 marks unknown i as given (its row of J is an identity row). PETSc must be
  // initialised.
  NewtonMatrixFactor(std::vector<char> prescribed, const NewtonMatrixOptions& options);
  ~NewtonMatrixFactor();
  NewtonMatrixFactor(const NewtonMatrixFactor&) = delete;
  NewtonMatrixFactor& operator=(const NewtonMatrixFactor&) = delete;

  // Factor J by the method and the policies above. Returns false if nothing could factor it
  // (the caller lets IDA cut the step). J must stay unchanged until the last solve() with it.
  bool factor(Mat J);
  // x = J⁻¹ b with the last successful factor() (the symmetric part's inverse where that is
  // what was factored: sparse_cholesky.hpp). Returns false if the solve failed (a Krylov method
  // that did not converge).
  bool solve(Vec b, Vec x);
  // The integrator accepted a step: a single-precision factor that gave way is tried again.
  void step_accepted() { setups_since_accepted_step_ = 0; }
  // The matrix to assemble for the next setup is the symmetric positive definite approximation
  // (NewtonMatrixOptions::symmetric_preconditioner, or the LU found not to fit in memory).
  bool wants_symmetric_matrix() const { return symmetric_preconditioner_ || lu_beyond_memory_; }
  // Makes `pc` a PCSHELL around this component: its setup factors the preconditioning matrix,
  // its apply solves; where either fails, the PC's failed reason says so (a KSP then stops with
  // KSP_DIVERGED_PC_FAILED). This object must outlive the PC's use of it.
  void attach_to(PC pc);

  long iterations() const;  // Krylov iterations over all solves (0 for direct methods)
  // How the Newton matrices were factored: by sparse Cholesky, by the single-precision LU on
  // its structure (unsymmetric matrices where the factor preconditions GMRES), and by the KSP
  // (all of them for "mumps" and the Krylov methods; with "cholesky", the setups that these
  // could not factor or were not tried on).
  // shifted: Cholesky factorisations of a symmetric part with a raised diagonal (counted in
  // cholesky too); lu_beyond_memory: the LU did not fit (the policy above); factor_mb: the
  // single-precision factor's values (L, and Uᵀ after an LU).
  struct Factorisations {
    long cholesky = 0;
    long lu = 0;
    long ksp = 0;
    long shifted = 0;
    bool lu_beyond_memory = false;
    double factor_mb = 0.0;
  };
  Factorisations factorisations() const;

 private:
  // The memory policy's choice, at a new pattern; the factorisation within it.
  void weigh_lu_against_memory();
  bool factor_within_memory(Mat J);

  std::unique_ptr<SparseCholesky> cholesky_;  // method "cholesky" only
  std::unique_ptr<KspSolver> ksp_;            // the method, or MUMPS LU where Cholesky fails
  bool cholesky_factored_ = false;            // which of the two holds the last factorisation
  static constexpr int kCholeskySkipsAfterIndefinite = 3;
  int cholesky_skips_left_ = 0;  // setups that go straight to LU after an indefinite one
  static constexpr int kSinglePrecisionSetupsWithoutStep = 2;
  int setups_since_accepted_step_ = 0;
  // The share of the usable memory a run may plan to fill at its first factorisation. The rest
  // is for what comes after it (GMRES's basis, allocated at the first solve: 20 state-sized
  // vectors), the page cache that the result file's writes go through and other processes. With
  // 0.9 the r 0.83/10°/0.25 level 2 (8.45 M unknowns) took the LU and reached 22.5 of 25.3 GB.
  static constexpr double kMemoryShare = 0.75;
  // Relative raises of an indefinite symmetric part's diagonal, tried in turn.
  static constexpr double kDiagonalShifts[] = {1e-3, 1e-2, 1e-1, 1.0};
  std::size_t memory_bytes_;
  bool symmetric_preconditioner_;
  bool lu_beyond_memory_ = false;
  long shifted_ = 0;
};

}  // namespace needlefem
