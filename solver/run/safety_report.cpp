#include "run/safety_report.hpp"

#include <cmath>
#include <unordered_map>

#include <fmt/core.h>

#include "case/mesh_resolution.hpp"
#include "case/specs/thresholds_spec.hpp"
#include "output/history_table.hpp"

namespace needlefem::run {

namespace {

constexpr double kMmPerM = 1e3;
constexpr const char* kCavity = "cavity";

// The limits (case key thresholds.<name>, ThresholdsSpec::*limit) and what each judges, in the
// words of summary.json and of the verdict line; values are shown in `unit` (the field's SI value
// times `scale`).
struct LimitText {
  const char* name;
  double ThresholdsSpec::*limit;
  int field;  // fields::ScalarQuantity
  const char* label;
  const char* quantity;
  const char* unit;
  double scale;
  bool windowed;  // judged over thresholds.strain_rate_window_s
};
constexpr LimitText kLimitText[] = {
    {"log_strain", &ThresholdsSpec::log_strain, fields::kLogStrain, "max principal log strain",
     "max principal logarithmic strain, ln of the largest principal stretch", "", 1.0, false},
    {"strain_rate_per_s", &ThresholdsSpec::strain_rate_per_s, fields::kStrainRate, "max principal strain rate",
     "max principal strain rate (1/s) sustained over window_s: ln of the largest principal stretch of the "
     "deformation over the window before t (F(t) F(t - window_s)^-1), divided by window_s, judged at the output "
     "times and at accepted steps a quarter window apart between them; for a steady stretching it is the largest "
     "eigenvalue of the rate of deformation D = sym(dF/dt F^-1), the stretch rate of the uniaxial tests the limit "
     "comes from, and a slip burst counts by the strain it delivers. critical_distance_instantaneous is the same "
     "ball average of the instantaneous largest eigenvalue of D at the output times (what paper 001 reported); "
     "max.equivalent_strain_rate_per_s, sqrt(2/3 D:D), counts shear too (2/sqrt(3) times larger in simple shear) "
     "and is reported, not judged",
     "1/s", 1.0, true},
    {"stress_pa", &ThresholdsSpec::stress_pa, fields::kVonMises, "von Mises stress",
     "von Mises (equivalent) Cauchy stress, Pa", "kPa", 1e-3, false}};
// The windowed limit's other critical-distance values (window_variants_), in summary.json.
enum WindowVariant { kHalfWindow, kDoubleWindow, kInstantaneous };
constexpr const char* kWindowVariantNames[] = {"critical_distance_half_window", "critical_distance_double_window",
                                               "critical_distance_instantaneous"};

// history.csv's column of a limit's critical-distance value.
std::string critical_distance_column(const char* limit_name) { return fmt::format("critical_distance_{}", limit_name); }

nlohmann::json millimetres(const Point3& x) { return {x[0] * kMmPerM, x[1] * kMmPerM, x[2] * kMmPerM}; }

// Per point: within `distance` of a node of the cavity surface (the needle's imprint).
std::vector<char> near_cavity(const TetMesh& mesh, const std::vector<Point3>& points, double distance) {
  const auto cavity = mesh.surface_faces.find(kCavity);
  std::vector<char> near(points.size(), 0);
  const auto cell = [distance](const Point3& x) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(x[0] / distance)),
                                    static_cast<long long>(std::floor(x[1] / distance)),
                                    static_cast<long long>(std::floor(x[2] / distance))};
  };
  const auto key = [](long long i, long long j, long long k) {
    return ((i + (1LL << 20)) << 42) | ((j + (1LL << 20)) << 21) | (k + (1LL << 20));
  };
  std::unordered_map<long long, std::vector<int>> nodes_in;
  for (int node : cavity->second) {
    const auto c = cell(mesh.nodes[node]);
    auto& list = nodes_in[key(c[0], c[1], c[2])];
    if (std::find(list.begin(), list.end(), node) == list.end()) list.push_back(node);
  }
  const double d2 = distance * distance;
#pragma omp parallel for schedule(static)
  for (std::size_t q = 0; q < points.size(); ++q) {
    const auto c = cell(points[q]);
    for (long long i = c[0] - 1; i <= c[0] + 1 && !near[q]; ++i)
      for (long long j = c[1] - 1; j <= c[1] + 1 && !near[q]; ++j)
        for (long long k = c[2] - 1; k <= c[2] + 1 && !near[q]; ++k) {
          const auto found = nodes_in.find(key(i, j, k));
          if (found == nodes_in.end()) continue;
          for (int node : found->second) {
            const Point3& x = mesh.nodes[node];
            const double dx = x[0] - points[q][0], dy = x[1] - points[q][1], dz = x[2] - points[q][2];
            if (dx * dx + dy * dy + dz * dz <= d2) {
              near[q] = 1;
              break;
            }
          }
        }
  }
  return near;
}

}  // namespace

nlohmann::json MaximumOverTime::to_json(const char* position_name) const {
  return {{"value", value}, {"time_s", time_s}, {position_name, millimetres(position)}};
}

SafetyReport::SafetyReport(const ThresholdsSpec& thresholds, const TetMesh& mesh,
                           const fields::TissueFieldEvaluator& evaluator)
    : radius_mm_(thresholds.critical_distance_mm),
      percentile_(thresholds.percentile),
      region_mm_(thresholds.region_mm),
      positions_(evaluator.point_positions()),
      volumes_(evaluator.point_volumes()),
      tetrahedra_(evaluator.tissue_tetrahedra()),
      point_barycentric_(evaluator.point_barycentric()),
      elements_(tetrahedra_, point_barycentric_),
      evaluator_(evaluator),
      window_s_(thresholds.strain_rate_window_s),
      window_(2.0 * window_s_, window_s_ / 4.0),
      now_(std::size(kLimitText)),
      over_time_(std::size(kLimitText)) {
  for (const LimitText& text : kLimitText)
    limits_.push_back({text.name, text.field, thresholds.*text.limit, text.windowed});
  const double radius = radius_mm_ / kMmPerM;
  ball_ = std::make_unique<fields::BallAverager>(positions_, volumes_, tetrahedra_, radius);
  half_ball_ = std::make_unique<fields::BallAverager>(positions_, volumes_, tetrahedra_, radius / 2);
  double_ball_ = std::make_unique<fields::BallAverager>(positions_, volumes_, tetrahedra_, 2 * radius);
  std::vector<char> region;  // per point: near the needle
  if (mesh.surface_faces.count(kCavity)) {
    region = near_cavity(mesh, positions_, region_mm_ / kMmPerM);
    region_description_ = fmt::format("tissue within {} mm of the cavity surface", region_mm_);
  } else {
    region.assign(positions_.size(), 1);
    region_description_ = "all tissue (the scene has no cavity)";
  }
  for (std::size_t q = 0; q < positions_.size(); ++q)
    if (region[q]) region_volume_ += volumes_[q];
  element_volumes_ = elements_.selected_volumes(volumes_);
  region_element_volumes_ = elements_.selected_volumes(volumes_, region);
}

void SafetyReport::observe_step(double t, Vec y) {
  if (!window_.wants_snapshot(t)) return;
  window_.add_snapshot(t, evaluator_.deformation_gradients(y));
  judge_windowed(t);
}

void SafetyReport::add_time(double t, const fields::TissueFields& f) {
  window_.add_snapshot(t, f.deformation_gradient);
  judge_windowed(t);
  for (std::size_t i = 0; i < limits_.size(); ++i) {
    const std::vector<double>& values = f.point_value[limits_[i].quantity];
    if (!limits_[i].windowed) {
      now_[i] = measure(limits_[i], values);
      keep_maximum(i, t, now_[i], values);
      continue;
    }
    window_variants_now_[kInstantaneous] = ball_->maximum(values);
    const fields::LocatedValue& v = window_variants_now_[kInstantaneous];
    window_variants_[kInstantaneous].update(v.value, t, v.position);
  }
}

void SafetyReport::judge_windowed(double t) {
  const std::vector<double> rate = window_.rate(window_s_);
  for (std::size_t i = 0; i < limits_.size(); ++i)
    if (limits_[i].windowed) {
      now_[i] = measure(limits_[i], rate);
      keep_maximum(i, t, now_[i], rate);
    }
  window_variants_now_[kHalfWindow] = ball_->maximum(window_.rate(window_s_ / 2.0));
  window_variants_now_[kDoubleWindow] = ball_->maximum(window_.rate(2.0 * window_s_));
  for (int v : {kHalfWindow, kDoubleWindow})
    window_variants_[v].update(window_variants_now_[v].value, t, window_variants_now_[v].position);
}

SafetyReport::Now SafetyReport::measure(const Limit& limit, const std::vector<double>& values) const {
  Now now;
  now.critical_distance = ball_->maximum(values);
  const std::vector<std::array<double, 4>> vertex_values = elements_.vertex_values(values);
  now.above = fields::volume_above(elements_, vertex_values, element_volumes_, limit.limit);
  const double in_region = fields::volume_above(elements_, vertex_values, region_element_volumes_, limit.limit).volume;
  now.region_fraction = region_volume_ > 0.0 ? in_region / region_volume_ : 0.0;
  now.percentile = fields::volume_percentile(vertex_values, region_element_volumes_, percentile_);
  return now;
}

void SafetyReport::keep_maximum(std::size_t i, double t, const Now& now, const std::vector<double>& values) {
  OverTime& max = over_time_[i];
  if (now.critical_distance.value > max.critical_distance.value) max.field_at_critical_distance = values;
  max.critical_distance.update(now.critical_distance.value, t, now.critical_distance.position);
  max.volume_above.update(now.above.volume * std::pow(kMmPerM, 3), t, now.above.centroid);
  max.region_fraction.update(now.region_fraction, t, {});
  max.percentile.update(now.percentile, t, {});
}

std::string SafetyReport::history_header() const {
  std::string header;
  for (const Limit& limit : limits_)
    header += fmt::format(",{0}{1},volume_above_{2}_mm3,region_fraction_above_{2},percentile_{2}{3}",
                          critical_distance_column(limit.name), output::history_position_columns(critical_distance_column(limit.name)),
                          limit.name, limit.windowed ? fmt::format(",critical_distance_instantaneous_{}", limit.name) : "");
  return header;
}

std::string SafetyReport::history_cells() const {
  std::string cells;
  for (std::size_t i = 0; i < limits_.size(); ++i) {
    const Now& now = now_[i];
    const Point3& x = now.critical_distance.position;
    cells += fmt::format(",{:.9g},{:.6g},{:.6g},{:.6g},{:.9g},{:.9g},{:.9g}", now.critical_distance.value,
                         x[0] * kMmPerM, x[1] * kMmPerM, x[2] * kMmPerM, now.above.volume * std::pow(kMmPerM, 3),
                         now.region_fraction, now.percentile);
    if (limits_[i].windowed) cells += fmt::format(",{:.9g}", window_variants_now_[kInstantaneous].value);
  }
  return cells;
}

nlohmann::json SafetyReport::summary(const std::array<MaximumOverTime, fields::kScalarQuantities>& point_maxima) const {
  nlohmann::json thresholds, safety;
  safety["settings"] = {{"critical_distance_mm", radius_mm_},
                        {"percentile", percentile_},
                        {"region", region_description_},
                        {"region_volume_mm3", region_volume_ * std::pow(kMmPerM, 3)}};
  safety["note"] = "critical_distance: the largest average over a ball of radius critical_distance_mm (reference "
                   "configuration, tissue part only), the mesh-objective value each verdict uses; point_max: the "
                   "largest quadrature-point value, mesh-dependent next to a needle edge; each the largest over the "
                   "output times";
  for (std::size_t i = 0; i < limits_.size(); ++i) {
    const Limit& limit = limits_[i];
    const MaximumOverTime& point = point_maxima[limit.quantity];
    if (!std::isfinite(point.value)) continue;  // no output time completed
    thresholds[limit.name] = {{"limit", limit.limit},
                              {"max", point.value},
                              {"pass", point.value <= limit.limit},
                              {"max_key", fields::scalar_quantities()[limit.quantity].summary_key}};
    const OverTime& max = over_time_[i];
    // A run that failed while writing an output time has its point maxima but not this time's
    // critical-distance values: the failure's summary then says what it has, not a second error.
    if (max.field_at_critical_distance.empty()) continue;
    const auto at_time = [&](const fields::BallAverager& ball) {
      const fields::LocatedValue v = ball.maximum(max.field_at_critical_distance);
      return nlohmann::json{{"value", v.value}, {"time_s", max.critical_distance.time_s},
                            {"position_mm", millimetres(v.position)}};
    };
    safety[limit.name] = {
        {"limit", limit.limit},
        {"point_max", point.to_json()},
        {"critical_distance", max.critical_distance.to_json()},
        {"critical_distance_half_radius", at_time(*half_ball_)},
        {"critical_distance_double_radius", at_time(*double_ball_)},
        {"volume_above_limit_mm3", max.volume_above.to_json("centroid_mm")},
        {"region_fraction_above_limit", {{"value", max.region_fraction.value}, {"time_s", max.region_fraction.time_s}}},
        {"percentile", {{"value", max.percentile.value}, {"time_s", max.percentile.time_s}}},
        {"quantity", kLimitText[i].quantity},
        {"history_columns", {{"critical_distance", critical_distance_column(limit.name)},
                             {"point_max", fields::history_maximum_column(fields::scalar_quantities()[limit.quantity])}}},
        {"verdict", max.critical_distance.value <= limit.limit ? "pass" : "fail"}};
    if (limit.windowed) {
      safety[limit.name]["window_s"] = window_s_;
      for (std::size_t v = 0; v < window_variants_.size(); ++v)
        safety[limit.name][kWindowVariantNames[v]] = window_variants_[v].to_json();
    }
  }
  nlohmann::json out = {{"thresholds", thresholds}, {"safety", safety}};
  bool decided = true, fails = false;
  for (const Limit& limit : limits_) {
    decided = decided && safety.contains(limit.name);
    fails = fails || (safety.contains(limit.name) && safety[limit.name]["verdict"] == "fail");
  }
  if (fails || decided) out["verdict"] = fails ? "fail" : "pass";
  return out;
}

std::string verdict_line(const nlohmann::json& summary) {
  if (!summary.contains("verdict")) return "";
  const nlohmann::json& safety = summary["safety"];
  std::string judged;
  for (const LimitText& text : kLimitText) {
    if (!safety.contains(text.name)) continue;
    const nlohmann::json& entry = safety[text.name];
    const double value = entry["critical_distance"]["value"].get<double>() * text.scale;
    const double limit = entry["limit"].get<double>() * text.scale;
    const bool passes = entry["verdict"] == "pass";
    const std::string unit = *text.unit ? std::string(" ") + text.unit : "";
    judged += fmt::format("{}{} {:.3g}{} {} {:.3g}{}{}", judged.empty() ? "" : ", ", text.label, value, unit,
                          passes ? "<=" : ">", limit, unit, passes ? "" : " FAILS");
  }
  const std::string mesh_warning =
      summary.contains("mesh_resolution")
          ? coarse_mesh_warning(summary["mesh_resolution"]["coarser"].get<std::vector<std::string>>())
          : "";
  const nlohmann::json& rate = safety.value("strain_rate_per_s", nlohmann::json::object());
  const std::string window = rate.contains("window_s")
                                 ? fmt::format("; the strain rate over {:g} ms", rate["window_s"].get<double>() * 1e3)
                                 : "";
  return fmt::format("verdict: {} (critical-distance values: averages over a {:g} mm ball{}): {}{}",
                     summary["verdict"].get<std::string>(), safety["settings"]["critical_distance_mm"].get<double>(),
                     window, judged, mesh_warning.empty() ? "" : "; " + mesh_warning);
}

}  // namespace needlefem::run
