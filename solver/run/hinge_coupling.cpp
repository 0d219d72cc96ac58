// Equations: hinge_coupling.hpp.
#include "run/hinge_coupling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "case/case_error.hpp"
#include "integration/petsc_session.hpp"
#include "output/xdmf_text.hpp"
#include "physics/contact/hinged_needle.hpp"
#include "run/output_schedule.hpp"
#include "steering/steering_case.hpp"

namespace needlefem::run {

namespace {

// The passes stop once every output time's tilt is within this fraction of the largest turning
// angle (Eq. 2.7 in air) of its moment balance, or within kSmallestTiltTolerance. Why relative: a
// pass's contact moment repeats only to the integration's own accuracy (its steps differ from pass
// to pass; measured on the 0.4 mm mesh at 15 deg, the second pass was 0.014 deg, 0.09 %, off), and
// 0.1 % of the angle is an order below the tissue's effect on it and two below the hinge model's.
constexpr double kRelativeTiltTolerance = 1e-3;
constexpr double kSmallestTiltTolerance = 1e-5;  // rad
constexpr int kMaxPasses = 6;
// The magnet may turn the head by at most this at the first output time, before the tissue is
// loaded: the cavity was meshed around the untilted needle.
constexpr double kLargestStartTilt = 1e-3;  // rad
constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kMmPerM = 1e3;

using Tilt = std::array<double, 2>;

// The magnet at one output time.
struct Pull {
  double distance_m = 0.0, flux_density_t = 0.0, force_n = 0.0;
  double moment_n_m = 0.0;  // F cos φ (L + l)/2: M_magnet's length
  Tilt axis{0.0, 1.0};      // e_z × e: the direction of M_magnet, and of the tilt it gives
  double eq27_case_rad = 0.0;  // Eq. 2.7 with the case's tissue term
};

Pull pull_at(const steering::SteeringSetup& setup, double t) {
  Pull pull;
  if (setup.schedule.empty()) return pull;
  const double depth = setup.run.insertion_speed_m_per_s * t;
  pull.distance_m = setup.schedule.distance_at(depth);
  steering::SteeringModel::HeadLoad load;
  try {
    load = setup.model.head_load(pull.distance_m);
  } catch (const std::domain_error& e) {
    throw case_error(setup.origin, "steering.magnet_distance_mm", e.what());
  }
  const double azimuth = setup.schedule.azimuth_at(depth);
  pull.flux_density_t = load.flux_density_t;
  pull.force_n = load.force_n;
  pull.moment_n_m = load.force_n * std::cos(setup.model.force_angle_rad) * setup.model.hinge.lever_arm_m();
  pull.axis = {-std::sin(azimuth), std::cos(azimuth)};
  pull.eq27_case_rad = load.turning_angle_rad;
  return pull;
}

double length(const Tilt& v) { return std::hypot(v[0], v[1]); }

// The next pass's tilts from this pass's tilts θ and contact moments: the balance with the tissue's
// fitted rotational stiffness k moved to the left, θ' = (M_magnet + M_contact + k θ)/(K + k).
std::vector<Tilt> next_tilts(const std::vector<Pull>& pulls, const std::vector<Tilt>& tilts,
                             const std::vector<Tilt>& contact_moments, double stiffness, double tissue_stiffness) {
  std::vector<Tilt> out(pulls.size());
  for (std::size_t i = 0; i < pulls.size(); ++i)
    for (int k = 0; k < 2; ++k)
      out[i][k] = (pulls[i].moment_n_m * pulls[i].axis[k] + contact_moments[i][k] + tissue_stiffness * tilts[i][k]) /
                  (stiffness + tissue_stiffness);
  return out;
}

// How far a pass's tilt is from its balance, per output time: |(M_magnet + M_contact)/K - θ|.
std::vector<double> imbalance(const std::vector<Pull>& pulls, const std::vector<Tilt>& tilts,
                              const std::vector<Tilt>& contact_moments, double stiffness) {
  std::vector<double> out(pulls.size());
  for (std::size_t i = 0; i < pulls.size(); ++i)
    out[i] = std::hypot((pulls[i].moment_n_m * pulls[i].axis[0] + contact_moments[i][0]) / stiffness - tilts[i][0],
                        (pulls[i].moment_n_m * pulls[i].axis[1] + contact_moments[i][1]) / stiffness - tilts[i][1]);
  return out;
}

std::vector<Tilt> head_moments_of(const std::string& origin, const nlohmann::json& summary, std::size_t count) {
  const auto& moments = summary.at("head").at("moment_n_m");
  if (moments.size() != count)
    throw case_error(origin, "output.interval_s", fmt::format("the run gave the head's moment at {} output times, not {}",
                                                   moments.size(), count));
  std::vector<Tilt> out;
  for (const auto& m : moments) out.push_back({m.at(0).get<double>(), m.at(1).get<double>()});
  return out;
}

struct Fit {
  double rotational_stiffness = 0.0;  // k = μ_t/3 (l/2 + L)³, N m/rad
  double spring_constant = 0.0;       // μ_t, N/m²
};

// Least squares of the tissue's moment M_t = -M_contact·axis against the angle |θ|: k = Σ M θ / Σ θ².
Fit fit_tissue_term(const std::vector<Pull>& pulls, const std::vector<Tilt>& tilts, const std::vector<Tilt>& moments,
                    double tip_lever_m) {
  double moment_angle = 0.0, angle_squared = 0.0;
  for (std::size_t i = 0; i < pulls.size(); ++i) {
    const double angle = length(tilts[i]);
    const double resisting = -(moments[i][0] * pulls[i].axis[0] + moments[i][1] * pulls[i].axis[1]);
    moment_angle += resisting * angle;
    angle_squared += angle * angle;
  }
  Fit fit;
  if (angle_squared == 0.0) return fit;
  fit.rotational_stiffness = moment_angle / angle_squared;
  fit.spring_constant = 3.0 * fit.rotational_stiffness / std::pow(tip_lever_m, 3);
  return fit;
}

// summary.json's "hinge" and hinge.csv of the last pass (its tilts, contact moments and imbalance).
std::string hinge_outputs(nlohmann::json& summary, const RunOptions& options, const std::vector<double>& times,
                          const std::vector<Pull>& pulls, const std::vector<Tilt>& tilts,
                          const std::vector<Tilt>& moments, const std::vector<double>& residuals, double stiffness,
                          const Fit& fit, int pass, double tolerance) {
  const double residual = *std::max_element(residuals.begin(), residuals.end());
  std::string csv =
      "time_s,magnet_distance_mm,flux_density_t,pull_force_n,head_angle_deg,head_angle_eq27_air_deg,"
      "head_angle_eq27_fitted_deg,magnet_moment_n_m,tissue_moment_n_m,balance_residual_rad\n";
  nlohmann::json angles = nlohmann::json::array(), air = nlohmann::json::array(), flux = nlohmann::json::array();
  double largest = 0.0, largest_air = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Pull& p = pulls[i];
    const double angle = length(tilts[i]), in_air = p.moment_n_m / stiffness;
    const double fitted = p.moment_n_m / (stiffness + fit.rotational_stiffness);
    const double tissue = -(moments[i][0] * p.axis[0] + moments[i][1] * p.axis[1]);
    csv += fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", times[i],
                       p.distance_m * kMmPerM, p.flux_density_t, p.force_n, angle * kDegPerRad, in_air * kDegPerRad,
                       fitted * kDegPerRad, p.moment_n_m, tissue, residuals[i]);
    angles.push_back(angle * kDegPerRad);
    air.push_back(in_air * kDegPerRad);
    flux.push_back(p.flux_density_t);
    largest = std::max(largest, angle);
    largest_air = std::max(largest_air, in_air);
  }
  summary["hinge"] = {
      {"passes", pass},
      {"converged", residual <= tolerance},
      {"balance_residual_rad", residual},
      {"tilt_tolerance_rad", tolerance},
      {"hinge_stiffness_n_m_per_rad", stiffness},
      {"max_head_angle_deg", largest * kDegPerRad},
      {"max_head_angle_eq27_air_deg", largest_air * kDegPerRad},
      {"tissue_rotational_stiffness_n_m_per_rad", fit.rotational_stiffness},
      {"fitted_tissue_spring_constant_n_per_m2", fit.spring_constant},
      {"time_s", times},
      {"head_angle_deg", angles},
      {"head_angle_eq27_air_deg", air},
      {"flux_density_t", flux},
      {"note", "the head's tilt balances the hinge spring K against the magnet's and the tissue's moments about the "
               "pivot at the output times (run/hinge_coupling.hpp); balance_residual_rad: how far the last pass's "
               "tilt was from that balance; fitted_tissue_spring_constant_n_per_m2: mu_t of Eq. 2.4 fitted to the FEM's "
               "tissue moment, for steering.tissue_spring_constant_n_per_m2 of `needlefem steer`"}};
  if (!(residual <= tolerance)) {
    summary["hinge"]["warning"] = fmt::format("the tilt did not reach the moment balance in {} passes (off by {:.3g} deg)",
                                              pass, residual * kDegPerRad);
    if (options.progress) fmt::print(options.progress, "hinge: warning: {}\n", summary["hinge"]["warning"].get<std::string>());
  }
  return csv;
}

}  // namespace

nlohmann::json run_hinged_case(const RunSpecs& specs, const RunOptions& options, const RunPass& run_pass) {
  const steering::SteeringSetup& setup = specs.hinge_steering.value();
  const double stiffness = setup.model.hinge.hinge_stiffness_n_m_per_rad();
  const std::vector<double> times = output_times(specs.output, specs.loading());
  std::vector<Pull> pulls;
  for (double t : times) pulls.push_back(pull_at(setup, t));
  if (pulls.front().eq27_case_rad > kLargestStartTilt)
    throw case_error(setup.origin, "steering.magnet_distance_mm",
                  fmt::format("the magnet turns the head by {:.3g} deg at t = {:.4g} s, before the tissue is loaded; "
                              "start the schedule with the magnet parked far away (e.g. 300 mm)",
                              pulls.front().eq27_case_rad * kDegPerRad, times.front()));
  std::vector<Tilt> tilts;
  for (const Pull& p : pulls) tilts.push_back({p.eq27_case_rad * p.axis[0], p.eq27_case_rad * p.axis[1]});
  double largest_in_air = 0.0;
  for (const Pull& p : pulls) largest_in_air = std::max(largest_in_air, p.moment_n_m / stiffness);
  const double tolerance = std::max(kSmallestTiltTolerance, kRelativeTiltTolerance * largest_in_air);

  const PetscSession petsc(options.petsc_options);  // one for every pass: MPI starts once per process
  nlohmann::json summary;
  std::vector<Tilt> moments;
  std::vector<double> residuals;
  double residual = std::numeric_limits<double>::infinity();
  int pass = 0;
  while (true) {
    ++pass;
    if (options.progress)
      fmt::print(options.progress, "hinge: pass {}: the head's tilt from {}\n", pass,
                 pass == 1 ? "Eq. 2.7 with the case's tissue term" : "the moment balance of the pass before");
    RunOptions pass_options = options;
    pass_options.head_tilt = std::make_shared<contact::HeadTilt>(times, tilts);
    summary = run_pass(specs, pass_options);
    moments = head_moments_of(specs.output.origin, summary, times.size());
    residuals = imbalance(pulls, tilts, moments, stiffness);
    residual = *std::max_element(residuals.begin(), residuals.end());
    if (options.progress)
      fmt::print(options.progress, "hinge: pass {}: the tilt is within {:.3g} deg of the moment balance\n", pass,
                 residual * kDegPerRad);
    if (residual <= tolerance || pass == kMaxPasses) break;
    const Fit fit = fit_tissue_term(pulls, tilts, moments, setup.model.tip_lever_m());
    tilts = next_tilts(pulls, tilts, moments, stiffness, std::max(0.0, fit.rotational_stiffness));
  }

  const Fit fit = fit_tissue_term(pulls, tilts, moments, setup.model.tip_lever_m());
  const std::string csv =
      hinge_outputs(summary, options, times, pulls, tilts, moments, residuals, stiffness, fit, pass, tolerance);
  summary["files"]["hinge"] = "hinge.csv";
  output::replace_files_atomically({{options.out_dir / "hinge.csv", csv},
                                    {options.out_dir / "summary.json", summary.dump(2) + "\n"}});
  return summary;
}

}  // namespace needlefem::run
