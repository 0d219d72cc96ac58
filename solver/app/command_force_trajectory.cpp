// `needlefem force-trajectory CASE.toml [--out DIR]`: paper 000's insertion force (Eq. 3.2;
// insertion_force/force_trajectory.hpp) from the elastic energy of a brain-tip mechanics run,
// written as DIR/<case>.h5 in the replay trajectory format (`needlefem replay` streams it) with
// DIR/<case>.json (rupture point, fracture force, the energy fit and its range).
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "case/case.hpp"
#include "insertion_force/deformation_energy.hpp"
#include "insertion_force/force_trajectory.hpp"

namespace needlefem::app {

namespace {

insertion::InsertionForceParameters parameters_from_case(const Case& input) {
  if (!input.has("insertion_force.rupture_force_n"))
    throw input.error("insertion_force.rupture_force_n", "needed: the tissue rupture force ending the deformation stage");
  insertion::InsertionForceParameters p;
  p.needle_radius_m = input.real("needle.radius_mm") * 1e-3;
  p.fracture_toughness_j_per_m2 = input.real("insertion_force.fracture_toughness_j_per_m2");
  p.rupture_force_n = input.real("insertion_force.rupture_force_n");
  p.shaft_friction_n_per_m = input.real("insertion_force.shaft_friction_n_per_mm") * 1e3;
  p.insertion_speed_m_per_s = input.real("motion.insertion_speed_mm_per_s") * 1e-3;
  p.travel_m = input.real("insertion_force.travel_mm") * 1e-3;
  p.sample_interval_s = input.real("insertion_force.sample_interval_s");
  return p;
}

void run_force_trajectory(const CaseOptions& options) {
  const Case input = Case::load(options.case_file, options.overrides);
  const std::filesystem::path history = input.path("insertion_force.energy_history");
  if (history.empty())
    throw input.error("insertion_force.energy_history",
                      "needed: history.csv of a `needlefem run` of the brain-tip scene (its elastic energy)");
  const insertion::InsertionForceParameters parameters = parameters_from_case(input);
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
      {"rupture_extrapolates_energy_by", result.rupture_displacement_m / energy.largest_sample_m},
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
                   "optional shaft friction; [insertion_force] keys) as a replay trajectory OUT/CASE.h5 + OUT/CASE.json",
                   "out/force_trajectory", run_force_trajectory);
}

}  // namespace needlefem::app
