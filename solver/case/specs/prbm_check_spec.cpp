#include "case/specs/prbm_check_spec.hpp"

#include "case/case.hpp"
#include "case/specs/steering_spec.hpp"

namespace needlefem {

PrbmCheckSpec parse_prbm_check_spec(const Case& c) {
  return {.angles_deg = c.reals("prbm_check.angles_deg"),
          .neck_youngs_modulus_gpa = parse_steering_spec(c).neck_youngs_modulus_gpa,
          .poisson_ratio = c.real("prbm_check.poisson_ratio"),
          .tolerance_percent = c.real("prbm_check.tolerance_percent"),
          .element_mm = c.real("prbm_check.element_mm"),
          .neck_element_mm = c.real("prbm_check.neck_element_mm")};
}

}  // namespace needlefem
