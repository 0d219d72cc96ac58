// Pseudo-rigid-body model of paper 000's compliant needle (Eq. 2.4-2.8) and `needlefem magnet`.
//
// The paper's worked example: l = 1 mm, L = 3.5 mm, neck diameter 0.2 mm, magnet pole
// 0.05 m x 0.06 m; turning 15 deg needs 0.0391 T and 30 deg 0.0553 T. The paper leaves E, phi and
// the tissue constant unstated. They are reproduced by a steel neck, E = 200 GPa, the pull along
// the head (phi = 0) and no tissue (mu_t = 0), with the gap area A_g = W L that Eq. 2.8 as
// printed omits:
//   K = E pi d^4 / (64 l) = 200e9 * pi * (2e-4)^4 / 64 / 1e-3 = 1.5708e-2 N m/rad
//   B(15 deg) = sqrt(8 pi 1e-7 * 2 * 0.261799 * K / (4.5e-3 * 3e-3)) = 0.039130 T
//   B(30 deg) = sqrt(2) * B(15 deg)                                  = 0.055338 T
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "steering/hinge.hpp"
#include "steering/magnet.hpp"

namespace needlefem::steering {
namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr double paper_gap_area_m2 = 0.05 * 0.06;

CompliantNeedleHinge paper_needle(double tissue_spring_constant = 0.0) {
  return {1e-3, 0.2e-3, 3.5e-3, 200e9, tissue_spring_constant};
}

TEST(CompliantNeedle, ReproducesThePapersWorkedExample) {
  const CompliantNeedleHinge needle = paper_needle();
  const double b15 = flux_density_for_turning_angle_t(needle, 15.0 * deg, paper_gap_area_m2, 0.0);
  const double b30 = flux_density_for_turning_angle_t(needle, 30.0 * deg, paper_gap_area_m2, 0.0);
  EXPECT_NEAR(b15 / 0.0391, 1.0, 0.005);
  EXPECT_NEAR(b30 / 0.0553, 1.0, 0.005);
  // The hand calculation in the header comment, to its printed digits.
  EXPECT_NEAR(needle.hinge_stiffness_n_m_per_rad(), 1.5708e-2, 1e-6);
  EXPECT_NEAR(b15, 0.0391302205, 1e-10);
  EXPECT_NEAR(b30, 0.0553384885, 1e-10);
}

TEST(CompliantNeedle, InverseRoundTrip) {
  for (double tissue : {0.0, 2e3, 5e4})
    for (double phi_deg : {0.0, 25.0, 60.0})
      for (double angle_deg : {1.0, 15.0, 30.0, 45.0}) {
        const CompliantNeedleHinge needle = paper_needle(tissue);
        const double b = flux_density_for_turning_angle_t(needle, angle_deg * deg, paper_gap_area_m2, phi_deg * deg);
        const double back = turning_angle_for_flux_density_rad(needle, b, paper_gap_area_m2, phi_deg * deg);
        EXPECT_NEAR(back / (angle_deg * deg), 1.0, 1e-12) << tissue << " " << phi_deg << " " << angle_deg;
      }
}

TEST(CompliantNeedle, TurningAngleBalancesTheMoments) {
  // Eq. 2.5-2.6 directly: F cos(phi) (L + l)/2 - M_t(theta) - K theta = 0, with the tissue moment
  // of Eq. 2.4 integrated numerically from its triangular load mu_t theta s on s in [0, l/2 + L].
  const CompliantNeedleHinge needle = paper_needle(3e4);
  const double force = 0.7, phi = 20.0 * deg;
  const double theta = turning_angle_rad(needle, force, phi);
  const double lever = 0.5 * needle.neck_length_m + needle.head_length_m;
  const int steps = 1000;
  double tissue_moment = 0.0;
  for (int i = 0; i < steps; ++i) {  // midpoint rule is exact for the quadratic s * (mu theta s)
    const double s = (i + 0.5) * lever / steps;
    tissue_moment += needle.tissue_spring_constant_n_per_m2 * theta * s * s * lever / steps;
  }
  const double residual = force * std::cos(phi) * 0.5 * (needle.head_length_m + needle.neck_length_m) -
                          tissue_moment - needle.hinge_stiffness_n_m_per_rad() * theta;
  EXPECT_NEAR(residual, 0.0, 1e-8 * force * lever);
  EXPECT_GT(tissue_moment, 0.0);
}

TEST(CompliantNeedle, RejectsPullsThatCannotTurnTheHead) {
  EXPECT_THROW(flux_density_for_turning_angle_t(paper_needle(), 10.0 * deg, paper_gap_area_m2, 90.0 * deg),
               std::domain_error);
  EXPECT_THROW(flux_density_for_turning_angle_t(paper_needle(), -1.0 * deg, paper_gap_area_m2, 0.0),
               std::domain_error);
  CompliantNeedleHinge broken = paper_needle();
  broken.neck_diameter_m = 0.0;
  EXPECT_THROW(turning_angle_rad(broken, 1.0, 0.0), std::invalid_argument);
}

nlohmann::json run_magnet_command(const std::string& arguments) {
  const std::string command = std::string(NEEDLEFEM_EXE_PATH) + " magnet " + arguments;
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  EXPECT_EQ(pclose(pipe), 0) << command;
  return nlohmann::json::parse(output);
}

TEST(MagnetCommand, PrintsTheWorkedExampleAsJson) {
  const auto out = run_magnet_command("--turning-angle-deg 15 30");
  ASSERT_EQ(out["results"].size(), 2u);
  EXPECT_NEAR(out["results"][0]["flux_density_t"].get<double>(), 0.0391302205, 1e-6);
  EXPECT_NEAR(out["results"][1]["flux_density_t"].get<double>(), 0.0553384885, 1e-6);
  // The distance printed puts the default magnet's Eq. 2.3 field at that flux density.
  const BlockMagnet magnet{out["magnet"]["residual_flux_density_t"], 0.05, 0.06,
                           1e-3 * out["magnet"]["thickness_mm"].get<double>(), out["magnet"]["correction_factor"]};
  const double distance = 1e-3 * out["results"][0]["distance_mm"].get<double>();
  EXPECT_NEAR(axial_flux_density_t(magnet, distance), 0.0391302205, 1e-6);
  EXPECT_NEAR(out["results"][0]["force_n"].get<double>(), gap_force_n(0.0391302205, paper_gap_area_m2), 1e-5);
}

TEST(MagnetCommand, RunsTheWorkedExampleWithoutArguments) {
  const auto out = run_magnet_command("");
  ASSERT_EQ(out["results"].size(), 2u);
  EXPECT_EQ(out["results"][0]["turning_angle_deg"].get<double>(), 15.0);
  EXPECT_EQ(out["results"][1]["turning_angle_deg"].get<double>(), 30.0);
  EXPECT_NEAR(out["results"][0]["flux_density_t"].get<double>(), 0.0391302205, 1e-6);
  EXPECT_NEAR(out["results"][1]["flux_density_t"].get<double>(), 0.0553384885, 1e-6);
}

TEST(MagnetCommand, DistanceGivesTheAngleBack) {
  const auto by_angle = run_magnet_command("--turning-angle-deg 20 --tissue-spring-constant-pa 1000");
  const double distance_mm = by_angle["results"][0]["distance_mm"];
  const auto by_distance =
      run_magnet_command("--distance-mm " + std::to_string(distance_mm) + " --tissue-spring-constant-pa 1000");
  EXPECT_NEAR(by_distance["results"][0]["turning_angle_deg"].get<double>(), 20.0, 1e-4);
}

}  // namespace
}  // namespace needlefem::steering
