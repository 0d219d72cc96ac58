// The contact stage's keys, parsed: the [contact] law (physics/contact/penalty_contact.hpp), the
// check of the needle's deflection under the contact loads (run/needle_output.hpp), and a mesh
// scene's obstacle ([obstacle], scene_obstacle.hpp). The needle in contact is built from the mesh
// spec's keys (its tip, needle.edge_radius_um, scene.mesh_file: case/specs/mesh_spec.hpp), the
// contact's face sizes follow its mesh.refinement_level. Values are in the units their keys name;
// the physics converts them to SI.
#pragma once

#include <array>
#include <string>

namespace needlefem {

class Case;

enum class ContactMode { frictional, tied };
enum class FrictionTangent { secant, consistent };
enum class FrictionLaw { return_map, velocity };
enum class NormalEnforcement { penalty, augmented };

struct ContactSpec {
  ContactMode mode;
  double friction_coefficient;
  double penalty_factor;
  double penalty_smoothing;
  double elastic_slip;
  double rate_strengthening_s_per_m;
  double slip_velocity_regularisation_mm_per_s;
  FrictionTangent friction_tangent;
  FrictionLaw friction_law;
  NormalEnforcement normal_enforcement;
};

ContactSpec parse_contact_spec(const Case& c);

// needle.deflection_check: the linear-elastic tip under the contact loads
// (physics/contact/needle_elasticity.hpp), with the needle's elastic constants.
struct NeedleDeflectionCheckSpec {
  std::string origin;         // the case's, for the CaseErrors of a tip or mesh the check cannot take
  bool enabled;               // needle.deflection_check
  double youngs_modulus_gpa;  // needle.youngs_modulus_gpa
  double poisson_ratio;       // needle.poisson_ratio
};

NeedleDeflectionCheckSpec parse_needle_deflection_check_spec(const Case& c);

enum class ObstacleKind { none, plane, sphere, needle };

struct ObstacleSpec {
  ObstacleKind kind;
  std::string group;  // the surface group it touches
  std::array<double, 3> point_mm;
  std::array<double, 3> normal;  // plane: outward, not zero
  double radius_mm;              // sphere
  std::array<double, 3> velocity_mm_per_s;
};

// The case's [obstacle] table. Throws CaseError (obstacle.normal) for a plane's zero normal.
ObstacleSpec parse_obstacle_spec(const Case& c);

// The kind's obstacle.kind value, for messages.
const char* obstacle_kind_name(ObstacleKind kind);

}  // namespace needlefem
