// The safety verdict's keys, parsed: [thresholds], the three limits and the settings of the
// metrics judged against them (run/safety_report.hpp). Values are in the units their keys name.
#pragma once

namespace needlefem {

class Case;

struct ThresholdsSpec {
  double log_strain;            // limit on the max principal log strain
  double strain_rate_per_s;     // limit on the max principal strain rate, over strain_rate_window_s
  double stress_pa;             // limit on the von Mises stress
  double critical_distance_mm;  // radius of the ball each limited field is averaged over
  double strain_rate_window_s;
  double percentile;  // of each limited field over the region near the needle
  double region_mm;   // that region: tissue within this distance of the cavity surface
};

ThresholdsSpec parse_thresholds_spec(const Case& c);

}  // namespace needlefem
