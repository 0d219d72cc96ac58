// The tissue's mechanics, parsed: material, element formulation and boundary conditions, the
// input of mechanics::MechanicsSystem::from_spec (physics/mechanics/mechanics_system.hpp).
#pragma once

#include "case/specs/boundary_spec.hpp"
#include "case/specs/material_spec.hpp"

namespace needlefem {

class Case;

// element.formulation: "mixed" is the mean-dilatation element.
enum class ElementFormulation { displacement, mean_dilatation };

struct MechanicsSpec {
  MaterialSpec material;
  ElementFormulation formulation;
  BoundarySpec boundary;
};

// Throws the CaseErrors of parse_material_spec and parse_boundary_spec (which takes the scene
// from `mesh`, the loading and contact.mode from the specs parsed from the same case).
MechanicsSpec parse_mechanics_spec(const Case& c, const MeshSpec& mesh, const LoadingSpec& loading,
                                   ContactMode contact_mode);

}  // namespace needlefem
