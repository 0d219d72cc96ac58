#include "run/needle_output.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <fmt/core.h>

#include "case/case.hpp"
#include "case/specs/contact_spec.hpp"
#include "integration/petsc_arrays.hpp"
#include "physics/mechanics/mechanics_system.hpp"
#include "wall_clock/seconds_since.hpp"

namespace needlefem::run {

namespace {

constexpr double kMmPerM = 1e3;
constexpr double kMm2PerM2 = 1e6;
constexpr double kPaPerGpa = 1e9;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

double largest_magnitude(const std::vector<double>& values) {
  double largest = 0.0;
  for (double v : values) largest = std::max(largest, std::abs(v));
  return largest;
}

}  // namespace

NeedleOutput::NeedleOutput(const NeedleDeflectionCheckSpec& check, const TetMesh& mesh,
                           const mechanics::MechanicsSystem& system, std::shared_ptr<const contact::NeedleContact> contact)
    : system_(system), contact_(std::move(contact)), initial_gap_(contact_->initial_gap()) {
  if (!check.enabled) return;
  if (contact_->hinged_needle())
    throw case_error(check.origin, "needle.deflection_check",
                     "the compliant tip's neck is the hinge spring of its head (run/hinge_coupling.hpp); the check is "
                     "for rigid tips");
  youngs_modulus_pa_ = check.youngs_modulus_gpa * kPaPerGpa;
  poisson_ratio_ = check.poisson_ratio;
  const NeedleMotion& motion = contact_->needle().motion();
  needle_travel_m_ = std::abs(motion.insertion_speed) * motion.elapsed(motion.duration);
  const auto start = WallClock::now();
  try {
    elasticity_ = std::make_unique<contact::NeedleElasticity>(mesh, youngs_modulus_pa_, poisson_ratio_);
  } catch (const std::runtime_error& e) {
    throw case_error(check.origin, "needle.deflection_check", e.what());
  }
  elasticity_seconds_ += seconds_since(start);
  deflection_check_ = true;
  needle_dofs_ = elasticity_->dofs();
  needle_elements_ = elasticity_->elements();
}

std::vector<output::FieldSpec> NeedleOutput::field_specs() {
  using output::FieldCentre, output::FieldType;
  return {{"contact_pressure", FieldCentre::node, FieldType::scalar, "Pa"},
          {"contact_slip", FieldCentre::node, FieldType::scalar, "mm", 1e3}};  // the mesh's unit
}

std::string NeedleOutput::history_header() const {
  return std::string(",needle_force_x_n,needle_force_y_n,needle_force_z_n,needle_moment_x_n_m,needle_moment_y_n_m,"
                     "needle_moment_z_n_m,contact_area_mm2,needle_lateral_force_xi_n,needle_lateral_force_eta_n") +
         (contact_->hinged_needle()
              ? ",head_angle_deg,head_tilt_x_rad,head_tilt_y_rad,head_moment_x_n_m,head_moment_y_n_m"
              : "");
}

void NeedleOutput::evaluate(double t, Vec y, Vec ydot) {
  const ReadArray state(y), rate(ydot);
  load_ = contact_->load_on_needle(t, state.data(), rate.data(), system_.dof_map());
  fields_ = contact_->surface_fields(t, state.data(), system_.dof_map());
  times_.push_back(t);
  axial_force_.push_back(load_.axial_force());
  torque_.push_back(load_.torque());
  // The lateral force in the needle's own frame, turned with it by ω τ(t) about z.
  const NeedleMotion& motion = contact_->needle().motion();
  const double angle = motion.rotation_speed * motion.elapsed(t), c = std::cos(angle), s = std::sin(angle);
  lateral_force_ = {c * load_.force[0] + s * load_.force[1], -s * load_.force[0] + c * load_.force[1]};
  lateral_force_magnitude_.push_back(std::hypot(lateral_force_[0], lateral_force_[1]));
  if (const contact::HingedNeedle* hinged = contact_->hinged_needle()) {
    head_load_ = contact_->load_on_head(t, state.data(), rate.data(), system_.dof_map());
    head_tilt_ = hinged->tilt().at(t);
    head_moments_.push_back({head_load_.moment[0], head_load_.moment[1]});
    head_tilts_.push_back(head_tilt_);
  }
  if (!elasticity_) return;
  const auto start = WallClock::now();
  const auto deflection =
      elasticity_->deflection(contact_->nodal_loads_in_needle_frame(t, state.data(), rate.data(), system_.dof_map()));
  elasticity_seconds_ += seconds_since(start);
  if (deflection.max_m >= largest_deflection_.max_m) {
    largest_deflection_ = deflection;
    largest_deflection_time_ = t;
  }
}

std::string NeedleOutput::history_cells() const {
  const Point3 &f = load_.force, &m = load_.moment;
  std::string cells = fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}", f[0], f[1], f[2],
                                  m[0], m[1], m[2], load_.contact_area * kMm2PerM2, lateral_force_[0], lateral_force_[1]);
  if (contact_->hinged_needle())
    cells += fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}", std::hypot(head_tilt_[0], head_tilt_[1]) * kDegPerRad,
                         head_tilt_[0], head_tilt_[1], head_load_.moment[0], head_load_.moment[1]);
  return cells;
}

nlohmann::json NeedleOutput::summary() const {
  nlohmann::json s;
  s["needle"] = {{"max_axial_force_n", largest_magnitude(axial_force_)},
                 {"max_torque_n_m", largest_magnitude(torque_)},
                 {"max_lateral_force_n", largest_magnitude(lateral_force_magnitude_)},
                 {"lateral_force_n", lateral_force_magnitude_},
                 {"time_s", times_},
                 {"axial_force_n", axial_force_},
                 {"torque_n_m", torque_},
                 {"note", "forces on the needle: axial = along +z (the insertion direction; negative = the tissue "
                          "resists insertion), torque about +z (sign opposite to the rotation = resisting it); "
                          "lateral force: its part across the axis, what steers a bevel tip (history.csv gives it in the "
                          "needle's frame, xi towards the bevel face's lateral normal, turning with the needle); "
                          "max_* are the largest magnitudes over the output times"}};
  if (contact_->hinged_needle())
    s["head"] = {{"time_s", times_},
                 {"tilt_rad", head_tilts_},
                 {"moment_n_m", head_moments_},
                 {"note", "the compliant tip's head: its tilt (rotation vector (x, y) about the pivot, "
                          "physics/contact/hinged_needle.hpp) and the contact's moment (x, y) on the head about the "
                          "pivot, at each output time"}};
  const auto range = [](const contact::GapRange& g) { return nlohmann::json{g.min * kMmPerM, g.max * kMmPerM}; };
  s["contact"] = {{"initial_gap_nodes_mm", range(initial_gap_.nodes)},
                  {"initial_gap_centroids_mm", range(initial_gap_.centroids)},
                  {"initial_gap_note", "[min, max] gap of the undeformed cavity to the needle at t = 0, at the cavity "
                                       "nodes and at the face centroids"},
                  {"edge_radius_mm", contact_->needle().edge_radius() * kMmPerM},
                  {"edge_note", "the needle's bevel and fillet edges are rounded with this radius (needle_obstacle.hpp): "
                                "cavity nodes on those edges start up to about this far from the needle"},
                  {"cavity_faces", contact_->contact().face_count()}};
  if (deflection_check_) {
    const double elastic_slip = contact_->contact().elastic_slip();
    const Point3& where = largest_deflection_.where;
    s["needle"]["deflection_check"] = {
        {"max_deflection_m", largest_deflection_.max_m},
        {"time_s", largest_deflection_time_},
        {"position_mm", {where[0] * kMmPerM, where[1] * kMmPerM, where[2] * kMmPerM}},
        {"elastic_energy_j", largest_deflection_.elastic_energy_j},
        {"elastic_slip_m", elastic_slip},
        {"deflection_per_elastic_slip", largest_deflection_.max_m / elastic_slip},
        {"needle_travel_m", needle_travel_m_},
        {"deflection_per_travel", needle_travel_m_ > 0.0 ? largest_deflection_.max_m / needle_travel_m_ : 0.0},
        {"youngs_modulus_pa", youngs_modulus_pa_},
        {"poisson_ratio", poisson_ratio_},
        {"needle_dofs", needle_dofs_},
        {"needle_elements", needle_elements_},
        {"seconds", elasticity_seconds_},
        {"note", "one-way check: the linear-elastic tip clamped on its rear face under the rigid run's contact "
                 "loads (physics/contact/needle_elasticity.hpp); a deflection far below the elastic "
                 "slip s0 (the contact's own resolution) cannot change the tissue's answer"}};
  }
  return s;
}

}  // namespace needlefem::run
