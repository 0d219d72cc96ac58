// What `needlefem run` reports of the mesh scene's loads (scene.kind = "mesh"; run/run_model.hpp
// builds them and adds them to the mechanics system): at every output time the history.csv columns
//   pressure_pa                                  the pressure applied (with groups.pressure,
//                                                physics/mechanics/surface_pressure.hpp),
//   obstacle_force_{x,y,z}_n, obstacle_moment_{x,y,z}_n_m, obstacle_contact_area_mm2
//                                                force the tissue exerts on the obstacle, its
//                                                moment about the scene's origin (a needle's axis
//                                                passes through it: z is the torque about the
//                                                axis), and the reference area of obstacle.group
//                                                in contact (with an obstacle,
//                                                physics/contact/scene_obstacle.hpp).
#pragma once

#include <memory>
#include <string>

#include <petscvec.h>

namespace needlefem::contact {
class PenaltyContact;
}
namespace needlefem::mechanics {
class MechanicsSystem;
class SurfacePressure;
}

namespace needlefem::run {

class MeshSceneLoads {
 public:
  // The loads of the run model's `system` (which must outlive every history_cells()): `pressure`
  // and `obstacle`, either null when the case has none.
  MeshSceneLoads(const mechanics::MechanicsSystem& system, std::shared_ptr<const mechanics::SurfacePressure> pressure,
                 std::shared_ptr<const contact::PenaltyContact> obstacle);

  std::string history_header() const;                          // starts with a comma
  std::string history_cells(double t, Vec y, Vec ydot) const;  // starts with a comma

 private:
  const mechanics::MechanicsSystem& system_;
  std::shared_ptr<const mechanics::SurfacePressure> pressure_;
  std::shared_ptr<const contact::PenaltyContact> obstacle_;
};

}  // namespace needlefem::run
