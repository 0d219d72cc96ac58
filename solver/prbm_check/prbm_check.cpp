// PRBM-vs-FEM sweep of the compliant needle; see prbm_check.hpp.
#include "prbm_check/prbm_check.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "case/specs/prbm_check_spec.hpp"
#include "geometry/needle_tip.hpp"
#include "prbm_check/tip_mesh.hpp"
#include "prbm_check/tip_statics.hpp"
#include "steering/hinge.hpp"
#include "wall_clock/seconds_since.hpp"

namespace needlefem::prbm {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// Largest angle of the (ascending) rows before the first whose |error| reaches the tolerance.
template <class Error>
double accurate_up_to(const std::vector<PrbmCheckRow>& rows, double tolerance, Error error) {
  double reached = 0.0;
  for (const auto& row : rows) {
    if (!(std::abs(error(row)) < tolerance)) break;
    reached = row.prbm_deg;
  }
  return reached;
}

}  // namespace

PrbmCheckResult run_prbm_check(const Case& input) {
  const NeedleTip needle = needle_tip_from_spec(parse_needle_tip_spec(input));
  if (needle.kind != NeedleTip::Kind::Compliant)
    throw input.error("needle.kind", "prbm-check needs the compliant (hinged) needle: set \"compliant\"");
  const PrbmCheckSpec spec = parse_prbm_check_spec(input);
  std::vector<double> angles = spec.angles_deg;
  if (angles.empty()) throw input.error("prbm_check.angles_deg", "needs at least one angle");
  std::sort(angles.begin(), angles.end());
  const CompliantTip& tip = needle.compliant;

  PrbmCheckResult result;
  result.youngs_modulus_pa = spec.neck_youngs_modulus_gpa * 1e9;
  result.poisson_ratio = spec.poisson_ratio;
  if (!(result.poisson_ratio < 0.5))
    throw input.error("prbm_check.poisson_ratio", "must be below 0.5 (the co-rotational law's lambda is infinite there)");
  result.tolerance_percent = spec.tolerance_percent;
  result.element_mm = spec.element_mm;
  result.neck_element_mm = spec.neck_element_mm;
  // In air (mu_t = 0) and with the pull normal to the head (phi = 0), as the FEM is loaded.
  const steering::CompliantNeedleHinge hinge{tip.neck_length, tip.neck_diameter, tip.head_length,
                                             result.youngs_modulus_pa, 0.0};
  result.hinge_stiffness_n_m_per_rad = hinge.hinge_stiffness_n_m_per_rad();
  result.prbm_lever_m = hinge.lever_arm_m();

  auto start = WallClock::now();
  TetMesh mesh = mesh_compliant_tip(tip, {result.element_mm * 1e-3, result.neck_element_mm * 1e-3});
  result.mesh_seconds = seconds_since(start);
  result.nodes = mesh.nodes.size();

  start = WallClock::now();
  CompliantTipStatics fem(tip, std::move(mesh), result.youngs_modulus_pa, result.poisson_ratio);
  result.elements = fem.elements();
  result.dofs = fem.dofs();
  result.fem_load_lever_m = fem.load_lever_m();
  const double linear_slope = fem.linear_rotation_per_newton();
  result.fem_stiffness_n_m_per_rad = result.fem_load_lever_m / linear_slope;

  for (double angle : angles) {
    PrbmCheckRow row;
    // The load for which Eq. 2.7 gives `angle`.
    row.force_n = angle / kDegPerRad * result.hinge_stiffness_n_m_per_rad / result.prbm_lever_m;
    row.prbm_deg = steering::turning_angle_rad(hinge, row.force_n, 0.0) * kDegPerRad;
    row.prbm_load_lever_deg = row.force_n * result.fem_load_lever_m / result.hinge_stiffness_n_m_per_rad * kDegPerRad;
    row.fem_linear_deg = row.force_n * linear_slope * kDegPerRad;
    result.rows.push_back(row);
  }
  // Two continuation passes, one per load kind, each from rest through the ascending loads.
  for (const LoadKind kind : {LoadKind::follower, LoadKind::dead}) {
    fem.reset();
    for (auto& row : result.rows) {
      const TipSolution solution = fem.solve(row.force_n, kind);
      if (kind == LoadKind::follower) {
        row.fem_follower_deg = solution.head_rotation_rad * kDegPerRad;
        row.follower_newton = solution.newton_iterations;
        row.max_corotated_strain = fem.max_corotated_strain();
      } else {
        row.fem_dead_deg = solution.head_rotation_rad * kDegPerRad;
        row.dead_newton = solution.newton_iterations;
      }
    }
  }
  result.solve_seconds = seconds_since(start);
  result.linear_solve_seconds = fem.seconds_in_linear_solves();
  result.accurate_up_to_deg = accurate_up_to(result.rows, result.tolerance_percent,
                                             [](const PrbmCheckRow& r) { return r.error_percent(); });
  result.dead_accurate_up_to_deg = accurate_up_to(result.rows, result.tolerance_percent,
                                                  [](const PrbmCheckRow& r) { return r.dead_error_percent(); });
  return result;
}

std::string accuracy_text(const PrbmCheckResult& result, bool dead_load) {
  const double up_to = dead_load ? result.dead_accurate_up_to_deg : result.accurate_up_to_deg;
  if (up_to > 0.0 || result.rows.empty())
    return fmt::format("within {:g} % up to {:.4g} deg", result.tolerance_percent, up_to);
  const auto error = [dead_load](const PrbmCheckRow& row) {
    return dead_load ? row.dead_error_percent() : row.error_percent();
  };
  std::vector<std::string> within;
  for (const PrbmCheckRow& row : result.rows)
    if (std::abs(error(row)) < result.tolerance_percent) within.push_back(fmt::format("{:.4g}", row.prbm_deg));
  const PrbmCheckRow& first = result.rows.front();
  return fmt::format("off by more than {:g} % already at the smallest angle, {:.4g} deg ({:+.3g} %){}",
                     result.tolerance_percent, first.prbm_deg, error(first),
                     within.empty() ? std::string("; at every angle")
                                    : fmt::format("; within it only at {} deg", fmt::join(within, ", ")));
}

}  // namespace needlefem::prbm
