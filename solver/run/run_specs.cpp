#include "run/run_specs.hpp"

#include <utility>

#include "physics/contact/needle_contact.hpp"
#include "physics/contact/penalty_contact.hpp"
#include "physics/mechanics/load_history.hpp"

namespace needlefem::run {

// The mesh spec, which throws no CaseError, is parsed first: the loading and mechanics specs take
// the scene from it, and the mechanics spec the loading and contact.mode.
RunSpecs parse_run_specs(const Case& c) {
  MeshSpec mesh = parse_mesh_spec(c);
  ContactSpec contact = parse_contact_spec(c);
  const LoadingSpec loading = parse_loading_spec(c, mesh.scene_kind);
  RunSpecs specs{.mechanics = parse_mechanics_spec(c, mesh, loading, contact.mode),
                 .contact = std::move(contact),
                 .mesh = std::move(mesh),
                 .needle_deflection_check = parse_needle_deflection_check_spec(c),
                 .obstacle = parse_obstacle_spec(c),
                 .pressure = parse_pressure_spec(c),
                 .integration = parse_integration_spec(c),
                 .thresholds = parse_thresholds_spec(c),
                 .output = parse_output_spec(c),
                 .needle_motion = std::nullopt,
                 .hinge_steering = std::nullopt};
  if (needle_in_contact(specs) || specs.obstacle.kind == ObstacleKind::needle)
    specs.needle_motion = parse_motion_spec(c);
  if (head_turns_in_tissue(specs)) specs.hinge_steering = steering::steering_setup_from_case(c);
  return specs;
}

bool head_turns_in_tissue(const RunSpecs& specs) {
  return needle_in_contact(specs) && specs.mesh.needle_tip.kind == NeedleKind::compliant;
}

bool needle_in_contact(const RunSpecs& specs) {
  return specs.mesh.scene_kind == SceneKind::brain_tip && specs.contact.mode == ContactMode::frictional;
}

contact::ContactParameters run_contact_parameters(const RunSpecs& specs, double reference_modulus) {
  return contact::contact_parameters_from_spec(specs.contact, reference_modulus, mechanics::history_end(specs.loading()),
                                               specs.mesh.refinement_level);
}

contact::NeedleSpecs run_needle_specs(const RunSpecs& specs) {
  return {.mesh = specs.mesh, .motion = specs.needle_motion.value()};
}

}  // namespace needlefem::run
