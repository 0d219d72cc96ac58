#include "run/run_model.hpp"

#include <optional>
#include <utility>

#include "integration/options_from_spec.hpp"
#include "physics/contact/needle_contact.hpp"
#include "physics/contact/scene_obstacle.hpp"
#include "physics/material/material.hpp"
#include "physics/mechanics/load_history.hpp"
#include "physics/mechanics/mechanics_system.hpp"
#include "physics/mechanics/surface_pressure.hpp"

namespace needlefem::run {

namespace {

// The obstacle's contact.
std::shared_ptr<contact::PenaltyContact> obstacle_contact(const RunSpecs& specs, const TetMesh& mesh,
                                                          const contact::ContactParameters& contact_parameters) {
  std::optional<contact::NeedleSpecs> needle;
  if (specs.obstacle.kind == ObstacleKind::needle) needle = run_needle_specs(specs);
  return contact::scene_obstacle_contact(specs.obstacle, needle ? &*needle : nullptr, contact_parameters, mesh);
}

// A mesh scene's pressure and obstacle, added to `model.system` in that order. The obstacle is
// built first: its errors come before any of the pressure's.
void add_mesh_scene_loads(const RunSpecs& specs, const TetMesh& mesh,
                          const contact::ContactParameters& contact_parameters, RunModel& model) {
  const mechanics::LoadHistory history = mechanics::LoadHistory::from_spec(specs.loading());
  std::shared_ptr<contact::PenaltyContact> obstacle = obstacle_contact(specs, mesh, contact_parameters);
  if (!specs.pressure.groups.empty()) {
    auto pressure = std::make_shared<mechanics::SurfacePressure>(
        mesh, specs.pressure.groups,
        [history, p = specs.pressure.value_pa](double t) { return history.factor(t) * p; }, specs.pressure.follower);
    model.system->add_surface_load(pressure);
    model.pressure = std::move(pressure);
  }
  if (obstacle) model.system->add_surface_load(obstacle);
  model.obstacle = std::move(obstacle);
}

}  // namespace

RunModel build_run_model(const RunSpecs& specs, const TetMesh& mesh, const material::Material& material,
                         std::shared_ptr<const contact::Needle> needle,
                         std::shared_ptr<const contact::HeadTilt> head_tilt) {
  RunModel model{.system = mechanics::MechanicsSystem::from_spec(specs.mechanics, mesh),
                 .needle = nullptr, .pressure = nullptr, .obstacle = nullptr};
  model.system->use_newton_matrix_options(newton_matrix_options_from_spec(specs.integration));
  if (needle && head_tilt) needle = contact::needle_from_spec(run_needle_specs(specs), nullptr, std::move(head_tilt));
  const contact::ContactParameters contact_parameters =
      run_contact_parameters(specs, material.instantaneous_shear_modulus());
  if (needle) {
    auto needle_contact = std::make_shared<contact::NeedleContact>(contact_parameters, mesh, std::move(needle));
    model.system->add_surface_load(needle_contact->surface_load());
    model.needle = std::move(needle_contact);
  }
  if (specs.mesh.scene_kind == SceneKind::mesh) add_mesh_scene_loads(specs, mesh, contact_parameters, model);
  return model;
}

}  // namespace needlefem::run
