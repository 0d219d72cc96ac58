// Equations: scene_obstacle.hpp.
#include "physics/contact/scene_obstacle.hpp"

#include "case/case.hpp"
#include "geometry/needle_motion.hpp"
#include "physics/contact/needle_contact.hpp"

namespace needlefem::contact {

namespace {

constexpr double kMetresPerMm = 1e-3;

Point3 point_in_metres(const Case& input, const std::string& key) {
  const std::vector<double> v = input.reals(key);
  return {v[0] * kMetresPerMm, v[1] * kMetresPerMm, v[2] * kMetresPerMm};
}

std::shared_ptr<const RigidObstacle> scene_obstacle(const Case& input) {
  const std::string kind = input.text("obstacle.kind");
  const Point3 velocity = point_in_metres(input, "obstacle.velocity_mm_per_s");
  if (kind == "plane") {
    const std::vector<double> n = input.reals("obstacle.normal");
    if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) throw input.error("obstacle.normal", "must not be zero");
    return std::make_shared<TranslatingPlane>(point_in_metres(input, "obstacle.point_mm"), Point3{n[0], n[1], n[2]},
                                              velocity);
  }
  if (kind == "sphere")
    return std::make_shared<TranslatingSphere>(point_in_metres(input, "obstacle.point_mm"),
                                               input.real("obstacle.radius_mm") * kMetresPerMm, velocity);
  if (kind == "needle")
    return std::make_shared<OffsetObstacle>(needle_from_case(input), point_in_metres(input, "obstacle.point_mm"));
  return nullptr;
}

}  // namespace

std::shared_ptr<PenaltyContact> scene_obstacle_contact(const Case& input, const TetMesh& mesh,
                                                       double reference_modulus) {
  auto obstacle = scene_obstacle(input);
  if (!obstacle) return nullptr;
  return std::make_shared<PenaltyContact>(mesh, input.text("obstacle.group"), std::move(obstacle),
                                          contact_parameters_from_case(input, reference_modulus));
}

}  // namespace needlefem::contact
