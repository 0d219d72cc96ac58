#include "case/specs/thresholds_spec.hpp"

#include "case/case.hpp"

namespace needlefem {

ThresholdsSpec parse_thresholds_spec(const Case& c) {
  return {.log_strain = c.real("thresholds.log_strain"),
          .strain_rate_per_s = c.real("thresholds.strain_rate_per_s"),
          .stress_pa = c.real("thresholds.stress_pa"),
          .critical_distance_mm = c.real("thresholds.critical_distance_mm"),
          .strain_rate_window_s = c.real("thresholds.strain_rate_window_s"),
          .percentile = c.real("thresholds.percentile"),
          .region_mm = c.real("thresholds.region_mm")};
}

}  // namespace needlefem
