#include "case/specs/output_spec.hpp"

#include "case/case.hpp"

namespace needlefem {

OutputSpec parse_output_spec(const Case& c) {
  return {.origin = c.origin(),
          .interval_s = c.real("output.interval_s"),
          .density_kg_per_m3 = c.real("output.density_kg_per_m3")};
}

}  // namespace needlefem
