// `needlefem force-trajectory CASE.toml [--out DIR]`: paper 000's insertion force (Eq. 3.2;
// insertion_force/force_trajectory.hpp) from the elastic energy of a brain-tip mechanics run,
// written as DIR/<case>.h5 in the replay trajectory format (`needlefem replay` streams it) with
// DIR/<case>.json (rupture point, fracture force, the energy fit and energy_extrapolated_by: the
// deformation stage's end over the run's last sample).
// A missing energy history stops with the command that makes it (insertion_force.energy_case); a
// deformation stage beyond insertion_force.extrapolation_warn_factor times the run's last sample
// is warned about on stderr, beyond insertion_force.extrapolation_limit_factor refused.
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "case/case.hpp"
#include "case/specs/insertion_force_spec.hpp"
#include "case/specs/needle_tip_spec.hpp"
#include "insertion_force/deformation_energy.hpp"
#include "insertion_force/force_trajectory.hpp"

namespace needlefem::app {

namespace {

insertion::InsertionForceParameters parameters_from_spec(const Case& input, const InsertionForceSpec& spec) {
  if (!spec.rupture_force_n)
    throw input.error("insertion_force.rupture_force_n", "needed: the tissue rupture force ending the deformation stage");
  insertion::InsertionForceParameters p;
  p.needle_radius_m = parse_needle_tip_spec(input).radius_mm * 1e-3;
  p.fracture_toughness_j_per_m2 = spec.fracture_toughness_j_per_m2;
  p.rupture_force_n = *spec.rupture_force_n;
  p.shaft_friction_n_per_m = spec.shaft_friction_n_per_mm * 1e3;
  p.insertion_speed_m_per_s = spec.insertion_speed_mm_per_s * 1e-3;
  p.travel_m = spec.travel_mm * 1e-3;
  p.sample_interval_s = spec.sample_interval_s;
  return p;
}

// A path as the user can type it here: relative to the working directory when inside it.
std::string typed(const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::path relative = std::filesystem::relative(path, error);
  if (!error && !relative.empty() && *relative.begin() != "..") return relative.string();
  return std::filesystem::weakly_canonical(path, error).string();
}

// The energy history must exist; if not, the error names the run that makes it.
void require_energy_history(const Case& input, const InsertionForceSpec& spec) {
  const std::filesystem::path& history = spec.energy_history;
  if (std::filesystem::exists(history)) return;
  const std::filesystem::path& run_case = spec.energy_case;
  if (run_case.empty())
    throw input.error("insertion_force.energy_history",
                      fmt::format("{} does not exist; make it with `needlefem run CASE --out {}` of a brain-tip case "
                                  "(insertion_force.energy_case names it)", typed(history),
                                  typed(history.parent_path())));
  if (!std::filesystem::is_regular_file(run_case))
    throw input.error("insertion_force.energy_case", fmt::format("{}: no such case file", typed(run_case)));
  throw input.error("insertion_force.energy_history",
                    fmt::format("{} does not exist; make it first: {} run {} --out {}", typed(history),
                                typed(std::filesystem::read_symlink("/proc/self/exe")), typed(run_case),
                                typed(history.parent_path())));
}

// How many times over the deformation stage extrapolates the energy run: warned or refused.
double energy_extrapolation(const Case& input, const InsertionForceSpec& spec,
                            const insertion::InsertionForceTrajectory& result,
                            const insertion::InsertionForceParameters& parameters,
                            const insertion::DeformationEnergy& energy) {
  const double stage_end_m = result.ruptured ? result.rupture_displacement_m : parameters.travel_m;
  const double factor = stage_end_m / energy.largest_sample_m;
  const std::string reach =
      fmt::format("the deformation stage runs to x = {:.3g} mm, {:.3g} times the energy run's last sample ({:.3g} mm)",
                  stage_end_m * 1e3, factor, energy.largest_sample_m * 1e3);
  const double limit = spec.extrapolation_limit_factor;
  const double warn = spec.extrapolation_warn_factor;
  if (factor > limit)
    throw input.error("insertion_force.extrapolation_limit_factor",
                      fmt::format("{}, more than {:g} times: sample it with a longer run (motion.duration_s of the "
                                  "energy case) or raise this factor", reach, limit));
  if (factor > warn)
    fmt::print(stderr, "force-trajectory: warning: {}: the force there is the power-law fit's extrapolation "
               "(insertion_force.extrapolation_warn_factor = {:g})\n", reach, warn);
  return factor;
}

void run_force_trajectory(const CaseOptions& options) {
  const Case input = Case::load(options.case_file, options.overrides);
  const InsertionForceSpec spec = parse_insertion_force_spec(input);
  const std::filesystem::path& history = spec.energy_history;
  if (history.empty())
    throw input.error("insertion_force.energy_history",
                      "needed: history.csv of a `needlefem run` of the brain-tip scene (its elastic energy)");
  const insertion::InsertionForceParameters parameters = parameters_from_spec(input, spec);
  require_energy_history(input, spec);
  insertion::EnergySamples samples;
  insertion::DeformationEnergy energy;
  try {
    samples = insertion::read_energy_history(history);
    energy = insertion::fit_deformation_energy(samples);
  } catch (const std::runtime_error& e) {
    throw input.error("insertion_force.energy_history", e.what());
  }
  insertion::InsertionForceTrajectory result;
  try {
    result = insertion::insertion_force_trajectory(energy, parameters);
  } catch (const std::invalid_argument& e) {
    // The schema keeps every other parameter positive: only F_r <= 2 pi J_c r is left to reject.
    throw input.error("insertion_force.rupture_force_n", e.what());
  }
  const double extrapolation = energy_extrapolation(input, spec, result, parameters, energy);
  result.trajectory.source_case = input.to_toml();

  const std::filesystem::path out(options.out_dir);
  std::filesystem::create_directories(out);
  const std::string stem = std::filesystem::path(options.case_file).stem().string();
  const std::filesystem::path h5 = out / (stem + ".h5");
  replay::write_trajectory(h5, result.trajectory);
  insertion::append_insertion_datasets(h5, result);

  const double steady_force = -result.trajectory.force_n.back()[2];
  nlohmann::json json = {
      {"trajectory_file", h5.string()},
      {"energy_source", history.string()},
      {"energy_source_contact_mode", samples.contact_mode},
      {"energy_fit", {{"coefficient_j_per_m_pow_p", energy.coefficient},
                      {"exponent_p", energy.exponent},
                      {"largest_sample_mm", energy.largest_sample_m * 1e3},
                      {"max_relative_error", energy.max_relative_fit_error}}},
      {"ruptured", result.ruptured},
      {"rupture_force_n", parameters.rupture_force_n},
      {"rupture_displacement_mm", result.rupture_displacement_m * 1e3},
      {"rupture_time_s", result.rupture_time_s},
      {"energy_extrapolated_by", extrapolation},
      {"fracture_force_n", result.fracture_force_n},
      {"steady_deformation_mm", result.steady_deformation_m * 1e3},
      {"crack_jump_at_rupture_mm", (result.rupture_displacement_m - result.steady_deformation_m) * 1e3},
      {"final_force_n", steady_force},
      {"final_crack_length_mm", result.crack_length_m.back() * 1e3},
      {"samples", result.trajectory.size()},
      {"duration_s", result.trajectory.duration_s()}};
  fmt::print("{}\n", json.dump(2));
  json["case"] = input.to_json();
  std::ofstream(out / (stem + ".json")) << json.dump(2) << '\n';
}

}  // namespace

void add_force_trajectory_command(CLI::App& app) {
  add_case_command(app, "force-trajectory",
                   "Paper 000's insertion force (Eq. 3.2: deformation energy of a brain-tip run, rupture, fracture 2 pi J_c r,\n"
                   "optional shaft friction; [insertion_force] keys) as a replay trajectory OUT/CASE.h5 + OUT/CASE.json.\n"
                   "While the energy run's history.csv is missing it stops with the command that makes it; a deformation\n"
                   "stage beyond insertion_force.extrapolation_warn_factor times the energy run's travel is warned about,\n"
                   "beyond insertion_force.extrapolation_limit_factor times it refused",
                   "out/force_trajectory", run_force_trajectory);
}

}  // namespace needlefem::app
