// The PRBM check's keys ([prbm_check]), parsed, with the neck's modulus of the steering spec: the
// input of run_prbm_check (prbm_check/prbm_check.hpp), which checks them. Values are in the units
// their keys name.
#pragma once

#include <vector>

namespace needlefem {

class Case;

struct PrbmCheckSpec {
  std::vector<double> angles_deg;  // the PRBM turning angles whose head loads the FEM solves, as given
  double neck_youngs_modulus_gpa;  // steering.neck_youngs_modulus_gpa (case/specs/steering_spec.hpp)
  double poisson_ratio;            // of the needle material in the tip FEM
  double tolerance_percent;        // PRBM-vs-FEM angle error below which the PRBM counts as accurate
  double element_mm;               // tip FEM element size in the shaft and head
  double neck_element_mm;          // and in the neck and one neck diameter beyond its ends
};

PrbmCheckSpec parse_prbm_check_spec(const Case& c);

}  // namespace needlefem
