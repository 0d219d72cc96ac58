// What the time integrator sees of the physics: a residual and a Jacobian, nothing more
// (in the spirit of deal.II's SUNDIALS::IDA wrapper). IDA solves F(t, y, y') = 0 with
// variable-order BDF; its Newton matrix is J = dF/dy + cj dF/dy'.
//
// Every callback returns Status::recoverable for a failure that a smaller step may cure
// (an inverted element, a diverging inner solve): IDA then cuts the step instead of
// aborting. No exception may cross these callbacks into SUNDIALS.
#pragma once

#include <petscvec.h>

namespace needlefem {

enum class DaeStatus { ok, recoverable, fatal };

// Runs a callback body so that no exception crosses into SUNDIALS: an exception becomes fatal.
template <class Body>
DaeStatus guarded(Body&& body) noexcept {
  try {
    return body();
  } catch (...) {
    return DaeStatus::fatal;
  }
}

class DaeSystem {
 public:
  virtual ~DaeSystem() = default;

  // Local length of y (all of it on one rank; the rank's share under MPI).
  virtual PetscInt local_size() const = 0;
  // Consistent initial values at t0.
  virtual void initial_state(double t0, Vec y, Vec ydot) = 0;
  // 1 for differential components (y' appears in F), 0 for algebraic ones.
  virtual void differential_mask(Vec id) = 0;

  virtual DaeStatus residual(double t, Vec y, Vec ydot, Vec F) = 0;
  // Assemble and factor J = dF/dy + cj dF/dy' at (t, y, y') for later solves.
  virtual DaeStatus setup_jacobian(double t, Vec y, Vec ydot, double cj) = 0;
  // Solve J x = b with the matrix of the last setup_jacobian().
  virtual DaeStatus solve_jacobian(Vec b, Vec x) = 0;
  // Called with each step the integrator accepts (state and rate there): systems with history
  // that is not part of y (e.g. friction anchors) update it. Residuals in between see the
  // history of the last accepted step, so a rejected step leaves no trace.
  virtual void accept_step(double /*t*/, Vec /*y*/, Vec /*ydot*/) {}
  // Iterations of the inner (Krylov) solver so far; 0 for a direct solver.
  virtual long linear_iterations() const { return 0; }
  // True if solve_jacobian() iterates (Krylov) rather than applying a factorisation: IDA then
  // treats the solver as matrix-iterative and reports its iterations.
  virtual bool iterative_linear_solver() const { return false; }
  // True if the Newton matrix factored at c_j = factored_cj serves as well at cj, the state
  // being nearly the same: the Krylov Newton then takes the probe step's factorisation over for
  // IDA's first step instead of factoring again (IdaIntegrator::make_initial_rates_consistent).
  // False, the default, is always safe.
  virtual bool newton_matrix_serves(double /*factored_cj*/, double /*cj*/) const { return false; }
};

}  // namespace needlefem
