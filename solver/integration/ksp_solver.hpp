// Linear solves with the Newton matrix J = dF/dy + cj dF/dy' of a DaeSystem, over PETSc KSP.
//
// Methods (KspMethod; integration.linear_solver's choices of the same names), each a starting
// point that the user can override on the command line after `--` with the options prefix
// (default "nf_"), e.g. `-nf_ksp_type fgmres -nf_pc_type hypre`, `-nf_ksp_view`, `-nf_ksp_monitor`:
//   mumps      ("mumps")      : direct LU with MUMPS (KSPPREONLY + PCLU); robust for the
//                               indefinite displacement-pressure systems, the default.
//   gmres_gamg ("gmres-gamg") : GMRES preconditioned with PETSc's smoothed-aggregation AMG (give
//                               the matrix a near-null space of rigid-body modes for elasticity).
//   gmres_asm  ("gmres-asm")  : GMRES with additive Schwarz, ILU(0) on each rank's block.
//
// factor() hands the matrix to KSP and sets the preconditioner up right away, so that a
// failed factorisation shows up in the Jacobian setup (where IDA can cut the step) rather
// than in a later solve. When the matrix keeps its nonzero pattern (its PETSc "nonzero
// state" is unchanged), PETSc reuses the symbolic factorisation / AMG hierarchy structure and
// redoes only the numeric part.
#pragma once

#include <string>

#include <petscksp.h>

namespace needlefem {

enum class KspMethod { mumps, gmres_gamg, gmres_asm };

struct KspOptions {
  KspMethod method = KspMethod::mumps;
  // Krylov methods (also one chosen with -<prefix>ksp_type): ||b - A x|| <= rtol ||b||.
  double relative_tolerance = 1e-10;
  int max_iterations = 1000;
  std::string prefix = "nf_";
};

class KspSolver {
 public:
  explicit KspSolver(MPI_Comm comm, const KspOptions& options = {});
  ~KspSolver();
  KspSolver(const KspSolver&) = delete;
  KspSolver& operator=(const KspSolver&) = delete;

  // Use A as the operator and factor it (or build the preconditioner). Returns false if that
  // failed numerically (zero pivot, ...); last_failure() says why. Throws on PETSc errors.
  bool factor(Mat A);
  // Solve A x = b with the operator of the last factor(). Returns false if the solver did
  // not converge or the preconditioner had failed; last_failure() says why.
  bool solve(Vec b, Vec x);

  // True if the configured KSP iterates (anything but KSPPREONLY), after command-line options.
  bool is_iterative() const;
  long iterations() const { return iterations_; }  // Krylov iterations over all solves
  long factorizations() const { return factorizations_; }
  long solves() const { return solves_; }
  const std::string& last_failure() const { return last_failure_; }
  KSP ksp() const { return ksp_; }

 private:
  KSP ksp_ = nullptr;
  long iterations_ = 0;
  long factorizations_ = 0;
  long solves_ = 0;
  std::string last_failure_;
};

}  // namespace needlefem
