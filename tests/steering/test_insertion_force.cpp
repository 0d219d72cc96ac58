// Paper 000's insertion-force trajectory (insertion_force/) against hand-computed stages, from a
// synthetic linear-elastic energy history U = c x^2 (so F_def = 2 c x, x(F) = F / (2 c)).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "insertion_force/deformation_energy.hpp"
#include "insertion_force/force_trajectory.hpp"
#include "replay/trajectory.hpp"

namespace needlefem::insertion {
namespace {

constexpr double c = 10.0;  // J/m^2: a 20 N/m tissue response, as the tied compliant brain-tip run gives

// history.csv + summary.json of a fake `needlefem run` at 2 mm/s with U = c x^2 (and a column
// the reader must skip).
std::filesystem::path write_history(const std::string& name) {
  const auto folder = std::filesystem::temp_directory_path() / ("needlefem_insertion_" + name);
  std::filesystem::create_directories(folder);
  std::ofstream csv(folder / "history.csv");
  csv << "time_s,steps,elastic_energy_j\n";
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.01 * k, x = 2e-3 * t;
    csv << t << "," << k << "," << c * x * x << "\n";
  }
  std::ofstream(folder / "summary.json") << R"({"case": {"motion": {"insertion_speed_mm_per_s": 2.0}}})";
  return folder / "history.csv";
}

InsertionForceParameters parameters() {
  InsertionForceParameters p;
  p.needle_radius_m = 0.5e-3;
  p.fracture_toughness_j_per_m2 = 10.0;  // F_c = 2 pi 10 0.5e-3 = 0.0314159 N
  p.rupture_force_n = 0.04;              // x_r = 0.04 / 20 = 2 mm
  p.insertion_speed_m_per_s = 1e-3;
  p.travel_m = 5e-3;
  p.sample_interval_s = 0.01;
  return p;
}

TEST(InsertionForce, HistoryFitRecoversTheQuadraticEnergy) {
  const EnergySamples samples = read_energy_history(write_history("fit"));
  ASSERT_EQ(samples.displacement_m.size(), 11u);
  EXPECT_DOUBLE_EQ(samples.insertion_speed_m_per_s, 2e-3);
  EXPECT_EQ(samples.contact_mode, "tied") << "a run that echoes no contact table was tied";
  EXPECT_NEAR(samples.displacement_m.back(), 0.2e-3, 1e-15);
  const DeformationEnergy fit = fit_deformation_energy(samples);
  EXPECT_NEAR(fit.exponent, 2.0, 1e-9);
  EXPECT_NEAR(fit.coefficient, c, 1e-6 * c);
  EXPECT_NEAR(fit.largest_sample_m, 0.2e-3, 1e-15);
  EXPECT_NEAR(fit.force_n(1e-3), 2 * c * 1e-3, 1e-9);
  EXPECT_NEAR(fit.displacement_at_force_m(0.02), 1e-3, 1e-12);
}

TEST(InsertionForce, StagesMatchHandComputedValues) {
  const DeformationEnergy energy = fit_deformation_energy(read_energy_history(write_history("stages")));
  const InsertionForceParameters p = parameters();
  const InsertionForceTrajectory r = insertion_force_trajectory(energy, p);
  const double fracture = 2.0 * std::numbers::pi * 10.0 * 0.5e-3;
  EXPECT_NEAR(r.fracture_force_n, fracture, 1e-15);
  ASSERT_TRUE(r.ruptured);
  EXPECT_NEAR(r.rupture_displacement_m, 0.04 / (2 * c), 1e-9);
  EXPECT_NEAR(r.rupture_time_s, 2.0, 1e-6);
  EXPECT_NEAR(r.steady_deformation_m, fracture / (2 * c), 1e-9);

  const auto& t = r.trajectory;
  double peak = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double force = -t.force_n[i][2], x = t.position_m[i][2];
    peak = std::max(peak, force);
    if (i > 0) {
      EXPECT_GT(t.time_s[i], t.time_s[i - 1]);
      EXPECT_GT(x, t.position_m[i - 1][2]) << "pose must advance monotonically";
    }
    EXPECT_NEAR(x, 1e-3 * t.time_s[i], 1e-15);
    if (r.stage[i] == static_cast<int>(Stage::deformation)) {
      EXPECT_NEAR(force, 2 * c * x, 1e-9) << "deformation stage at x = " << x;
      EXPECT_EQ(r.crack_length_m[i], 0.0);
    } else {
      EXPECT_NEAR(force, fracture, 1e-12) << "steady penetration at x = " << x;
      EXPECT_NEAR(r.crack_length_m[i], x - fracture / (2 * c), 1e-9);
    }
  }
  EXPECT_NEAR(peak, 0.04, 1e-9) << "the rupture instant is sampled: the peak is F_r";
  EXPECT_EQ(r.stage.front(), static_cast<int>(Stage::deformation));
  EXPECT_EQ(r.stage.back(), static_cast<int>(Stage::penetration));
  EXPECT_NEAR(t.time_s.back(), 5.0, 1e-12);
}

TEST(InsertionForce, ShaftFrictionAddsLinearlyInTheCrackLength) {
  const DeformationEnergy energy = fit_deformation_energy(read_energy_history(write_history("friction")));
  InsertionForceParameters p = parameters();
  p.shaft_friction_n_per_m = 3.0;
  const InsertionForceTrajectory r = insertion_force_trajectory(energy, p);
  const double l = 5e-3 - r.steady_deformation_m;
  EXPECT_NEAR(-r.trajectory.force_n.back()[2], p.fracture_force_n() + 3.0 * l, 1e-12);
}

TEST(InsertionForce, RoundTripsThroughTheReplayFormat) {
  const DeformationEnergy energy = fit_deformation_energy(read_energy_history(write_history("file")));
  const InsertionForceTrajectory r = insertion_force_trajectory(energy, parameters());
  const auto file = std::filesystem::temp_directory_path() / "needlefem_insertion_trajectory.h5";
  replay::write_trajectory(file, r.trajectory);
  append_insertion_datasets(file, r);
  const replay::Trajectory back = replay::read_trajectory(file);
  ASSERT_EQ(back.size(), r.trajectory.size());
  EXPECT_EQ(back.force_n[100][2], r.trajectory.force_n[100][2]);
}

TEST(InsertionForce, RuptureBelowTheFractureForceIsRejected) {
  const DeformationEnergy energy = fit_deformation_energy(read_energy_history(write_history("reject")));
  InsertionForceParameters p = parameters();
  p.rupture_force_n = 0.03;
  EXPECT_THROW(insertion_force_trajectory(energy, p), std::invalid_argument);
}

TEST(InsertionForce, MissingSummaryNamesTheFile) {
  const auto folder = std::filesystem::temp_directory_path() / "needlefem_insertion_nosummary";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "history.csv") << "time_s,elastic_energy_j\n0,0\n";
  std::filesystem::remove(folder / "summary.json");
  try {
    read_energy_history(folder / "history.csv");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("summary.json: cannot open"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace needlefem::insertion
