#include "run/mesh_scene_loads.hpp"

#include <optional>

#include <fmt/core.h>

#include "integration/petsc_arrays.hpp"
#include "physics/contact/needle_contact.hpp"
#include "physics/contact/scene_obstacle.hpp"
#include "physics/mechanics/mechanics_system.hpp"
#include "physics/mechanics/surface_pressure.hpp"

namespace needlefem::run {

namespace {

constexpr double kMm2PerM2 = 1e6;

// The obstacle's contact; the needle obstacle's motion is parsed (and checked) only for it.
std::shared_ptr<contact::PenaltyContact> obstacle_contact(const Case& input, const RunSpecs& specs, const TetMesh& mesh,
                                                 const contact::ContactParameters& contact_parameters) {
  std::optional<contact::NeedleSpecs> needle;
  if (specs.obstacle.kind == ObstacleKind::needle) needle = run_needle_specs(input, specs);
  return contact::scene_obstacle_contact(specs.obstacle, needle ? &*needle : nullptr, contact_parameters, mesh);
}

}  // namespace

std::unique_ptr<MeshSceneLoads> MeshSceneLoads::attach(const Case& input, const RunSpecs& specs, const TetMesh& mesh,
                                                       mechanics::MechanicsSystem& system,
                                                       const contact::ContactParameters& contact_parameters) {
  if (specs.scene_kind != SceneKind::mesh) return nullptr;
  return std::make_unique<MeshSceneLoads>(input, specs, mesh, system, contact_parameters);
}

MeshSceneLoads::MeshSceneLoads(const Case& input, const RunSpecs& specs, const TetMesh& mesh,
                               mechanics::MechanicsSystem& system,
                               const contact::ContactParameters& contact_parameters)
    : system_(system),
      history_(mechanics::LoadHistory::from_spec(specs.loading)),
      pressure_pa_(specs.pressure.value_pa),
      pressure_(!specs.pressure.groups.empty()),
      contact_(obstacle_contact(input, specs, mesh, contact_parameters)) {
  if (pressure_)
    system.add_surface_load(std::make_shared<mechanics::SurfacePressure>(
        mesh, specs.pressure.groups,
        [history = history_, p = pressure_pa_](double t) { return history.factor(t) * p; },
        specs.pressure.follower));
  if (contact_) system.add_surface_load(contact_);
}

std::string MeshSceneLoads::history_header() const {
  return std::string(pressure_ ? ",pressure_pa" : "") +
         (contact_ ? ",obstacle_force_x_n,obstacle_force_y_n,obstacle_force_z_n,obstacle_moment_x_n_m,"
                     "obstacle_moment_y_n_m,obstacle_moment_z_n_m,obstacle_contact_area_mm2"
                   : "");
}

std::string MeshSceneLoads::history_cells(double t, Vec y, Vec ydot) const {
  std::string cells;
  if (pressure_) cells += fmt::format(",{:.9g}", history_.factor(t) * pressure_pa_);
  if (!contact_) return cells;
  const ReadArray state(y), rate(ydot);
  const contact::ContactResultant r = contact_->resultant(t, state.data(), rate.data(), system_.dof_map());
  return cells + fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}", r.force_on_obstacle[0],
                             r.force_on_obstacle[1], r.force_on_obstacle[2], r.moment_on_obstacle[0],
                             r.moment_on_obstacle[1], r.moment_on_obstacle[2], r.contact_area * kMm2PerM2);
}

}  // namespace needlefem::run
