// What `needlefem run` adds for the mesh scene (scene.kind = "mesh"): the pressure s(t) p on
// groups.pressure (physics/mechanics/surface_pressure.hpp) and the contact of the case's rigid
// obstacle with obstacle.group (physics/contact/scene_obstacle.hpp), both registered as surface
// loads of the mechanics system, and at every output time the history.csv columns
//   pressure_pa                                  the pressure applied (with groups.pressure),
//   obstacle_force_{x,y,z}_n, obstacle_moment_{x,y,z}_n_m, obstacle_contact_area_mm2
//                                                force the tissue exerts on the obstacle, its
//                                                moment about the scene's origin (a needle's axis
//                                                passes through it: z is the torque about the
//                                                axis), and the reference area of obstacle.group
//                                                in contact (with an obstacle).
#pragma once

#include <memory>
#include <string>

#include <petscvec.h>

#include "physics/contact/penalty_contact.hpp"
#include "physics/mechanics/load_history.hpp"
#include "run/run_specs.hpp"

namespace needlefem {
class Case;
}
namespace needlefem::mechanics {
class MechanicsSystem;
}

namespace needlefem::run {

class MeshSceneLoads {
 public:
  // nullptr unless scene.kind = "mesh"; otherwise adds the loads to `system` (`mesh` and `system`
  // must outlive the result), the obstacle's contact by the [contact] law `contact_parameters`
  // (run_contact_parameters). Takes the Case for the needle obstacle's motion (run_needle_specs).
  static std::unique_ptr<MeshSceneLoads> attach(const Case& input, const RunSpecs& specs, const TetMesh& mesh,
                                                mechanics::MechanicsSystem& system,
                                                const contact::ContactParameters& contact_parameters);
  MeshSceneLoads(const Case& input, const RunSpecs& specs, const TetMesh& mesh, mechanics::MechanicsSystem& system,
                 const contact::ContactParameters& contact_parameters);

  std::string history_header() const;                          // starts with a comma
  std::string history_cells(double t, Vec y, Vec ydot) const;  // starts with a comma

 private:
  const mechanics::MechanicsSystem& system_;
  mechanics::LoadHistory history_;
  double pressure_pa_ = 0.0;
  bool pressure_ = false;
  std::shared_ptr<contact::PenaltyContact> contact_;
};

}  // namespace needlefem::run
