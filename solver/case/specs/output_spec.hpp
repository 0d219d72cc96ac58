// What `needlefem run` writes at its output times, parsed: [output] (when: run/output_schedule.hpp;
// the kinetic energy's density: physics/fields/tissue_fields.hpp and summary.json "energy").
#pragma once

#include <string>

namespace needlefem {

class Case;

struct OutputSpec {
  std::string origin;        // the case's, for the CaseError of too many output times
  double interval_s;         // between output times
  double density_kg_per_m3;  // the tissue's, for the kinetic energy the quasi-static model neglects
};

OutputSpec parse_output_spec(const Case& c);

}  // namespace needlefem
