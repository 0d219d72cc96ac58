// The safety verdict of a run: paper 001's three limits (thresholds.*: max principal log strain,
// max principal strain rate, von Mises stress) against
//   the point maximum      the largest value at a tissue quadrature point (mesh-dependent next
//                          to a needle edge: kept as paper 001 reported it, labelled so),
//   the mesh-objective metrics of physics/fields/safety_metrics.hpp:
//     critical_distance              the largest ball average, ball radius thresholds.critical_distance_mm
//                                    (also at half and twice that radius, at the output time of
//                                    its maximum, to show the verdict's sensitivity to it),
//     volume_above_limit_mm3         the tissue volume above the limit, with its centroid,
//     region_fraction_above_limit    that volume's share of the region near the needle
//                                    (tissue within thresholds.region_mm of the cavity surface),
//     percentile                     the thresholds.percentile-th percentile over that region,
// each the largest over the output times, with when (and where). The verdict of each limit is
// the critical-distance value's: "pass" when it is at most the limit; the run's verdict is "fail"
// when any limit fails, else "pass". `needlefem converge` gives the same metrics their
// discretisation error band.
//   The strain rate judged is the max principal strain rate (largest eigenvalue of the rate of
//   deformation D): the limit comes from uniaxial stretching tests, where it is the stretch rate,
//   as the strain limit is on the max principal log strain. It is judged as those tests applied
//   it, sustained over a window (thresholds.strain_rate_window_s, physics/fields/
//   strain_rate_window.hpp): the rate of the largest principal stretch over the window before t,
//   judged at the output times and at accepted steps a quarter window apart between them, so that
//   a slip burst counts by the strain it delivers, never missed nor caught by chance.
//   Its critical-distance value is also given at half and twice the window, and the instantaneous
//   rate's (sampled at the output times, as paper 001 did) beside it. The equivalent rate sqrt(2/3 D:D) is
//   reported beside it (summary "max", history.csv) and not judged: equal in uniaxial isochoric
//   stretching, 2/sqrt(3) times larger in simple shear, it counts shear the tests did not apply.
//   history.csv   per output time: critical-distance value and position, volume above, region
//                 fraction and percentile of each limited quantity;
//   summary.json  "verdict" (the run's), "thresholds" (point maxima, as before, each with max_key,
//                 its key under "max") and "safety" (all of the above, each limit naming its
//                 quantity and its history.csv columns), so that readers need no map of names.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "physics/fields/safety_metrics.hpp"
#include "physics/fields/strain_rate_window.hpp"
#include "physics/fields/tissue_fields.hpp"

namespace needlefem {
struct ThresholdsSpec;
}

namespace needlefem::run {

// The largest value seen over all output times, with when and where.
struct MaximumOverTime {
  double value = -std::numeric_limits<double>::infinity();
  double time_s = 0.0;
  Point3 position{};
  void update(double v, double t, const Point3& x) {
    if (v > value) *this = {v, t, x};
  }
  nlohmann::json to_json(const char* position_name = "position_mm") const;
};

class SafetyReport {
 public:
  // `thresholds` gives the limits and the metrics' settings; `evaluator` the tissue's quadrature
  // points and their deformation gradients (it must outlive the report); `mesh` its cavity surface.
  SafetyReport(const ThresholdsSpec& thresholds, const TetMesh& mesh, const fields::TissueFieldEvaluator& evaluator);
  SafetyReport(const SafetyReport&) = delete;  // elements_ views its own arrays
  SafetyReport& operator=(const SafetyReport&) = delete;

  // After an accepted step at t between output times, state y: when a quarter of the strain-rate
  // window has passed since the last, keeps the deformation gradient and judges the windowed rate.
  void observe_step(double t, Vec y);
  // Evaluates the metrics of the fields at output time t (and keeps their maxima over time).
  void add_time(double t, const fields::TissueFields& f);
  std::string history_header() const;  // starts with a comma
  std::string history_cells() const;   // of the last add_time(), starts with a comma
  // "verdict", "thresholds" and "safety" of summary.json, given the point maxima over time;
  // "verdict" only once every limit has a critical-distance value.
  nlohmann::json summary(const std::array<MaximumOverTime, fields::kScalarQuantities>& point_maxima) const;

 private:
  struct Limit {
    const char* name;        // summary key and history column stem
    int quantity;            // fields::ScalarQuantity
    double limit;
    bool windowed;           // judged over the strain-rate window, not at an instant
  };
  struct Now {  // one limit at the last output time
    fields::LocatedValue critical_distance;
    fields::VolumeAbove above;
    double region_fraction = 0.0, percentile = 0.0;
  };
  struct OverTime {
    MaximumOverTime critical_distance, volume_above, region_fraction, percentile;
    std::vector<double> field_at_critical_distance;  // the point values at the time of its maximum
  };

  std::vector<Limit> limits_;
  double radius_mm_, percentile_, region_mm_;
  const std::vector<Point3>& positions_;
  const std::vector<double>& volumes_;
  std::vector<fields::Tetrahedron> tetrahedra_;           // per tissue element
  std::vector<std::array<double, 4>> point_barycentric_;  // per point of an element
  fields::TissueElements elements_;                       // views of the two above
  double region_volume_ = 0.0;  // of the tissue near the needle
  // Per element: its volume, and its volume in the region.
  std::vector<double> element_volumes_, region_element_volumes_;
  std::string region_description_;
  std::unique_ptr<fields::BallAverager> ball_, half_ball_, double_ball_;
  const fields::TissueFieldEvaluator& evaluator_;
  double window_s_;
  fields::StrainRateWindow window_;
  // The strain-rate limit's (the windowed limit's) critical-distance values at half and twice
  // the window and of the instantaneous field: at the last output time and their maxima over time.
  std::array<fields::LocatedValue, 3> window_variants_now_{};
  std::array<MaximumOverTime, 3> window_variants_;
  Now measure(const Limit& limit, const std::vector<double>& values) const;
  void keep_maximum(std::size_t i, double t, const Now& now, const std::vector<double>& values);
  // The windowed strain rate's metrics at t, the last snapshot's time, and their maxima over time.
  void judge_windowed(double t);

  std::vector<Now> now_;
  std::vector<OverTime> over_time_;
};

// The run's verdict in one line, from a summary.json with "verdict" and "safety": e.g.
// "verdict: fail (critical-distance values: averages over a 0.25 mm ball; the strain rate over
// 10 ms): max principal log strain 0.252 > 0.19 FAILS, max principal strain rate 1.48 1/s <= 10
// 1/s, von Mises stress 3.1 kPa <= 120 kPa", followed on a mesh coarser than the converged setting by
// "; mesh coarser than the converged setting (...)" (case/mesh_resolution.hpp).
// Empty when the summary has no verdict.
std::string verdict_line(const nlohmann::json& summary);

}  // namespace needlefem::run
