// `needlefem prbm-check CASE.toml [--out DIR] [-- PETSc options]`: paper 000's pseudo-rigid-body
// turning angle (Eq. 2.7) against a large-rotation 3-D FEM of the compliant tip
// (prbm_check/prbm_check.hpp). Writes DIR/<case>.json (the table, stiffnesses, levers, mesh,
// timings, the resolved case) and prints the table.
#include <filesystem>
#include <fstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "case/case.hpp"
#include "integration/petsc_session.hpp"
#include "prbm_check/prbm_check.hpp"

namespace needlefem::app {

namespace {

nlohmann::json up_to_or_null(double degrees) { return degrees > 0.0 ? nlohmann::json(degrees) : nlohmann::json(); }

nlohmann::json to_json(const prbm::PrbmCheckResult& r) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& row : r.rows)
    rows.push_back({{"force_n", row.force_n},
                    {"prbm_deg", row.prbm_deg},
                    {"prbm_with_fem_load_lever_deg", row.prbm_load_lever_deg},
                    {"fem_follower_deg", row.fem_follower_deg},
                    {"fem_dead_deg", row.fem_dead_deg},
                    {"fem_linear_deg", row.fem_linear_deg},
                    {"error_vs_follower_percent", row.error_percent()},
                    {"error_vs_dead_percent", row.dead_error_percent()},
                    {"geometric_nonlinearity_follower_percent",
                     100.0 * (row.fem_follower_deg - row.fem_linear_deg) / row.fem_linear_deg},
                    {"geometric_nonlinearity_dead_percent",
                     100.0 * (row.fem_dead_deg - row.fem_linear_deg) / row.fem_linear_deg},
                    {"newton_iterations_follower", row.follower_newton},
                    {"newton_iterations_dead", row.dead_newton},
                    {"max_corotated_strain", row.max_corotated_strain}});
  return {{"rows", rows},
          {"youngs_modulus_pa", r.youngs_modulus_pa},
          {"poisson_ratio", r.poisson_ratio},
          {"prbm_hinge_stiffness_n_m_per_rad", r.hinge_stiffness_n_m_per_rad},
          {"fem_hinge_stiffness_n_m_per_rad", r.fem_stiffness_n_m_per_rad},
          {"prbm_lever_mm", r.prbm_lever_m * 1e3},
          {"fem_load_lever_mm", r.fem_load_lever_m * 1e3},
          {"tolerance_percent", r.tolerance_percent},
          // null: even the smallest tabulated angle is off by more than the tolerance.
          {"prbm_accurate_up_to_deg_follower", up_to_or_null(r.accurate_up_to_deg)},
          {"prbm_accurate_up_to_deg_dead", up_to_or_null(r.dead_accurate_up_to_deg)},
          {"prbm_accuracy_follower", prbm::accuracy_text(r, false)},
          {"prbm_accuracy_dead", prbm::accuracy_text(r, true)},
          {"mesh", {{"nodes", r.nodes}, {"tets", r.elements}, {"dofs", r.dofs}, {"element_mm", r.element_mm},
                    {"neck_element_mm", r.neck_element_mm}}},
          {"seconds", {{"mesh", r.mesh_seconds}, {"solve", r.solve_seconds}, {"linear_solves", r.linear_solve_seconds}}}};
}

void print_table(const prbm::PrbmCheckResult& r) {
  fmt::print("PRBM (Eq. 2.7) vs 3-D FEM of the compliant tip: E = {:.4g} GPa, nu = {}, K = EI/l = {:.5g} N m/rad "
             "(FEM, small load: {:.5g}), lever {:.4g} mm (FEM load: {:.4g} mm)\n",
             r.youngs_modulus_pa * 1e-9, r.poisson_ratio, r.hinge_stiffness_n_m_per_rad, r.fem_stiffness_n_m_per_rad,
             r.prbm_lever_m * 1e3, r.fem_load_lever_m * 1e3);
  fmt::print("{:>10} {:>9} {:>12} {:>9} {:>9} {:>10} {:>9} {:>13} {:>8}\n", "load N", "PRBM deg", "FEM foll deg",
             "err %", "FEM dead", "err dead %", "FEM lin", "PRBM FEM lever", "strain");
  for (const auto& row : r.rows)
    fmt::print("{:>10.4g} {:>9.3f} {:>12.3f} {:>9.2f} {:>9.3f} {:>10.2f} {:>9.3f} {:>13.3f} {:>8.4f}\n", row.force_n,
               row.prbm_deg, row.fem_follower_deg, row.error_percent(), row.fem_dead_deg, row.dead_error_percent(),
               row.fem_linear_deg, row.prbm_load_lever_deg, row.max_corotated_strain);
  fmt::print("PRBM against the FEM: follower load {}; dead load {}; {} tets, {} dofs, {:.1f} s\n",
             prbm::accuracy_text(r, false), prbm::accuracy_text(r, true), r.elements, r.dofs,
             r.mesh_seconds + r.solve_seconds);
}

void run_prbm_check(const CaseOptions& options) {
  const Case input = Case::load(options.case_file, options.overrides);
  const PetscSession petsc(backend_options());
  const prbm::PrbmCheckResult result = prbm::run_prbm_check(input);
  const std::filesystem::path out(options.out_dir);
  std::filesystem::create_directories(out);
  const std::filesystem::path json_file = out / (std::filesystem::path(options.case_file).stem().string() + ".json");
  nlohmann::json json = to_json(result);
  json["case"] = input.to_json();
  std::ofstream(json_file) << json.dump(2) << '\n';
  print_table(result);
  fmt::print("wrote {}\n", json_file.string());
}

}  // namespace

void add_prbm_check_command(CLI::App& app) {
  add_case_command(app, "prbm-check",
                   "Paper 000's pseudo-rigid-body hinge angle (Eq. 2.7) against a large-rotation 3-D FEM of the compliant tip\n"
                   "([prbm_check] keys; E from steering.neck_youngs_modulus_gpa), the tip meshed alone and clamped under follower\n"
                   "and dead head loads: angle table, hinge stiffness, neck strain, and up to which angle the PRBM stays\n"
                   "within prbm_check.tolerance_percent, as JSON",
                   "out/prbm_check", run_prbm_check);
}

}  // namespace needlefem::app
