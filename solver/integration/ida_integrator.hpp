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

#include <memory>
#include <optional>

#include <petscvec.h>

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
  // shorten the step that lands on them.
  std::optional<double> fixed_step;
};

inline constexpr double kFixedStepErrorTolerance = 1e6;

struct IdaCounters {
  long steps = 0;
  long residual_evaluations = 0;
  long newton_iterations = 0;
  long jacobian_setups = 0;      // Jacobian evaluations = factorisations
  long linear_solver_setups = 0;
  long error_test_failures = 0;
  long newton_convergence_failures = 0;
  long linear_iterations = 0;    // Krylov iterations reported by the system; 0 for a direct solver
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

  // Integrate to exactly t_out (> time()): t_out is a stop time no step crosses, and on
  // return time() == t_out and state()/state_rate() hold y and y' there.
  void advance_to(double t_out);

  double time() const;
  Vec state() const;
  Vec state_rate() const;
  IdaCounters counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace needlefem
