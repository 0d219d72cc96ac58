// The compliant-tip FEM of `needlefem prbm-check` (prbm_check/tip_statics.hpp) against closed forms.
//
// A steel tip with a slender neck (l = 2 mm, d = 0.2 mm, l/d = 10) and a flat 1 mm head: the head
// is 625 times stiffer in bending than the neck, so under a small head load F with lever a (neck
// centre to load resultant) it turns rigidly on an Euler-Bernoulli cantilever neck whose end
// moment varies linearly from F (a - l/2) to F (a + l/2):
//   theta = ∫_0^l M/(EI) dz = F a l / (E I),  I = pi d^4 / 64.
// The 3-D tip is softer by the elastic rotation of the neck's roots in the shoulders, O(d/l)
// (3 % here; 6 % at the paper's l/d = 5) and the quadratic tets are slightly stiffer than the
// converged solution (1-2 % at 0.07 mm), hence the one-sided band: 0 % to 6 % softer.
//
// At a 20 deg turn: under a follower load the moment about the neck stays F a, so the angle stays
// linear in F (the co-rotational FEM must not stiffen or soften by more than 1 %); under a dead load
// the moment arm shortens to a cos(theta), so the rigid-head estimate K theta = F a cos(theta) with
// K = F a / theta_linear holds to 2 % (the pivot is not exactly at the neck centre).
// main(): tests/mechanics/petsc_main.cpp (GoogleTest inside PETSc).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "prbm_check/prbm_check.hpp"
#include "prbm_check/tip_mesh.hpp"
#include "prbm_check/tip_statics.hpp"

namespace needlefem::prbm {
namespace {

constexpr double E = 200e9, nu = 0.3;

CompliantTip slender_tip() {
  CompliantTip tip;
  tip.radius = 0.5e-3;
  tip.shaft = 0.1e-3;
  tip.neck_length = 2.0e-3;
  tip.neck_diameter = 0.2e-3;
  tip.head_length = 1.0e-3;
  tip.point_length = 0.0;
  return tip;
}

class TipFem : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    fem_ = new CompliantTipStatics(tip_, mesh_compliant_tip(tip_, {0.3e-3, 0.07e-3}), E, nu);
  }
  static void TearDownTestSuite() { delete fem_; }
  static inline CompliantTip tip_ = slender_tip();
  static inline CompliantTipStatics* fem_ = nullptr;
};

TEST_F(TipFem, LoadResultantSitsAtTheFlatHeadsCentre) {
  EXPECT_NEAR(fem_->load_lever_m(), 0.5 * (tip_.neck_length + tip_.head_length), 1e-3 * tip_.head_length);
}

TEST_F(TipFem, SmallLoadRotationMatchesTheEulerBernoulliNeck) {
  const double I = std::numbers::pi * std::pow(tip_.neck_diameter, 4) / 64.0;
  const double closed_form = fem_->load_lever_m() * tip_.neck_length / (E * I);  // rad per N
  const double fem = fem_->linear_rotation_per_newton();
  const double softer = fem / closed_form - 1.0;
  RecordProperty("softer_than_euler_bernoulli_percent", std::to_string(100.0 * softer));
  EXPECT_GT(softer, 0.0) << "FEM " << fem << " rad/N, Euler-Bernoulli " << closed_form;
  EXPECT_LT(softer, 0.06) << "FEM " << fem << " rad/N, Euler-Bernoulli " << closed_form;
}

TEST_F(TipFem, LargeRotationFollowerStaysLinearDeadLoadLosesItsArm) {
  const double slope = fem_->linear_rotation_per_newton();
  const double theta_linear = 20.0 * std::numbers::pi / 180.0;
  const double force = theta_linear / slope;
  fem_->reset();
  const TipSolution follower = fem_->solve(force, LoadKind::follower);
  RecordProperty("follower_over_linear", std::to_string(follower.head_rotation_rad / theta_linear));
  EXPECT_NEAR(follower.head_rotation_rad / theta_linear, 1.0, 0.01);
  EXPECT_LT(follower.newton_iterations, 15);
  fem_->reset();
  const double dead = fem_->solve(force, LoadKind::dead).head_rotation_rad;
  // Rigid head on a torsion spring: theta = theta_linear cos(theta), solved by fixed point.
  double rigid = theta_linear;
  for (int i = 0; i < 100; ++i) rigid = theta_linear * std::cos(rigid);
  RecordProperty("dead_over_rigid_head_estimate", std::to_string(dead / rigid));
  EXPECT_NEAR(dead / rigid, 1.0, 0.02) << "dead " << dead << " rad, rigid-head estimate " << rigid;
}

// The table's summary in words: "within 5 % up to 0 deg" once said "never".
TEST(PrbmAccuracy, SaysWhenEvenTheSmallestAngleMissesTheTolerance) {
  PrbmCheckResult result;
  result.tolerance_percent = 5.0;
  const auto row = [](double prbm_deg, double follower_error, double dead_error) {
    PrbmCheckRow r;
    r.prbm_deg = prbm_deg;
    r.fem_follower_deg = prbm_deg / (1.0 + follower_error);
    r.fem_dead_deg = prbm_deg / (1.0 + dead_error);
    return r;
  };
  // Follower load off by 7 % throughout; dead load within 5 % from 2 to 15 deg, then 6 % off.
  result.rows = {row(2.0, -0.0713, -0.02), row(15.0, -0.0705, 0.04), row(30.0, -0.0681, 0.06)};
  result.accurate_up_to_deg = 0.0;
  result.dead_accurate_up_to_deg = 15.0;
  EXPECT_EQ(accuracy_text(result, false),
            "off by more than 5 % already at the smallest angle, 2 deg (-7.13 %); at every angle");
  EXPECT_EQ(accuracy_text(result, true), "within 5 % up to 15 deg");
  // Paper 000's neck under a dead load: 7 % off at 2 deg, within 5 % again from 15 deg (prbm-check's table).
  result.rows = {row(2.0, -0.0713, -0.0708), row(15.0, -0.0705, -0.0401), row(30.0, -0.0681, 0.0425)};
  result.dead_accurate_up_to_deg = 0.0;
  EXPECT_EQ(accuracy_text(result, true),
            "off by more than 5 % already at the smallest angle, 2 deg (-7.08 %); within it only at 15, 30 deg");
}

}  // namespace
}  // namespace needlefem::prbm
