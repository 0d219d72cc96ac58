// Time integration of a DaeSystem F(t, y, y') = 0 with SUNDIALS IDA (variable-order,
// variable-step BDF, orders 1-5) on PETSc vectors (NVECTOR_PETSC).
//
// Method (Brenan, Campbell & Petzold 1996; Hindmarsh et al. 2005, ACM TOMS 31:363): at each
// step IDA predicts y from its history, solves the BDF-discretised F(t_n, y_n, y'_n) = 0 with
// a modified Newton iteration whose matrix J = dF/dy + cj dF/dy' (cj = alpha_s / h_n) it
// refreshes only when needed (step-size ratio change, convergence trouble), and accepts the
// step if the weighted RMS norm of the local error estimate, with weights
// 1 / (rtol |y_i| + atol_i), is at most 1. So the same factorisation serves many Newton
// iterations and steps; the counters report how many were made.
//
// Failures reported by the system: DaeStatus::recoverable makes IDA retry with a smaller step
// (residual, Jacobian or solve); DaeStatus::fatal stops, and advance_to() throws a
// std::runtime_error naming the time reached and IDA's reason.
#pragma once

#include <functional>

#include <memory>
#include <optional>

#include <petscvec.h>

#include "case/specs/integration_spec.hpp"
#include "integration/dae_system.hpp"

namespace needlefem {

struct IdaOptions {
  double relative_tolerance = 1e-4;
  // Scalar absolute tolerance; set_absolute_tolerances() gives one per component instead.
  double absolute_tolerance = 1e-8;
  int max_order = 5;               // 1..5
  double initial_step = 0.0;       // s; 0 lets IDA choose
  double max_step = 0.0;           // s; 0 means unbounded
  int max_newton_iterations = 4;   // per step attempt (IDA's default)
  // How IDA's Newton iteration solves with J = dF/dy + cj dF/dy' (NewtonMethod, the choice of
  // integration.newton, case/specs/integration_spec.hpp):
  //   modified  the system's factored J (DaeSystem::setup_jacobian), kept over many iterations
  //             and steps until IDA judges it stale (cj changed, slow convergence).
  //   krylov    GMRES on products with the current J (IDA's difference quotients of F),
  //             left-preconditioned by that same factored J. The Newton iteration then stays
  //             (inexactly) a full Newton while the factorisation ages, so far fewer
  //             factorisations are needed when each is expensive; each GMRES iteration costs a
  //             residual evaluation and a triangular solve.
  NewtonMethod newton = NewtonMethod::modified;
  // Newton stops when its estimated error is below this fraction of the local error test's
  // tolerance (IDA's epcon, default 0.33). Near-incompressible tissue amplifies a displacement
  // error δu into a pressure error ~ K δu / h, so the Newton-Krylov iteration, which stops as
  // soon as the test passes, needs a tighter value than IDA's default (measured on a uniaxial
  // block, K/μ ~ 1e4: 0.33 gives a stress error of 6e-3, 0.01 below 1e-4). The penalty contact's
  // kinks stall Newton at such tight values, hence IDA's default stays the default.
  double newton_convergence_coefficient = 0.33;
  int krylov_dimension = 20;       // GMRES basis size (krylov)
  // GMRES (krylov) stops when its residual is below this fraction of the Newton test's
  // tolerance (IDA's epslin, default 0.05). The preconditioner is a factorisation kept over many
  // steps, so each GMRES iteration (one residual evaluation and one triangular solve) buys less
  // than a further Newton iteration, and a looser tolerance gives the same maxima for fewer
  // GMRES iterations (docs/speed.md, "Experiments"). IDA's Newton test sees only the updates, though, so a loose
  // solve can stop Newton on a wrong iterate where the matrix is nearly singular (K/mu = 1e5:
  // a 4x wrong reaction with 0.25); hence 0.25 only in the study's case files (schema.cpp).
  double krylov_tolerance = 0.05;
  // GMRES iterations allowed, per linear solve, with a Newton matrix factored in an earlier
  // step (the whole krylov_dimension with one factored in the current step). At the limit IDA's
  // Newton sees a failed linear solve and retries with a fresh matrix (a step cut only when the
  // matrix was fresh). While the needle moves, a matrix from the previous step can leave GMRES
  // stagnating at the full basis, where a fresh matrix would have converged at once (same
  // maxima; docs/speed.md, "Experiments"). 0: no limit (runs take
  // integration.krylov_stale_iterations, schema.cpp).
  int krylov_stale_iterations = 0;
  // A Newton matrix from an earlier step ages out (ida_integrator.cpp, StaleMatrixPolicy): the
  // next step refactors it once a step it served needed more than this many times the GMRES
  // iterations per Newton iteration of the step that factored it. 0: only when GMRES fails.
  double krylov_aged_matrix_ratio = 2.0;
  // IDA refreshes the Newton matrix when cj = alpha/h has changed by more than this fraction
  // since the last setup (IDA's default 0.25). The tissue's matrix depends on cj only through
  // rate-dependent surface loads (friction's slip velocity), and on the step only through the
  // Prony step's elastic fraction (mechanics_system.hpp), so a larger value saves
  // factorisations when steps grow.
  double newton_matrix_cj_change = 0.25;
  long max_steps_per_advance = 100000;
  // Leave algebraic components (mask 0) out of the local error test.
  bool suppress_algebraic_error = false;
  // Stability studies: take steps of exactly this size with the error test switched off.
  // Implemented as initial step = max step = fixed_step, and both error tolerances multiplied
  // by S = kFixedStepErrorTolerance / relative_tolerance, so that the error test passes unless
  // the local error exceeds 1e6 |y| (IDA then never shrinks the step, and never grows it past
  // max step), while IDA's Newton convergence coefficient is divided by S, so Newton still
  // converges to the requested rtol/atol. A Newton failure or a recoverable system failure may
  // still cut a step; the counters show it. Output times that are not multiples of the step
  // shorten the step that lands on them. Requires newton = modified (the constructor throws
  // otherwise).
  std::optional<double> fixed_step;
};

inline constexpr double kFixedStepErrorTolerance = 1e6;

struct IdaCounters {
  long steps = 0;
  long residual_evaluations = 0;
  long newton_iterations = 0;
  long jacobian_setups = 0;      // Newton-matrix (or preconditioner) setups = factorisations
  long linear_solver_setups = 0;
  long error_test_failures = 0;
  long newton_convergence_failures = 0;
  long linear_iterations = 0;    // Krylov iterations (IDA's GMRES, or the system's KSP); 0 for a direct solve
  // Krylov Newton: steps whose Newton matrix from an earlier step failed GMRES, and steps that
  // refused it without a try (ida_integrator.cpp, StaleMatrixPolicy); each refusal is also one
  // of newton_convergence_failures.
  long stale_matrix_failures = 0;
  long stale_matrix_refusals = 0;
  long stale_matrix_aged = 0;    // steps whose stale matrix aged (refused by the next step)
  double last_step = 0.0;        // s
  int last_order = 0;
};

class IdaIntegrator {
 public:
  // Calls system.initial_state(t0, ...) and prepares IDA; `comm` must be the communicator of
  // the system's vectors. The integrator owns one SUNContext (made with `comm`) for its life.
  IdaIntegrator(DaeSystem& system, const IdaOptions& options, double t0, MPI_Comm comm = PETSC_COMM_WORLD);
  ~IdaIntegrator();
  IdaIntegrator(const IdaIntegrator&) = delete;
  IdaIntegrator& operator=(const IdaIntegrator&) = delete;

  // One absolute tolerance per component (same layout as y), e.g. metres for displacements
  // and pascals for pressures. Replaces options.absolute_tolerance.
  void set_absolute_tolerances(Vec absolute_tolerances);

  // Make the initial state consistent (F(t0, y, y') = 0) with IDACalcIC: keeps the
  // differential components of y, solves for the algebraic components of y and for the
  // derivatives y' of the differential ones. `t_first_output` (> t0) only sets the scale of
  // the trial step. Call before the first advance_to(), when the system's initial_state() is
  // not already consistent.
  void make_initial_state_consistent(double t_first_output);

  // Replace the initial rates y'(t0) by those of a probe backward-Euler step of size `probe`
  // (tiny against the time scales of the loading): solves F(t0 + probe, y0 + probe y', y') = 0
  // for y' by modified Newton (matrix J at cj = 1/probe, factored once), keeping y(t0) = y0.
  // As probe -> 0 this is the consistent y'(t0) also of components whose equations contain no
  // y' (displacements driven by a moving boundary or obstacle), which IDACalcIC leaves alone.
  // Why: with y'(t0) = 0 while the load already moves, IDA's first predictor misses by
  // h v, its error test forces h ~ atol / v and the step then needs doublings to reach the
  // loading's time scale (docs/speed.md, "Measurements formerly in code comments"). Convergence: the largest weighted component of the update times
  // probe_horizon below 1e-3. The largest, not IDA's RMS norm: one contact point whose state
  // changes inside the probe step is invisible in an RMS over millions of unknowns, and its rate
  // is then wrong (measured: 1.1e5 1/s at t = 0 at one point of the cavity, r = 0.32 mm tip on
  // the level-2 mesh of mesh.seed 4, the probe converged by RMS in 7 iterations).
  // If the probe does not converge in `max_iterations` (an initial state far from equilibrium,
  // e.g. initial contact penetration, or such a point), y'(t0) is left as the system gave it, IDA
  // starts from there (correct, only slower), and the result says so.
  // Call after the tolerances are set and before the first advance_to().
  struct InitialRates {
    bool converged = false;
    int iterations = 0;
    double last_update = 0.0;  // largest weighted component of the last update over the horizon
  };
  InitialRates make_initial_rates_consistent(double probe, double probe_horizon, int max_iterations = 10);

  // Integrate to exactly t_out (> time()): t_out is a stop time no step crosses, and on
  // return time() == t_out and state()/state_rate() hold y and y' there.
  // after_step, if given, is called with the time reached after each accepted step (progress).
  void advance_to(double t_out, const std::function<void(double)>& after_step = {});

  double time() const;
  Vec state() const;
  Vec state_rate() const;
  IdaCounters counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace needlefem
