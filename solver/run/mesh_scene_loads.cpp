#include "run/mesh_scene_loads.hpp"

#include <utility>

#include <fmt/core.h>

#include "integration/petsc_arrays.hpp"
#include "physics/contact/penalty_contact.hpp"
#include "physics/mechanics/mechanics_system.hpp"
#include "physics/mechanics/surface_pressure.hpp"

namespace needlefem::run {

namespace {

constexpr double kMm2PerM2 = 1e6;

}  // namespace

MeshSceneLoads::MeshSceneLoads(const mechanics::MechanicsSystem& system,
                               std::shared_ptr<const mechanics::SurfacePressure> pressure,
                               std::shared_ptr<const contact::PenaltyContact> obstacle)
    : system_(system), pressure_(std::move(pressure)), obstacle_(std::move(obstacle)) {}

std::string MeshSceneLoads::history_header() const {
  return std::string(pressure_ ? ",pressure_pa" : "") +
         (obstacle_ ? ",obstacle_force_x_n,obstacle_force_y_n,obstacle_force_z_n,obstacle_moment_x_n_m,"
                      "obstacle_moment_y_n_m,obstacle_moment_z_n_m,obstacle_contact_area_mm2"
                    : "");
}

std::string MeshSceneLoads::history_cells(double t, Vec y, Vec ydot) const {
  std::string cells;
  if (pressure_) cells += fmt::format(",{:.9g}", pressure_->pressure(t));
  if (!obstacle_) return cells;
  const ReadArray state(y), rate(ydot);
  const contact::ContactResultant r = obstacle_->resultant(t, state.data(), rate.data(), system_.dof_map());
  return cells + fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}", r.force_on_obstacle[0],
                             r.force_on_obstacle[1], r.force_on_obstacle[2], r.moment_on_obstacle[0],
                             r.moment_on_obstacle[1], r.moment_on_obstacle[2], r.contact_area * kMm2PerM2);
}

}  // namespace needlefem::run
