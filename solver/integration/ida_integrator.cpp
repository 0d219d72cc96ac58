#include "integration/ida_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/core.h>
#include <ida/ida.h>
#include <nvector/nvector_petsc.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunnonlinsol/sunnonlinsol_newton.h>
#include <sundials/sundials_context.h>

#include "integration/dae_linear_solver.hpp"
#include "integration/petsc_session.hpp"
#include "integration/threaded_vector_ops.hpp"

namespace needlefem {

namespace {


Vec petsc_vector(N_Vector v) { return N_VGetVector_Petsc(v); }

// When GMRES may use a Newton matrix factored in an earlier step (a stale one).
// - Its iteration limit (IdaOptions::krylov_stale_iterations): the whole basis with a matrix
//   factored during the current step, fewer with a stale one, so that a stale preconditioner on
//   which GMRES stagnates gives way to a fresh one early. SPGMR reads its maxl field at every
//   solve; values up to the basis it was created with are valid.
// - Skipping it: once a stale matrix has failed GMRES in two steps in a row, the next steps
//   refuse it at their first solve (a recoverable failure, on which IDA's Newton refreshes the
//   matrix and retries the iteration), 1 step after the second failure in a row, 2 after the
//   third, then 3; a stale matrix that serves a step resets the count. Where every step needs a
//   fresh matrix (the tied brain tip after 0.01 s, whose deformation per step rotates the
//   volumetric stiffness K ~ 1e4 mu) each try cost a Newton iteration and `stale` GMRES
//   iterations for nothing; isolated failures (a contact event) still leave the matrix in use.
// - Aging: a step that served its Newton iterations from a stale matrix with more than
//   IdaOptions::krylov_aged_matrix_ratio times the GMRES iterations per Newton iteration of the
//   step that factored it (at least kFreshIterationsFloor) makes the next step refuse it, once.
//   Sliding friction ages a matrix slowly: without this rule one early matrix can serve a whole
//   Table I run while its steps need ever more GMRES iterations, which together cost more than
//   a few fresh factorisations (docs/measurements.md, "Speed").
class StaleMatrixPolicy {
 public:
  StaleMatrixPolicy() = default;
  StaleMatrixPolicy(SUNLinearSolverContent_SPGMR gmres, int fresh_limit, int stale_limit, double aged_ratio)
      : gmres_(gmres), fresh_limit_(fresh_limit), stale_limit_(stale_limit), aged_ratio_(aged_ratio) {}

  // IDA's Newton asks for a fresh matrix.
  void matrix_refreshed() {
    if (gmres_) gmres_->maxl = fresh_limit_;
    if (stale_ && stale_tried_) stale_failed_ = true;
    stale_ = false;
  }
  // IDA's first setup takes the matrix factored for the consistent initial rates instead
  // (IdaCallbacks::probe_matrix_cj), tried like a stale one.
  void matrix_taken_over() {
    become_stale();
    ++taken_over_;
  }
  // The step is over: the matrix becomes stale for the next one. The totals of GMRES and Newton
  // iterations so far measure its aging.
  void step_accepted(long linear_iterations, long newton_iterations) {
    if (gmres_) gmres_->maxl = stale_limit_;
    const double per_newton = static_cast<double>(linear_iterations - linear_before_) /
                              static_cast<double>(std::max(newton_iterations - newton_before_, 1L));
    linear_before_ = linear_iterations;
    newton_before_ = newton_iterations;
    if (!stale_) {
      fresh_per_newton_ = std::max(per_newton, kFreshIterationsFloor);
    } else if (aged_ratio_ > 0.0 && stale_tried_ && !stale_failed_ && per_newton > aged_ratio_ * fresh_per_newton_) {
      steps_to_skip_ = std::max(steps_to_skip_, 1);
      ++aged_;
    }
    if (stale_failed_) {
      ++failures_;
      if (++failures_in_a_row_ >= 2) steps_to_skip_ = std::min(failures_in_a_row_ - 1, kMostStepsSkipped);
    } else if (stale_tried_) {
      failures_in_a_row_ = 0;
    }
    become_stale();
  }
  // At each preconditioner solve: true refuses the stale matrix.
  bool refuse_matrix() {
    if (!gmres_ || !stale_) return false;
    if (steps_to_skip_ > 0) {
      --steps_to_skip_;
      ++refusals_;
      return true;
    }
    stale_tried_ = true;
    return false;
  }
  long failures() const { return failures_; }
  long refusals() const { return refusals_; }
  long taken_over() const { return taken_over_; }
  long aged() const { return aged_; }

 private:
  static constexpr int kMostStepsSkipped = 3;
  static constexpr double kFreshIterationsFloor = 3.0;
  void become_stale() {
    if (gmres_) gmres_->maxl = stale_limit_;
    stale_ = true;
    stale_tried_ = stale_failed_ = false;
  }
  SUNLinearSolverContent_SPGMR gmres_ = nullptr;  // null: not a Krylov Newton
  int fresh_limit_ = 0, stale_limit_ = 0;
  double aged_ratio_ = 0.0;
  bool stale_ = false;          // the factored matrix is from an earlier step
  bool stale_tried_ = false;    // GMRES ran on it in this step
  bool stale_failed_ = false;   // ... and Newton then refreshed it
  int failures_in_a_row_ = 0;  // steps in a row whose stale matrix failed
  int steps_to_skip_ = 0;
  long linear_before_ = 0, newton_before_ = 0;      // the totals at the last accepted step
  double fresh_per_newton_ = kFreshIterationsFloor;  // GMRES per Newton iteration of the factoring step
  long failures_ = 0, refusals_ = 0, taken_over_ = 0, aged_ = 0;
};

// Modified Newton's convergence test (integration.newton = "modified", adaptive steps). IDA's own (ida_nls.c):
// converged when ss |δ| <= tol in IDA's weighted norm, ss = rate/(1 - rate) from this solve's
// updates, recoverable divergence when the rate exceeds 0.9; except that before a solve's second
// update ss is 20, the value IDA itself takes after a matrix setup, not the rate the previous
// step left. IDA keeps that rate while c_j is unchanged, and with a matrix from an earlier step
// the first update of an equal step can miss by more than the tolerance and still pass on the
// previous step's fast rate: tied 0.4 mm benchmark (steps of 0.01 s at constant order), one
// iteration at t = 0.09 s put the max principal stress at 2377 instead of 2052 Pa and the
// cavity's reaction 3x off.
struct ModifiedNewtonTest {
  double first_norm = 0.0;
  double rate_factor = 0.0;  // ss
};

int modified_newton_test(SUNNonlinearSolver nls, N_Vector, N_Vector update, realtype tol, N_Vector weights,
                         void* data) {
  constexpr double kRateFactorBeforeARate = 20.0, kNegligibleFirstUpdate = 1e-4, kDivergingRate = 0.9;
  auto& test = *static_cast<ModifiedNewtonTest*>(data);
  int iteration = 0;
  if (SUNNonlinSolGetCurIter(nls, &iteration) != SUN_NLS_SUCCESS) return -1;
  const double norm = N_VWrmsNorm(update, weights);
  if (iteration == 0) {
    test.first_norm = norm;
    test.rate_factor = kRateFactorBeforeARate;
    if (norm <= kNegligibleFirstUpdate * tol) return SUN_NLS_SUCCESS;
  } else {
    const double rate = std::pow(norm / test.first_norm, 1.0 / iteration);
    if (rate > kDivergingRate) return SUN_NLS_CONV_RECVR;
    test.rate_factor = rate / (1.0 - rate);
  }
  return test.rate_factor * norm <= tol ? SUN_NLS_SUCCESS : SUN_NLS_CONTINUE;
}

// IDA's user data, handed to every callback.
struct IdaCallbacks {
  DaeCallbackContext dae;
  StaleMatrixPolicy stale_matrix;
  // Krylov Newton: c_j of the probe step's factored matrix (make_initial_rates_consistent), 0 if
  // none. IDA's first setup (forced at its first step, at t0 + h0 and c_j = 1/h0) takes it over
  // when the system says it serves at that c_j (DaeSystem::newton_matrix_serves): the state has
  // moved by h0 y' only, GMRES corrects the difference, and if it cannot, Newton refreshes the
  // matrix, which saves one factorisation. Not with friction's slip-velocity terms, whose c_j
  // part is h0/probe times stiffer in the probe's matrix (1000x here): with them some runs of the
  // default case stopped in their first steps with IDA_CONV_FAIL (docs/speed.md, "Experiments").
  double probe_matrix_cj = 0.0;
};

DaeCallbackContext& dae_context(void* user_data) { return static_cast<IdaCallbacks*>(user_data)->dae; }

// A work vector shaped like another, destroyed with its scope.
struct ScratchVec {
  explicit ScratchVec(Vec like) { petsc_check(VecDuplicate(like, &v), "VecDuplicate"); }
  ~ScratchVec() { VecDestroy(&v); }
  ScratchVec(const ScratchVec&) = delete;
  ScratchVec& operator=(const ScratchVec&) = delete;
  Vec v = nullptr;
};

int residual_callback(realtype t, N_Vector y, N_Vector ydot, N_Vector F, void* user_data) {
  auto& callbacks = dae_context(user_data);
  try {
    return to_sundials_code(callbacks.system.residual(t, petsc_vector(y), petsc_vector(ydot), petsc_vector(F)));
  } catch (const std::exception& e) {
    callbacks.last_exception = e.what();
    return -1;
  }
}

int jacobian_callback(realtype t, realtype cj, N_Vector y, N_Vector ydot, N_Vector, SUNMatrix, void* user_data,
                      N_Vector, N_Vector, N_Vector) {
  auto& callbacks = dae_context(user_data);
  try {
    return to_sundials_code(callbacks.system.setup_jacobian(t, petsc_vector(y), petsc_vector(ydot), cj));
  } catch (const std::exception& e) {
    callbacks.last_exception = e.what();
    return -1;
  }
}

// Newton-Krylov: the system's factored Newton matrix, refreshed only when IDA asks, is the
// preconditioner of GMRES on IDA's difference-quotient products with the current Jacobian.
int preconditioner_setup(realtype t, N_Vector y, N_Vector ydot, N_Vector, realtype cj, void* user_data) {
  auto& all = *static_cast<IdaCallbacks*>(user_data);
  const double probe_cj = std::exchange(all.probe_matrix_cj, 0.0);
  if (probe_cj > 0.0 && all.dae.system.newton_matrix_serves(probe_cj, cj)) {
    all.stale_matrix.matrix_taken_over();
    return 0;
  }
  all.stale_matrix.matrix_refreshed();
  return jacobian_callback(t, cj, y, ydot, nullptr, nullptr, user_data, nullptr, nullptr, nullptr);
}

int preconditioner_solve(realtype, N_Vector, N_Vector, N_Vector, N_Vector r, N_Vector z, realtype, realtype,
                         void* user_data) {
  auto& all = *static_cast<IdaCallbacks*>(user_data);
  if (all.stale_matrix.refuse_matrix()) return 1;  // recoverable: Newton refreshes the matrix
  auto& callbacks = all.dae;
  try {
    return to_sundials_code(callbacks.system.solve_jacobian(petsc_vector(r), petsc_vector(z)));
  } catch (const std::exception& e) {
    callbacks.last_exception = e.what();
    return -1;
  }
}

// Keeps IDA's last error text for the exception; warnings go to stderr as IDA would print them.
void error_handler(int code, const char* module, const char* function, char* message, void* user_data) {
  auto& last_error = *static_cast<std::string*>(user_data);
  if (code == IDA_WARNING) {
    fmt::print(stderr, "needlefem: {} warning in {}: {}\n", module, function, message);
    return;
  }
  last_error = fmt::format("{} in {}: {}", module, function, message);
}

void ida_check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(fmt::format("IDA: {} failed ({})", what, IDAGetReturnFlagName(flag)));
}

// Tolerances, order and step settings IDA can work with; throws std::invalid_argument otherwise.
void check_options(const IdaOptions& options) {
  if (!(options.relative_tolerance > 0.0) || !(options.absolute_tolerance >= 0.0))
    throw std::invalid_argument(fmt::format("IDA tolerances must be rtol > 0, atol >= 0, got {}, {}",
                                            options.relative_tolerance, options.absolute_tolerance));
  if (options.max_order < 1 || options.max_order > 5)
    throw std::invalid_argument(fmt::format("IDA max order must be 1..5, got {}", options.max_order));
  // Measured (docs/benchmarks/stability.json): with the tolerances scaled for fixed steps, IDA's
  // Krylov Newton accepted one iteration per step and gave step-independent wrong answers.
  if (options.fixed_step && options.newton == NewtonMethod::krylov)
    throw std::invalid_argument("fixed time steps need integration.newton = modified (the Krylov Newton's "
                                "stopping test is not meaningful with the error test switched off)");
  if (options.fixed_step && !(*options.fixed_step > 0.0))
    throw std::invalid_argument(fmt::format("fixed time step must be positive, got {}", *options.fixed_step));
}

}  // namespace

struct IdaIntegrator::Impl {
  Impl(DaeSystem& system, const IdaOptions& options, MPI_Comm comm) : options(options), comm(comm), callbacks{{system, {}}, {}} {}
  ~Impl() {
    IDAFree(&ida);
    SUNNonlinSolFree(newton);
    SUNLinSolFree(linear_solver);
    SUNMatDestroy(jacobian);
    N_VDestroy(y_nv);
    N_VDestroy(ydot_nv);
    VecDestroy(&y);
    VecDestroy(&ydot);
    VecDestroy(&absolute_tolerances);
    if (context) SUNContext_Free(&context);
  }

  // Appends IDA's own message and a caught exception's text, if any, to `reason`.
  std::string with_failure_details(const std::string& reason) const {
    std::string text = reason;
    if (!last_ida_error.empty()) text += " (" + last_ida_error + ")";
    if (!callbacks.dae.last_exception.empty()) text += "; " + callbacks.dae.last_exception;
    return text;
  }
  void clear_failure_details() {
    last_ida_error.clear();
    callbacks.dae.last_exception.clear();
  }

  double tolerance_scale() const {
    return options.fixed_step ? kFixedStepErrorTolerance / options.relative_tolerance : 1.0;
  }
  // IDA's linear solver (GMRES preconditioned by the system's Newton matrix, or the system's own
  // direct solve) and, for the modified Newton with adaptive steps, the nonlinear solver.
  void attach_linear_solver();

  IdaOptions options;
  MPI_Comm comm;
  IdaCallbacks callbacks;
  std::string last_ida_error;
  double time = 0.0;
  SUNContext context = nullptr;
  Vec y = nullptr, ydot = nullptr;
  N_Vector y_nv = nullptr, ydot_nv = nullptr;
  SUNMatrix jacobian = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  SUNNonlinearSolver newton = nullptr;  // modified Newton with adaptive steps only (IDA's own otherwise)
  ModifiedNewtonTest newton_test;
  void* ida = nullptr;
  Vec absolute_tolerances = nullptr;  // scaled as given to IDA; null: options.absolute_tolerance
};

void IdaIntegrator::Impl::attach_linear_solver() {
  if (options.newton == NewtonMethod::krylov) {
    linear_solver = SUNLinSol_SPGMR(y_nv, SUN_PREC_LEFT, options.krylov_dimension, context);
    if (!linear_solver) throw std::runtime_error("creating IDA's GMRES solver failed");
    ida_check(IDASetLinearSolver(ida, linear_solver, nullptr), "IDASetLinearSolver");
    ida_check(IDASetPreconditioner(ida, preconditioner_setup, preconditioner_solve), "IDASetPreconditioner");
    ida_check(IDASetEpsLin(ida, options.krylov_tolerance), "IDASetEpsLin");
    callbacks.stale_matrix = StaleMatrixPolicy(
        static_cast<SUNLinearSolverContent_SPGMR>(linear_solver->content), options.krylov_dimension,
        options.krylov_stale_iterations > 0 ? std::min(options.krylov_stale_iterations, options.krylov_dimension)
                                            : options.krylov_dimension,
        options.krylov_aged_matrix_ratio);
  } else {
    jacobian = make_jacobian_handle(context);
    linear_solver = make_dae_linear_solver(context, callbacks.dae);
    if (!jacobian || !linear_solver) throw std::runtime_error("creating the IDA linear solver failed");
    ida_check(IDASetLinearSolver(ida, linear_solver, jacobian), "IDASetLinearSolver");
    ida_check(IDASetJacFn(ida, jacobian_callback), "IDASetJacFn");
    // Fixed steps (stability studies) keep IDA's own test. With the rate factor reset per solve,
    // the stability map's frictional brain tip at fixed steps did not complete (Newton's rate
    // test failing at stick/slip changes, steps cut to a few µs that fixed-step mode does not
    // grow back), where IDA's test completes them (docs/measurements.md, "Stability").
    if (!options.fixed_step) {
      newton = SUNNonlinSol_Newton(y_nv, context);
      if (!newton) throw std::runtime_error("creating IDA's Newton solver failed");
      ida_check(IDASetNonlinearSolver(ida, newton), "IDASetNonlinearSolver");
      // After IDASetNonlinearSolver, which installs IDA's own test.
      if (SUNNonlinSolSetConvTestFn(newton, modified_newton_test, &newton_test) != SUN_NLS_SUCCESS)
        throw std::runtime_error("setting the modified Newton convergence test failed");
    }
  }
}

IdaIntegrator::IdaIntegrator(DaeSystem& system, const IdaOptions& options, double t0, MPI_Comm comm)
    : impl_(std::make_unique<Impl>(system, options, comm)) {
  check_options(options);
  Impl& m = *impl_;
  m.time = t0;
  if (SUNContext_Create(&m.comm, &m.context) != 0) throw std::runtime_error("SUNContext_Create failed");

  petsc_check(VecCreateMPI(comm, system.local_size(), PETSC_DETERMINE, &m.y), "VecCreateMPI");
  petsc_check(VecDuplicate(m.y, &m.ydot), "VecDuplicate");
  system.initial_state(t0, m.y, m.ydot);
  m.y_nv = N_VMake_Petsc(m.y, m.context);
  m.ydot_nv = N_VMake_Petsc(m.ydot, m.context);
  use_threaded_vector_operations(m.y_nv);  // and so IDA's and GMRES's clones
  use_threaded_vector_operations(m.ydot_nv);

  m.ida = IDACreate(m.context);
  if (!m.ida) throw std::runtime_error("IDACreate failed");
  ida_check(IDASetErrHandlerFn(m.ida, error_handler, &m.last_ida_error), "IDASetErrHandlerFn");
  ida_check(IDAInit(m.ida, residual_callback, t0, m.y_nv, m.ydot_nv), "IDAInit");
  ida_check(IDASetUserData(m.ida, &m.callbacks), "IDASetUserData");
  const double scale = m.tolerance_scale();
  ida_check(IDASStolerances(m.ida, options.relative_tolerance * scale, options.absolute_tolerance * scale),
            "IDASStolerances");

  {
    Vec mask = nullptr;
    petsc_check(VecDuplicate(m.y, &mask), "VecDuplicate");
    system.differential_mask(mask);
    N_Vector mask_nv = N_VMake_Petsc(mask, m.context);
    const int flag = IDASetId(m.ida, mask_nv);  // IDA keeps its own copy
    N_VDestroy(mask_nv);
    VecDestroy(&mask);
    ida_check(flag, "IDASetId");
  }

  m.attach_linear_solver();

  ida_check(IDASetMaxOrd(m.ida, options.max_order), "IDASetMaxOrd");
  ida_check(IDASetDeltaCjLSetup(m.ida, options.newton_matrix_cj_change), "IDASetDeltaCjLSetup");
  ida_check(IDASetMaxNonlinIters(m.ida, options.max_newton_iterations), "IDASetMaxNonlinIters");
  ida_check(IDASetSuppressAlg(m.ida, options.suppress_algebraic_error ? SUNTRUE : SUNFALSE), "IDASetSuppressAlg");
  double initial_step = options.initial_step, max_step = options.max_step;
  if (options.fixed_step) initial_step = max_step = *options.fixed_step;
  ida_check(IDASetNonlinConvCoef(m.ida, options.newton_convergence_coefficient / scale), "IDASetNonlinConvCoef");
  ida_check(IDASetInitStep(m.ida, initial_step), "IDASetInitStep");
  ida_check(IDASetMaxStep(m.ida, max_step), "IDASetMaxStep");
}

IdaIntegrator::~IdaIntegrator() = default;

void IdaIntegrator::set_absolute_tolerances(Vec absolute_tolerances) {
  Impl& m = *impl_;
  Vec scaled = nullptr;
  petsc_check(VecDuplicate(absolute_tolerances, &scaled), "VecDuplicate");
  petsc_check(VecCopy(absolute_tolerances, scaled), "VecCopy");
  petsc_check(VecScale(scaled, m.tolerance_scale()), "VecScale");
  N_Vector scaled_nv = N_VMake_Petsc(scaled, m.context);
  const int flag = IDASVtolerances(m.ida, m.options.relative_tolerance * m.tolerance_scale(), scaled_nv);
  N_VDestroy(scaled_nv);
  VecDestroy(&m.absolute_tolerances);
  m.absolute_tolerances = scaled;
  ida_check(flag, "IDASVtolerances");
}

IdaIntegrator::InitialRates IdaIntegrator::make_initial_rates_consistent(double probe, double probe_horizon,
                                                                        int max_iterations) {
  Impl& m = *impl_;
  if (!(probe > 0.0) || !(probe_horizon > 0.0))
    throw std::invalid_argument("make_initial_rates_consistent: probe step and horizon must be positive");
  DaeSystem& system = m.callbacks.dae.system;
  const double t_probe = m.time + probe;
  const ScratchVec given_rates(m.y), y_probe(m.y), residual(m.y), update(m.y), weights(m.y);
  petsc_check(VecCopy(m.ydot, given_rates.v), "VecCopy");
  // IDA's error weights at y0, W_i = 1 / (rtol |y_i| + atol_i).
  petsc_check(VecCopy(m.y, weights.v), "VecCopy");
  petsc_check(VecAbs(weights.v), "VecAbs");
  petsc_check(VecScale(weights.v, m.options.relative_tolerance * m.tolerance_scale()), "VecScale");
  if (m.absolute_tolerances)
    petsc_check(VecAXPY(weights.v, 1.0, m.absolute_tolerances), "VecAXPY");
  else
    petsc_check(VecShift(weights.v, m.options.absolute_tolerance * m.tolerance_scale()), "VecShift");
  petsc_check(VecReciprocal(weights.v), "VecReciprocal");

  InitialRates result;
  while (result.iterations < max_iterations) {
    ++result.iterations;
    petsc_check(VecWAXPY(y_probe.v, probe, m.ydot, m.y), "VecWAXPY");  // y0 + probe y'
    if (system.residual(t_probe, y_probe.v, m.ydot, residual.v) != DaeStatus::ok) break;
    if (result.iterations == 1 && system.setup_jacobian(t_probe, y_probe.v, m.ydot, 1.0 / probe) != DaeStatus::ok)
      break;
    // dF/dy' along the probe step is probe J(cj = 1/probe): the y' update is -J⁻¹F / probe.
    if (system.solve_jacobian(residual.v, update.v) != DaeStatus::ok) break;
    petsc_check(VecAXPY(m.ydot, -1.0 / probe, update.v), "VecAXPY");
    // Size of the update as the change it makes to y over the horizon, in IDA's norm.
    petsc_check(VecScale(update.v, probe_horizon / probe), "VecScale");
    petsc_check(VecPointwiseMult(update.v, update.v, weights.v), "VecPointwiseMult");
    double norm = 0.0;
    petsc_check(VecNorm(update.v, NORM_INFINITY, &norm), "VecNorm");
    result.last_update = norm;
    if (result.last_update < 1e-3) {
      result.converged = true;
      break;
    }
  }
  if (!result.converged) petsc_check(VecCopy(given_rates.v, m.ydot), "VecCopy");
  m.callbacks.probe_matrix_cj = result.converged && m.options.newton == NewtonMethod::krylov ? 1.0 / probe : 0.0;
  ida_check(IDAReInit(m.ida, m.time, m.y_nv, m.ydot_nv), "IDAReInit");
  return result;
}

void IdaIntegrator::make_initial_state_consistent(double t_first_output) {
  Impl& m = *impl_;
  m.clear_failure_details();
  const int flag = IDACalcIC(m.ida, IDA_YA_YDP_INIT, t_first_output);
  if (flag < 0) {
    const std::string reason = fmt::format("IDA could not make the initial state at t = {:.9g} s consistent: {}", m.time,
                                     IDAGetReturnFlagName(flag));
    throw std::runtime_error(m.with_failure_details(reason));
  }
  ida_check(IDAGetConsistentIC(m.ida, m.y_nv, m.ydot_nv), "IDAGetConsistentIC");
}

void IdaIntegrator::advance_to(double t_out, const std::function<void(double)>& after_step) {
  Impl& m = *impl_;
  if (t_out == m.time) return;
  if (!(t_out > m.time))
    throw std::invalid_argument(fmt::format("advance_to({} s): the integrator is already at t = {} s", t_out, m.time));
  m.clear_failure_details();
  realtype t_reached = m.time;
  int flag = IDA_SUCCESS;
  long steps = 0;
  // One step at a time (IDA_ONE_STEP) with t_out as a stop time no step crosses. When the
  // natural next step h would leave a sliver of t_out - t - h < h, the last two steps are made
  // equal instead (an intermediate stop halfway): a landing step much shorter than its
  // predecessors makes y' there — BDF divided differences over that step — carry the Newton
  // error of y divided by the sliver (measured: isolated strain-rate spikes of 10-200 1/s at
  // output times on the brain-tip scene). Fixed steps keep their size (the output shortens one).
  while (true) {
    double stop = t_out;
    realtype h_next = 0.0;
    ida_check(IDAGetCurrentStep(m.ida, &h_next), "IDAGetCurrentStep");
    const double remaining = t_out - t_reached;
    // IDA takes a stop time within 100 units of round-off of t + h as reached (its stop test), so
    // a remaining interval that exceeds the next step by no more is one step, not two halves
    // (docs/speed.md, "Experiments").
    const double round_off = 100.0 * std::numeric_limits<double>::epsilon() * (std::abs(t_reached) + h_next);
    if (!m.options.fixed_step && h_next > 0.0 && remaining - h_next > round_off && remaining < 2.0 * h_next)
      stop = t_reached + 0.5 * remaining;
    ida_check(IDASetStopTime(m.ida, stop), "IDASetStopTime");
    flag = IDASolve(m.ida, stop, &t_reached, m.y_nv, m.ydot_nv, IDA_ONE_STEP);
    if (flag < 0) break;
    m.callbacks.dae.system.accept_step(t_reached, m.y, m.ydot);
    if (m.options.newton == NewtonMethod::krylov) {
      long linear = 0, newton = 0;
      ida_check(IDAGetNumLinIters(m.ida, &linear), "IDAGetNumLinIters");
      ida_check(IDAGetNumNonlinSolvIters(m.ida, &newton), "IDAGetNumNonlinSolvIters");
      m.callbacks.stale_matrix.step_accepted(linear, newton);
    }
    if (after_step) after_step(t_reached);
    if (flag == IDA_TSTOP_RETURN && stop == t_out) break;
    if (++steps >= m.options.max_steps_per_advance) {
      flag = IDA_TOO_MUCH_WORK;  // IDASetMaxNumSteps counts per IDASolve call, one step here
      break;
    }
  }
  if (flag < 0) {
    realtype t_failed = t_reached;
    IDAGetCurrentTime(m.ida, &t_failed);
    const std::string reason = fmt::format("IDA stopped at t = {:.9g} s while advancing to t = {:.9g} s: {}", t_failed,
                                     t_out, IDAGetReturnFlagName(flag));
    throw std::runtime_error(m.with_failure_details(reason));
  }
  // IDA lands on the stop time up to round-off and interpolates y, y' there.
  m.time = t_out;
}

double IdaIntegrator::time() const { return impl_->time; }
Vec IdaIntegrator::state() const { return impl_->y; }
Vec IdaIntegrator::state_rate() const { return impl_->ydot; }

IdaCounters IdaIntegrator::counters() const {
  const Impl& m = *impl_;
  IdaCounters c;
  ida_check(IDAGetNumSteps(m.ida, &c.steps), "IDAGetNumSteps");
  ida_check(IDAGetNumResEvals(m.ida, &c.residual_evaluations), "IDAGetNumResEvals");
  ida_check(IDAGetNumNonlinSolvIters(m.ida, &c.newton_iterations), "IDAGetNumNonlinSolvIters");
  if (m.options.newton == NewtonMethod::krylov) {
    ida_check(IDAGetNumPrecEvals(m.ida, &c.jacobian_setups), "IDAGetNumPrecEvals");
    c.jacobian_setups -= m.callbacks.stale_matrix.taken_over();
    ida_check(IDAGetNumLinIters(m.ida, &c.linear_iterations), "IDAGetNumLinIters");
  } else {
    ida_check(IDAGetNumJacEvals(m.ida, &c.jacobian_setups), "IDAGetNumJacEvals");
    c.linear_iterations = m.callbacks.dae.system.linear_iterations();
  }
  ida_check(IDAGetNumLinSolvSetups(m.ida, &c.linear_solver_setups), "IDAGetNumLinSolvSetups");
  ida_check(IDAGetNumErrTestFails(m.ida, &c.error_test_failures), "IDAGetNumErrTestFails");
  ida_check(IDAGetNumNonlinSolvConvFails(m.ida, &c.newton_convergence_failures), "IDAGetNumNonlinSolvConvFails");
  c.stale_matrix_failures = m.callbacks.stale_matrix.failures();
  c.stale_matrix_refusals = m.callbacks.stale_matrix.refusals();
  c.stale_matrix_aged = m.callbacks.stale_matrix.aged();
  ida_check(IDAGetLastStep(m.ida, &c.last_step), "IDAGetLastStep");
  ida_check(IDAGetLastOrder(m.ida, &c.last_order), "IDAGetLastOrder");
  return c;
}

}  // namespace needlefem
