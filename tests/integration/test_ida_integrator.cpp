// IdaIntegrator on closed-form DAEs: accuracy against the exact generalised Maxwell solid,
// convergence order with fixed steps, must-hit output times, recoverable and fatal failures,
// and the counters (factorisation reuse, one linear solve per Newton iteration).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "integration/ida_integrator.hpp"
#include "maxwell_solid.hpp"

namespace needlefem {
namespace {

using testing::MaxwellSolid;
using testing::MaxwellSolidSystem;

IdaOptions with_tolerance(double rtol) {
  IdaOptions options;
  options.relative_tolerance = rtol;
  return options;
}

const std::vector<double> kOutputTimes{0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 3.0};

std::array<double, 3> values(Vec v) {
  const double* a = nullptr;
  petsc_check(VecGetArrayRead(v, &a), "VecGetArrayRead");
  std::array<double, 3> copy{a[0], a[1], a[2]};
  petsc_check(VecRestoreArrayRead(v, &a), "VecRestoreArrayRead");
  return copy;
}

// Largest error over the output times, stress relative to the peak stress and viscous strains
// relative to the strain amplitude.
double max_relative_error(IdaIntegrator& ida, const MaxwellSolid& solid, const std::vector<double>& times) {
  double worst = 0.0;
  for (double t : times) {
    ida.advance_to(t);
    const auto y = values(ida.state());
    const auto exact = solid.exact(t);
    worst = std::max({worst, std::abs(y[0] - exact[0]) / solid.peak_stress(), std::abs(y[1] - exact[1]) / solid.eps0,
                      std::abs(y[2] - exact[2]) / solid.eps0});
  }
  return worst;
}

// Per-component absolute tolerances: rtol times the stress and strain scales.
void set_scaled_tolerances(IdaIntegrator& ida, const MaxwellSolid& solid, double rtol) {
  Vec atol = nullptr;
  petsc_check(VecDuplicate(ida.state(), &atol), "VecDuplicate");
  const PetscInt index[3] = {0, 1, 2};
  const double scale[3] = {rtol * solid.peak_stress(), rtol * solid.eps0, rtol * solid.eps0};
  petsc_check(VecSetValues(atol, 3, index, scale, INSERT_VALUES), "VecSetValues");
  petsc_check(VecAssemblyBegin(atol), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(atol), "VecAssemblyEnd");
  ida.set_absolute_tolerances(atol);
  VecDestroy(&atol);
}

TEST(IdaIntegrator, MaxwellSolidErrorFollowsTheTolerance) {
  double previous_error = 1.0;
  for (double rtol : {1e-4, 1e-6, 1e-8}) {
    MaxwellSolidSystem system;
    IdaIntegrator ida(system, with_tolerance(rtol), 0.0, PETSC_COMM_SELF);
    set_scaled_tolerances(ida, system.solid(), rtol);
    const double error = max_relative_error(ida, system.solid(), kOutputTimes);
    const auto c = ida.counters();
    std::printf("rtol %.0e: max relative error %.3e, steps %ld, Newton %ld, Jacobian setups %ld, "
                "error-test failures %ld\n",
                rtol, error, c.steps, c.newton_iterations, c.jacobian_setups, c.error_test_failures);
    EXPECT_LT(error, 20.0 * rtol) << "rtol " << rtol;
    EXPECT_LT(error, 0.2 * previous_error) << "rtol " << rtol;
    previous_error = error;
  }
}

// Fixed steps, error test off: BDF1 (backward Euler) converges at order 1, BDF up to order 2
// at order 2, measured from successive step halvings over [0, 1] s (the ramp end 0.1 s is a
// step boundary for every h).
TEST(IdaIntegrator, FixedStepOrderOfAccuracy) {
  for (int max_order : {1, 2}) {
    std::vector<double> errors;
    for (double h : {0.01, 0.005, 0.0025}) {
      MaxwellSolidSystem system;
      IdaOptions options = with_tolerance(1e-10);
      options.max_order = max_order;
      options.fixed_step = h;
      IdaIntegrator ida(system, options, 0.0, PETSC_COMM_SELF);
      set_scaled_tolerances(ida, system.solid(), 1e-10);
      errors.push_back(max_relative_error(ida, system.solid(), {0.1, 0.5, 1.0}));
      const auto c = ida.counters();
      EXPECT_EQ(c.error_test_failures, 0);
      EXPECT_NEAR(c.last_step, h, 1e-9 * h);
      // 1 s in steps of h (a few more while the very first steps build up history).
      EXPECT_GE(c.steps, std::lround(1.0 / h));
    }
    for (std::size_t k = 1; k < errors.size(); ++k) {
      const double order = std::log2(errors[k - 1] / errors[k]);
      std::printf("max order %d: errors %.3e -> %.3e, observed order %.3f\n", max_order, errors[k - 1], errors[k], order);
      EXPECT_NEAR(order, max_order, 0.2) << "max order " << max_order;
    }
  }
}

TEST(IdaIntegrator, ReturnsExactlyAtEachOutputTime) {
  MaxwellSolidSystem system;
  IdaIntegrator ida(system, with_tolerance(1e-8), 0.0, PETSC_COMM_SELF);
  set_scaled_tolerances(ida, system.solid(), 1e-8);
  for (double t : {0.013, 0.0999999, 0.1, 0.1000001, 0.37, 1.0, 2.5}) {
    ida.advance_to(t);
    EXPECT_EQ(ida.time(), t);
    // The state is the solution AT t (not at the last internal step past it).
    const auto y = values(ida.state());
    EXPECT_NEAR(y[0], system.solid().exact(t)[0], 1e-6 * system.solid().peak_stress()) << "t = " << t;
  }
  ida.advance_to(2.5);  // already there: no-op
  EXPECT_EQ(ida.time(), 2.5);
  EXPECT_THROW(ida.advance_to(1.0), std::invalid_argument);
}

// An output time that the next step reaches up to round-off is one step away: with steps capped
// at 0.005 s and outputs every 0.01 s, each output takes exactly two steps (the halving that
// keeps a landing step from being a sliver must not turn the second into two halves).
TEST(IdaIntegrator, OutputTimesOneStepAwayTakeOneStep) {
  MaxwellSolidSystem system;
  IdaOptions options = with_tolerance(1e-4);
  options.max_step = 0.005;
  IdaIntegrator ida(system, options, 0.0, PETSC_COMM_SELF);
  set_scaled_tolerances(ida, system.solid(), 1e-4);
  ida.advance_to(1.0);
  const long steps_before = ida.counters().steps;
  for (int k = 1; k <= 100; ++k) ida.advance_to(1.0 + 0.01 * k);
  EXPECT_EQ(ida.counters().steps - steps_before, 200);
  EXPECT_NEAR(ida.counters().last_step, 0.005, 1e-12);
}

TEST(IdaIntegrator, CountersAreConsistentAndFactorisationsAreReused) {
  MaxwellSolidSystem system;
  IdaIntegrator ida(system, with_tolerance(1e-6), 0.0, PETSC_COMM_SELF);
  set_scaled_tolerances(ida, system.solid(), 1e-6);
  max_relative_error(ida, system.solid(), kOutputTimes);
  const auto c = ida.counters();
  std::printf("steps %ld, residuals %ld, Newton %ld, Jacobian setups %ld, LS setups %ld, error-test failures %ld, "
              "Newton failures %ld, last step %.3e s, last order %d\n",
              c.steps, c.residual_evaluations, c.newton_iterations, c.jacobian_setups, c.linear_solver_setups,
              c.error_test_failures, c.newton_convergence_failures, c.last_step, c.last_order);
  EXPECT_GT(c.steps, 10);
  EXPECT_LT(c.steps, 10000);
  EXPECT_GE(c.newton_iterations, c.steps);
  EXPECT_LT(c.newton_iterations, 10 * c.steps);  // sane, not garbage in the upper bits
  EXPECT_GE(c.residual_evaluations, c.newton_iterations);
  EXPECT_GT(c.jacobian_setups, 0);
  EXPECT_EQ(c.jacobian_setups, c.linear_solver_setups);
  EXPECT_LT(c.jacobian_setups, c.steps);  // the factorisation is reused across steps
  EXPECT_EQ(c.linear_iterations, 0);      // MUMPS LU
  EXPECT_GE(c.last_order, 1);
  EXPECT_LE(c.last_order, 5);
  EXPECT_GT(c.last_step, 0.0);
  // The custom linear solver is really the one IDA uses: every Jacobian evaluation reached
  // setup_jacobian() (which factors; without it the KSP has no operator and solves fail), and
  // every Newton iteration one solve_jacobian().
  EXPECT_EQ(system.jacobian_setups(), c.jacobian_setups);
  EXPECT_EQ(system.jacobian_solves(), c.newton_iterations);
}

// A Krylov solve makes the linear solver matrix-iterative for IDA: same answer, and the
// iterations are counted.
TEST(IdaIntegrator, IterativeLinearSolverGivesTheSameAccuracy) {
  MaxwellSolidSystem system({}, {.method = KspMethod::gmres_asm, .relative_tolerance = 1e-12});
  ASSERT_TRUE(system.iterative_linear_solver());
  IdaIntegrator ida(system, with_tolerance(1e-6), 0.0, PETSC_COMM_SELF);
  set_scaled_tolerances(ida, system.solid(), 1e-6);
  const double error = max_relative_error(ida, system.solid(), kOutputTimes);
  const auto c = ida.counters();
  std::printf("gmres-asm: max relative error %.3e, Newton %ld, Krylov iterations %ld\n", error, c.newton_iterations,
              c.linear_iterations);
  EXPECT_LT(error, 20.0 * 1e-6);
  // ILU(0) of this triangular matrix is exact: one iteration per solve, none when b is
  // already below the Krylov tolerance (IDA then takes the solver's "residual" as correction).
  EXPECT_GT(c.linear_iterations, 0);
  EXPECT_LE(c.linear_iterations, c.newton_iterations);
  EXPECT_EQ(system.jacobian_solves(), c.newton_iterations);
}

// Start mid-ramp with the stress (algebraic) and the viscous rates (derivatives of the
// differential unknowns) wrong: IDACalcIC restores them from the viscous strains.
class InconsistentStart : public MaxwellSolidSystem {
 public:
  void initial_state(double t0, Vec y, Vec ydot) override {
    MaxwellSolidSystem::initial_state(t0, y, ydot);
    VecSetValue(y, 0, 0.0, INSERT_VALUES);
    VecAssemblyBegin(y);
    VecAssemblyEnd(y);
    VecSet(ydot, 0.0);
  }
};

TEST(IdaIntegrator, InitialStateIsMadeConsistent) {
  InconsistentStart system;
  const MaxwellSolid& solid = system.solid();
  const double t0 = 0.05;
  IdaIntegrator ida(system, with_tolerance(1e-8), t0, PETSC_COMM_SELF);
  set_scaled_tolerances(ida, solid, 1e-8);
  ida.make_initial_state_consistent(0.1);
  const auto y = values(ida.state()), rate = values(ida.state_rate()), exact = solid.exact(t0);
  EXPECT_NEAR(y[0], exact[0], 1e-9 * solid.peak_stress());
  EXPECT_NEAR(y[1], exact[1], 1e-12);  // differential: kept
  EXPECT_NEAR(rate[1], (solid.strain(t0) - exact[1]) / solid.tau[0], 1e-9);
  EXPECT_NEAR(rate[2], (solid.strain(t0) - exact[2]) / solid.tau[1], 1e-9);
  EXPECT_LT(max_relative_error(ida, solid, {0.1, 1.0}), 20e-8);
}

// Start at rest on a strain ramp already moving (y' = 0 while eps' = eps0/t_ramp): the probe
// step recovers the consistent rates, sigma' = (E_inf + Σ E_i) eps' and alpha_i' = 0 (exact at
// t0 = 0, where eps = alpha_i = 0), to O(probe), and the run then needs fewer steps.
class StartsAtRest : public MaxwellSolidSystem {
 public:
  void initial_state(double t0, Vec y, Vec ydot) override {
    MaxwellSolidSystem::initial_state(t0, y, ydot);
    VecSet(ydot, 0.0);
  }
};

TEST(IdaIntegrator, ProbeStepGivesTheConsistentInitialRates) {
  const double rtol = 1e-6;
  long steps_from_rest = 0;
  {
    StartsAtRest system;
    IdaIntegrator ida(system, with_tolerance(rtol), 0.0, PETSC_COMM_SELF);
    set_scaled_tolerances(ida, system.solid(), rtol);
    EXPECT_LT(max_relative_error(ida, system.solid(), kOutputTimes), 20.0 * rtol);
    steps_from_rest = ida.counters().steps;
  }
  StartsAtRest system;
  const MaxwellSolid& solid = system.solid();
  IdaIntegrator ida(system, with_tolerance(rtol), 0.0, PETSC_COMM_SELF);
  set_scaled_tolerances(ida, solid, rtol);
  const double probe = 1e-9;
  const auto probed = ida.make_initial_rates_consistent(probe, 0.05);
  EXPECT_TRUE(probed.converged);
  EXPECT_LE(probed.iterations, 3);  // linear system: one iteration, plus the one that sees it converged
  const auto rate = values(ida.state_rate());
  const double strain_rate = solid.eps0 / solid.t_ramp;
  const double stiffness = solid.e_inf + solid.e_branch[0] + solid.e_branch[1];
  EXPECT_NEAR(rate[0], stiffness * strain_rate, 1e-6 * stiffness * strain_rate);
  // alpha_i' = eps(probe) / (tau_i + probe) ~ strain_rate probe / tau_i: O(probe).
  EXPECT_NEAR(rate[1], 0.0, 10.0 * strain_rate * probe / solid.tau[0]);
  EXPECT_LT(max_relative_error(ida, solid, kOutputTimes), 20.0 * rtol);
  const long steps_probed = ida.counters().steps;
  std::printf("steps from rest %ld, after the probe step %ld\n", steps_from_rest, steps_probed);
  EXPECT_LT(steps_probed, steps_from_rest);
}

// Newton-Krylov (GMRES on IDA's difference quotients, preconditioned by the factored matrix):
// the same accuracy; a stale factorisation may serve across larger cj changes.
TEST(IdaIntegrator, NewtonKrylovGivesTheSameAccuracyWithFewerFactorisations) {
  const double rtol = 1e-6;
  long modified_setups = 0;
  for (NewtonMethod method : {NewtonMethod::modified, NewtonMethod::krylov}) {
    MaxwellSolidSystem system;
    IdaOptions options = with_tolerance(rtol);
    options.newton = method;
    if (method == NewtonMethod::krylov) options.newton_matrix_cj_change = 0.9;
    IdaIntegrator ida(system, options, 0.0, PETSC_COMM_SELF);
    set_scaled_tolerances(ida, system.solid(), rtol);
    const double error = max_relative_error(ida, system.solid(), kOutputTimes);
    const auto c = ida.counters();
    std::printf("%s: error %.3e, steps %ld, Newton %ld, setups %ld, GMRES iterations %ld\n",
                method == NewtonMethod::krylov ? "krylov" : "modified", error, c.steps, c.newton_iterations,
                c.jacobian_setups, c.linear_iterations);
    EXPECT_LT(error, 20.0 * rtol);
    EXPECT_EQ(system.jacobian_setups(), c.jacobian_setups);
    if (method == NewtonMethod::modified) {
      modified_setups = c.jacobian_setups;
      EXPECT_EQ(c.linear_iterations, 0);
    } else {
      EXPECT_GT(c.linear_iterations, 0);
      EXPECT_LT(c.jacobian_setups, modified_setups);
    }
  }
}

// After the probe step, IDA's first setup takes the probe's factored matrix (c_j = 1/probe) over
// where the system says it serves (DaeSystem::newton_matrix_serves): one factorisation fewer,
// the same accuracy, and IDA's count of setups stays the system's own (less the probe's). With
// three unknowns GMRES is exact within three iterations on any preconditioner, so here any
// matrix serves.
class StartsAtRestAnyMatrixServes : public StartsAtRest {
 public:
  bool newton_matrix_serves(double, double) const override { return true; }
};

TEST(IdaIntegrator, KrylovNewtonTakesTheProbeMatrixOverWhereItServes) {
  const double rtol = 1e-6;
  const auto run = [&](StartsAtRest& system) {
    IdaOptions options = with_tolerance(rtol);
    options.newton = NewtonMethod::krylov;
    IdaIntegrator ida(system, options, 0.0, PETSC_COMM_SELF);
    set_scaled_tolerances(ida, system.solid(), rtol);
    EXPECT_TRUE(ida.make_initial_rates_consistent(1e-9, 0.05).converged);
    const double error = max_relative_error(ida, system.solid(), kOutputTimes);
    const auto c = ida.counters();
    std::printf("error %.3e, steps %ld, setups %ld (system %ld), GMRES iterations %ld\n", error, c.steps,
                c.jacobian_setups, system.jacobian_setups(), c.linear_iterations);
    EXPECT_LT(error, 20.0 * rtol);
    EXPECT_EQ(system.jacobian_setups(), c.jacobian_setups + 1);  // + the probe step's
    return system.jacobian_setups();
  };
  StartsAtRest refactoring;
  StartsAtRestAnyMatrixServes taking_over;
  const long refactored = run(refactoring), taken_over = run(taking_over);
  EXPECT_EQ(taken_over, refactored - 1);
}

// y' = (1 - y) / tau, y(0) = 0 (a saturating variable such as a damage fraction that cannot
// exceed 1): exact y = 1 - exp(-t / tau). The residual reports a recoverable failure for y > 1,
// which only the predictor of a long step reaches (polynomial extrapolation of the saturating
// curve overshoots); the corrector of every step stays below 1.
class SaturatingSystem : public DaeSystem {
 public:
  double tau = 1.0;
  long recoverable_failures = 0;
  PetscInt local_size() const override { return 1; }
  void initial_state(double, Vec y, Vec ydot) override {
    VecSet(y, 0.0);
    VecSet(ydot, 1.0 / tau);
  }
  void differential_mask(Vec id) override { VecSet(id, 1.0); }
  DaeStatus residual(double, Vec y, Vec ydot, Vec F) override {
    const double v = scalar(y);
    if (v > 1.0) {
      ++recoverable_failures;
      return DaeStatus::recoverable;
    }
    VecSet(F, scalar(ydot) - (1.0 - v) / tau);
    return DaeStatus::ok;
  }
  DaeStatus setup_jacobian(double, Vec, Vec, double cj) override {
    jacobian_ = cj + 1.0 / tau;
    return DaeStatus::ok;
  }
  DaeStatus solve_jacobian(Vec b, Vec x) override {
    VecCopy(b, x);
    VecScale(x, 1.0 / jacobian_);
    return DaeStatus::ok;
  }
  static double scalar(Vec v) {
    const PetscInt index = 0;
    double value = 0;
    VecGetValues(v, 1, &index, &value);
    return value;
  }

 private:
  double jacobian_ = 1.0;
};

TEST(IdaIntegrator, RecoverableFailureCutsTheStepAndTheRunFinishes) {
  SaturatingSystem system;
  IdaOptions options = with_tolerance(1e-4);
  options.absolute_tolerance = 1e-6;
  options.max_order = 1;
  IdaIntegrator ida(system, options, 0.0, PETSC_COMM_SELF);
  ida.advance_to(40.0);
  const auto c = ida.counters();
  const double y = SaturatingSystem::scalar(ida.state());
  std::printf("recoverable failures %ld, Newton convergence failures %ld, steps %ld, y(40) - exact = %.2e\n",
              system.recoverable_failures, c.newton_convergence_failures, c.steps, y - (1.0 - std::exp(-40.0)));
  EXPECT_GT(system.recoverable_failures, 0);
  EXPECT_GE(c.newton_convergence_failures, system.recoverable_failures);
  EXPECT_EQ(ida.time(), 40.0);
  EXPECT_NEAR(y, 1.0 - std::exp(-40.0), 1e-4);
}

// Fatal after t = 0.5 s (as if an element had inverted beyond repair).
class FailingSystem : public SaturatingSystem {
 public:
  bool throw_instead = false;
  DaeStatus residual(double t, Vec y, Vec ydot, Vec F) override {
    if (t > 0.5) {
      if (throw_instead) throw std::runtime_error("element 17 inverted");
      return DaeStatus::fatal;
    }
    return SaturatingSystem::residual(t, y, ydot, F);
  }
};

double time_named_in(const std::string& message) {
  const std::string marker = "stopped at t = ";
  const auto at = message.find(marker);
  if (at == std::string::npos) return -1.0;
  return std::stod(message.substr(at + marker.size()));
}

TEST(IdaIntegrator, FatalFailureThrowsNamingTheTime) {
  for (bool throw_instead : {false, true}) {
    FailingSystem system;
    system.throw_instead = throw_instead;
    IdaIntegrator ida(system, {}, 0.0, PETSC_COMM_SELF);
    try {
      ida.advance_to(1.0);
      ADD_FAILURE() << "advance_to past a fatal failure returned";
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      std::printf("%s\n", message.c_str());
      EXPECT_NE(message.find("IDA_RES_FAIL"), std::string::npos) << message;
      const double t_failed = time_named_in(message);
      EXPECT_GT(t_failed, 0.0) << message;
      EXPECT_LE(t_failed, 0.5) << message;
      if (throw_instead) {
        EXPECT_NE(message.find("element 17 inverted"), std::string::npos) << message;
      }
    }
  }
}

TEST(IdaIntegrator, RejectsInvalidOptions) {
  MaxwellSolidSystem system;
  IdaOptions order_six, negative_step, zero_rtol, krylov_fixed_step;
  order_six.max_order = 6;
  negative_step.fixed_step = -0.1;
  zero_rtol.relative_tolerance = 0.0;
  krylov_fixed_step.fixed_step = 0.01;
  krylov_fixed_step.newton = NewtonMethod::krylov;
  for (const auto& options : {order_six, negative_step, zero_rtol, krylov_fixed_step})
    EXPECT_THROW(IdaIntegrator(system, options, 0.0, PETSC_COMM_SELF), std::invalid_argument);
}

}  // namespace
}  // namespace needlefem
