// The rigid obstacle a mesh-scene case places ([obstacle], scene.kind = "mesh"), in frictional
// contact (penalty_contact.hpp, with the [contact] law) with the surface group obstacle.group:
//   plane   the solid half-space behind the plane through obstacle.point_mm with outward normal
//           obstacle.normal (TranslatingPlane);
//   sphere  the solid ball of radius obstacle.radius_mm centred at obstacle.point_mm
//           (TranslatingSphere);
//   both translating at obstacle.velocity_mm_per_s;
//   needle  the rigid needle of [needle] (bevel tip; bevel_deg = 90 and fillet_mm = 0 make a
//           flat-ended punch, fillet_mm = radius_mm a round-ended rod) moved by [motion]
//           (needle_obstacle.hpp): axis along z, tip towards +z, the centre of its rear face at
//           obstacle.point_mm at t = 0 (OffsetObstacle).
#pragma once

#include <memory>

#include "physics/contact/penalty_contact.hpp"

namespace needlefem::contact {

struct NeedleSpecs;

// The contact of the case's obstacle `spec` with spec.group of `mesh` (which must outlive it), by
// the [contact] law `parameters` (contact_parameters_from_spec); nullptr for obstacle.kind =
// "none". `needle`: the needle obstacle's tip and motion (needle_from_spec), needed only for
// obstacle.kind = "needle".
std::shared_ptr<PenaltyContact> scene_obstacle_contact(const ObstacleSpec& spec, const NeedleSpecs* needle,
                                                       const ContactParameters& parameters, const TetMesh& mesh);

}  // namespace needlefem::contact
