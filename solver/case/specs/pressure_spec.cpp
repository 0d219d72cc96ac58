#include "case/specs/pressure_spec.hpp"

#include "case/case.hpp"

namespace needlefem {

PressureSpec parse_pressure_spec(const Case& c) {
  return {.groups = c.texts("groups.pressure"),
          .value_pa = c.real("pressure.value_pa"),
          .follower = c.flag("pressure.follower")};
}

}  // namespace needlefem
