#include "case/specs/mechanics_spec.hpp"

#include <array>
#include <utility>

#include "case/specs/choice.hpp"

namespace needlefem {

MechanicsSpec parse_mechanics_spec(const Case& c, const MeshSpec& mesh, const LoadingSpec& loading,
                                   ContactMode contact_mode) {
  return {.material = parse_material_spec(c),
          .formulation = parse_choice(c, "element.formulation",
                                      std::array{std::pair{"mixed", ElementFormulation::mean_dilatation},
                                                 std::pair{"displacement", ElementFormulation::displacement}}),
          .boundary = parse_boundary_spec(c, mesh, loading, contact_mode)};
}

}  // namespace needlefem
