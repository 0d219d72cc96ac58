// Coulomb stick and slip under IDA (penalty_contact.hpp): a 1 x 1 x 0.25 mm tissue slab
// (neo-Hookean, μ₀ = 1 kPa, K = 2μ₀/3, i.e. ν = 0, so pressing does not spread the base and the
// interface starts untouched tangentially) rests on the fixed rigid plane z = 0 with friction
// μ = 0.5 and slip regularisation ε_v = 1e-5 m/s. Its top face is pressed down 5 % over 0.1 s,
// then dragged in x while held down, at a speed that ramps up to V = 1 mm/s = 100 ε_v over
// 10 ms. Both ramps are smoothsteps, with zero speed at their start, so the rest state is a
// consistent start for IDA and no interface point is asked to jump from rest to sliding.
// Checks:
//  * pressing: a normal reaction N and no tangential one;
//  * sticking (drag 4 µm, about a third of the drag at which the base slides): T < μ N; the
//    base has slipped no more than the regularisation's creep allows: a point loaded at a
//    fraction φ of its Coulomb limit slides at ε_v φ/√(1 - φ²), φ rises with the drag, so over
//    the drag time t_d the slip is at most ε_v t_d φ_max/√(1 - φ_max²) with φ_max the largest
//    face ratio |t_T|/(μ p) at the end; and T is the force that shears the same slab (same
//    penalty normal contact) with its base held in x and y (static solve), to within that slip
//    over the slab's shear compliance;
//  * sliding (drag 55 µm): T/N = μ within 1e-3 (the regularisation's own deficit at |v_T| = V
//    is μ ε_v²/(2V²) = 2.5e-5), no lateral force, the whole base sliding at V.
// IDA tolerances: at a sliding point the slip velocity is set by equilibrium alone (the consistent
// friction tangent along the slip is μ p ε_v²/s³ ≈ 0), so IDA's velocity y' = c_j (y - y_pred)
// there carries the corrector's displacement tolerance times c_j. That must stay far below ε_v or
// the friction direction flips between iterations: measured, rtol 1e-6 / atol 1e-12 ends in
// IDA_CONV_FAIL at the onset of slip (steps cut to 1e-20 s), rtol 1e-7 / atol 1e-13 and tighter
// pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "integration/ida_integrator.hpp"
#include "physics/contact/penalty_contact.hpp"
#include "structured_block.hpp"

namespace needlefem::contact::testing {
namespace {

constexpr double kSide = 1e-3, kHeight = 0.25e-3;                                   // m
constexpr double kShearModulus = 1000.0, kBulkModulus = 2.0 / 3.0 * kShearModulus;  // Pa
constexpr double kPressDepth = 0.05 * kHeight, kPressTime = 0.1;                    // m, s
constexpr double kDragSpeed = 1e-3, kDragRamp = 0.01;                               // m/s, s
constexpr double kFriction = 0.5, kSlipRegularisation = 1e-5;                       // -, m/s

// Smoothstep 3s² - 2s³ on [0, 1].
double smoothstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

// Drag distance: the speed V smoothstep((t - t_p)/t_r), integrated.
double drag(double t) {
  const double s = t - kPressTime;
  if (s <= 0.0) return 0.0;
  if (s >= kDragRamp) return kDragSpeed * (s - 0.5 * kDragRamp);
  const double r = s / kDragRamp;
  return kDragSpeed * kDragRamp * (r * r * r - 0.5 * r * r * r * r);
}

Point3 top_displacement(double t) { return {drag(t), 0.0, -kPressDepth * smoothstep(t / kPressTime)}; }

TetMesh slab() {
  std::vector<double> xs, zs{0.0, kHeight};
  for (int i = 0; i <= 4; ++i) xs.push_back(kSide * i / 4);
  return structured_block(xs, xs, zs);
}

struct Reading {
  double normal = 0.0, tangential = 0.0, lateral = 0.0;  // reactions on the plane, N
  std::vector<double> base_x, base_vx;                   // x displacement and speed of the base nodes
  double largest_ratio = 0.0;                            // max over faces of |t_T| / (μ p)
};

Reading read(const PenaltyContact& contact, const TetMesh& mesh, const mechanics::DofMap& dofs,
             const std::vector<int>& base, double t, Vec state, Vec state_rate) {
  const PetscScalar *y, *ydot;
  VecGetArrayRead(state, &y);
  VecGetArrayRead(state_rate, &ydot);
  const ContactResultant result = contact.resultant(t, y, ydot, dofs);
  Reading r;
  r.normal = -result.force_on_obstacle[2];  // the slab pushes the plane down
  r.tangential = result.force_on_obstacle[0];
  r.lateral = result.force_on_obstacle[1];
  for (int node : base) {
    r.base_x.push_back(y[dofs.dof(node, 0)]);
    r.base_vx.push_back(ydot[dofs.dof(node, 0)]);
  }
  const int m = contact.nodes_per_face();
  std::vector<double> x(3 * m), v(3 * m);
  for (std::size_t face = 0; face < contact.face_count(); ++face) {
    for (int a = 0; a < m; ++a)
      for (int c = 0; c < 3; ++c) {
        const int node = contact.face_nodes(face)[a];
        x[3 * a + c] = mesh.nodes[node][c] + y[dofs.dof(node, c)];
        v[3 * a + c] = ydot[dofs.dof(node, c)];
      }
    const Point3 f = contact.face_terms(face, x.data(), v.data(), t, 0.0, false).force_on_tissue;
    if (f[2] > 0.0) r.largest_ratio = std::max(r.largest_ratio, std::hypot(f[0], f[1]) / (kFriction * f[2]));
  }
  VecRestoreArrayRead(state, &y);
  VecRestoreArrayRead(state_rate, &ydot);
  return r;
}

std::vector<int> unique_nodes(std::vector<int> nodes) {
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

// The same slab and penalty normal contact, but the base held in x and y (a perfectly sticking
// interface), its top displaced to top_displacement(t): x reaction of the base (static solve).
double sticking_shear_force(const TetMesh& mesh, const ContactParameters& parameters, double t) {
  const mechanics::DofMap dofs = mechanics::tissue_dof_map(mesh);
  mechanics::DirichletConditions conditions;
  constrain(conditions, mesh, dofs, "z_max", {0, 1, 2},
            [](const Point3&, double time) { return top_displacement(time); });
  constrain(conditions, mesh, dofs, "z_min", {0, 1}, [](const Point3&, double) { return Point3{0.0, 0.0, 0.0}; });
  mechanics::MechanicsSystem system(mesh, neo_hookean(kShearModulus, kBulkModulus),
                                    elements::Formulation::mean_dilatation, conditions);
  ContactParameters frictionless = parameters;
  frictionless.friction_coefficient = 0.0;
  auto plane = std::make_shared<TranslatingPlane>(Point3{0, 0, 0}, Point3{0, 0, 1}, Point3{0, 0, 0});
  system.add_surface_load(std::make_shared<PenaltyContact>(mesh, "z_min", plane, frictionless));
  Vec y, ydot;
  VecCreateSeq(PETSC_COMM_SELF, system.local_size(), &y);
  VecDuplicate(y, &ydot);
  system.initial_state(t, y, ydot);
  EXPECT_GT(solve_static(system, t, y, ydot), 0);
  const double force = -system.reaction_force(y, "z_min")[0];  // what the base pulls the plane along with
  VecDestroy(&y);
  VecDestroy(&ydot);
  return force;
}

// The slab on the fixed rigid plane z = 0, its top face moved by top_displacement(t), integrated
// by IDA with `options`; advance(t) reads the contact there.
struct DraggedSlab {
  DraggedSlab(const ContactParameters& parameters, const IdaOptions& options)
      : mesh(slab()),
        dofs(mechanics::tissue_dof_map(mesh)),
        conditions(top_moved(mesh, dofs)),
        system(mesh, neo_hookean(kShearModulus, kBulkModulus), elements::Formulation::mean_dilatation, conditions),
        contact(std::make_shared<PenaltyContact>(
            mesh, "z_min", std::make_shared<TranslatingPlane>(Point3{0, 0, 0}, Point3{0, 0, 1}, Point3{0, 0, 0}),
            parameters)),
        base(unique_nodes(mesh.surface_faces.at("z_min"))) {
    system.add_surface_load(contact);
    integrator = std::make_unique<IdaIntegrator>(system, options, 0.0, PETSC_COMM_SELF);
    // The element pressures' tolerance: what the displacements' makes of K θ over the slab.
    Vec atol = nullptr;
    VecDuplicate(integrator->state(), &atol);
    system.absolute_tolerances(atol, options.absolute_tolerance,
                               kBulkModulus * options.absolute_tolerance / kHeight);
    integrator->set_absolute_tolerances(atol);
    VecDestroy(&atol);
  }
  static mechanics::DirichletConditions top_moved(const TetMesh& mesh, const mechanics::DofMap& dofs) {
    mechanics::DirichletConditions conditions;
    constrain(conditions, mesh, dofs, "z_max", {0, 1, 2},
              [](const Point3&, double t) { return top_displacement(t); });
    return conditions;
  }
  Reading advance(double t) {
    integrator->advance_to(t);
    return read(*contact, mesh, dofs, base, t, integrator->state(), integrator->state_rate());
  }

  TetMesh mesh;
  mechanics::DofMap dofs;
  mechanics::DirichletConditions conditions;
  mechanics::MechanicsSystem system;
  std::shared_ptr<PenaltyContact> contact;
  std::vector<int> base;
  std::unique_ptr<IdaIntegrator> integrator;
};

TEST(FrictionalSliding, SticksBelowAndSlidesAtCoulombLimit) {
  ContactParameters parameters;
  parameters.friction_coefficient = kFriction;
  parameters.reference_modulus = kShearModulus;
  parameters.friction_law = FrictionLaw::velocity;
  parameters.slip_velocity_regularisation = kSlipRegularisation;
  IdaOptions options;
  options.relative_tolerance = 1e-7;
  options.absolute_tolerance = 1e-13;
  options.max_step = 2e-3;
  DraggedSlab slab_on_plane(parameters, options);
  const TetMesh& mesh = slab_on_plane.mesh;
  IdaIntegrator& integrator = *slab_on_plane.integrator;
  const auto advance = [&](double t) { return slab_on_plane.advance(t); };
  const Reading pressed = advance(kPressTime);
  const double stick_time = kPressTime + 0.009, slide_time = kPressTime + 0.06;
  const Reading stuck = advance(stick_time);
  const IdaCounters at_stick = integrator.counters();
  const Reading sliding = advance(slide_time);
  const IdaCounters counters = integrator.counters();

  double slip = 0.0, stuck_speed = 0.0, slowest_slide = kDragSpeed;
  for (std::size_t i = 0; i < slab_on_plane.base.size(); ++i) {
    slip = std::max(slip, std::abs(stuck.base_x[i] - pressed.base_x[i]));
    stuck_speed = std::max(stuck_speed, std::abs(stuck.base_vx[i]));
    slowest_slide = std::min(slowest_slide, sliding.base_vx[i]);
  }
  const double phi = stuck.largest_ratio;
  const double slip_bound = kSlipRegularisation * (stick_time - kPressTime) * phi / std::sqrt(1.0 - phi * phi);
  const double sticking = sticking_shear_force(mesh, parameters, stick_time);
  // Shear compliance of the slab: drag / sticking force; creep slip relaxes T by slip / compliance.
  const double relaxation_bound = slip_bound / drag(stick_time);
  const double deficit = kFriction - sliding.tangential / sliding.normal;
  std::printf("pressed: N = %.4e N, T/N = %.1e\n", pressed.normal, pressed.tangential / pressed.normal);
  std::printf(
      "stuck (drag %.2f um): T/(mu N) = %.4f, max face phi = %.4f; T / T_stick - 1 = %+.2e (bound %.1e); "
      "base slip %.3e um <= bound %.3e um; base speed %.2e m/s\n",
      drag(stick_time) * 1e6, stuck.tangential / (kFriction * stuck.normal), phi, stuck.tangential / sticking - 1.0,
      relaxation_bound, slip * 1e6, slip_bound * 1e6, stuck_speed);
  std::printf(
      "sliding (drag %.1f um): T/N = %.7f, |T/N - mu| = %.2e (regularisation deficit mu eps^2/2V^2 = %.1e), "
      "lateral/N = %.1e, slowest base node %.5f V\n",
      drag(slide_time) * 1e6, sliding.tangential / sliding.normal, deficit,
      kFriction * kSlipRegularisation * kSlipRegularisation / (2.0 * kDragSpeed * kDragSpeed),
      sliding.lateral / sliding.normal, slowest_slide / kDragSpeed);
  std::printf(
      "IDA: %ld steps, %ld Newton iterations, %ld Jacobian setups, %ld error-test and %ld Newton failures "
      "(%ld steps up to the stick reading)\n",
      counters.steps, counters.newton_iterations, counters.jacobian_setups, counters.error_test_failures,
      counters.newton_convergence_failures, at_stick.steps);

  EXPECT_GT(pressed.normal, 0.0);
  EXPECT_LT(std::abs(pressed.tangential), 1e-3 * pressed.normal);

  EXPECT_GT(stuck.tangential, 0.0);
  EXPECT_LT(stuck.tangential, kFriction * stuck.normal);
  EXPECT_LT(phi, 1.0);
  EXPECT_LT(slip, slip_bound);
  EXPECT_LT(std::abs(stuck.tangential / sticking - 1.0), relaxation_bound);

  EXPECT_NEAR(sliding.tangential / sliding.normal, kFriction, 1e-3);
  EXPECT_LT(std::abs(sliding.lateral), 1e-3 * sliding.normal);
  EXPECT_GT(slowest_slide, 0.99 * kDragSpeed);
}

// The same slab and history with the return-map law at IDA's default tolerances. Sticking is
// elastic on the stick stiffness μ p/s₀ (no creep): the base moves up to the elastic slip s₀
// relative to the plane, so T falls short of the perfectly sticking slab's force by about the
// stick springs' share of the compliance, C_stick/(C_slab + C_stick) with C_stick = s₀/(μ N)
// (μ p/s₀ per area, summed over the base) and C_slab = drag/T_stick (a uniform-shear estimate:
// neither the base's shear nor its pressure is uniform near the slab's free edges, hence a factor
// 1.5 of room). Sliding points carry exactly μ p: T/N = μ up to the few
// base points still sticking near the trailing edge (measured 4e-6; bound 1e-4, ten times
// tighter than the velocity law's).
TEST(FrictionalSliding, ReturnMapSticksElasticallyAndSlidesAtExactlyMu) {
  ContactParameters parameters;
  parameters.friction_coefficient = kFriction;
  parameters.reference_modulus = kShearModulus;
  ASSERT_EQ(parameters.friction_law, FrictionLaw::return_map);
  // needlefem's run defaults: Newton-Krylov with up to 20 iterations, rtol 1e-4, atol 1e-8. The
  // whole base goes from stick to slip at once here, a kink in every contact point together:
  // modified Newton (a stick matrix much stiffer than the slab contracts a sliding point by
  // k/(k + K) ≈ 1 per iteration) and 4 iterations both end in IDA_CONV_FAIL at the onset of slip
  // (measured with the earlier stick stiffness ε_T = ε_N).
  IdaOptions options;
  options.newton = NewtonMethod::krylov;
  options.max_newton_iterations = 20;
  options.max_step = 2e-3;
  DraggedSlab slab_on_plane(parameters, options);
  const TetMesh& mesh = slab_on_plane.mesh;
  const auto advance = [&](double t) { return slab_on_plane.advance(t); };
  const Reading pressed = advance(kPressTime);
  const double stick_time = kPressTime + 0.009, slide_time = kPressTime + 0.06;
  const Reading stuck = advance(stick_time);
  const Reading sliding = advance(slide_time);
  const IdaCounters counters = slab_on_plane.integrator->counters();

  const double sticking = sticking_shear_force(mesh, parameters, stick_time);
  // s₀ = e h_face with h_face = c μ₀/ε_N (one face size on this mesh).
  const double face_size = parameters.penalty_factor * kShearModulus / slab_on_plane.contact->penalty(0);
  const double stick_compliance = parameters.elastic_slip * face_size / (kFriction * stuck.normal);
  const double slab_compliance = drag(stick_time) / sticking;
  const double shortfall_bound = stick_compliance / (slab_compliance + stick_compliance);
  double slowest_slide = kDragSpeed;
  for (double v : sliding.base_vx) slowest_slide = std::min(slowest_slide, v);
  std::printf("return map: stuck T/(mu N) = %.4f, max face phi = %.4f, 1 - T/T_stick = %.3e (bound %.3e); "
              "sliding T/N = %.12f, lateral/N = %.1e, slowest base node %.5f V; IDA %ld steps, %ld Newton its, "
              "%ld Newton failures\n",
              stuck.tangential / (kFriction * stuck.normal), stuck.largest_ratio, 1.0 - stuck.tangential / sticking,
              shortfall_bound, sliding.tangential / sliding.normal, sliding.lateral / sliding.normal,
              slowest_slide / kDragSpeed, counters.steps, counters.newton_iterations,
              counters.newton_convergence_failures);

  EXPECT_GT(pressed.normal, 0.0);
  EXPECT_LT(std::abs(pressed.tangential), 1e-3 * pressed.normal);
  EXPECT_LT(stuck.largest_ratio, 1.0);
  EXPECT_GT(stuck.tangential, 0.0);
  EXPECT_GE(1.0 - stuck.tangential / sticking, 0.0);
  EXPECT_LT(1.0 - stuck.tangential / sticking, 1.5 * shortfall_bound);
  EXPECT_NEAR(sliding.tangential / sliding.normal, kFriction, 1e-4);
  EXPECT_LT(std::abs(sliding.lateral), 1e-3 * sliding.normal);
  EXPECT_GT(slowest_slide, 0.99 * kDragSpeed);
}

}  // namespace
}  // namespace needlefem::contact::testing
