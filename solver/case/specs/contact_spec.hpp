// The contact stage's keys, parsed: the [contact] law (physics/contact/penalty_contact.hpp), what
// the needle in contact reads beyond its tip's shape (needle_contact.hpp; the shape:
// geometry/needle_tip.hpp) with the check of its deflection under the contact loads
// (run/needle_output.hpp), and a mesh scene's obstacle ([obstacle], scene_obstacle.hpp).
// Values are in the units their keys name; the physics converts them to SI.
#pragma once

#include <array>
#include <filesystem>
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
  // mesh.refinement_level: the contact scales its face sizes by 2^level to keep the level-0 mesh's
  // enforcement.
  long mesh_refinement_level;
};

ContactSpec parse_contact_spec(const Case& c);

// needle.deflection_check: the linear-elastic tip under the contact loads
// (physics/contact/needle_elasticity.hpp), with the needle's elastic constants.
struct NeedleDeflectionCheckSpec {
  bool enabled;               // needle.deflection_check
  double youngs_modulus_gpa;  // needle.youngs_modulus_gpa
  double poisson_ratio;       // needle.poisson_ratio
};

struct NeedleContactSpec {
  std::string origin;                     // the case's, for the CaseErrors of rules checked against the mesh
  double edge_radius_um;                  // needle.edge_radius_um
  std::filesystem::path scene_mesh_file;  // scene.mesh_file, resolved; empty: the generated mesh
  NeedleDeflectionCheckSpec deflection_check;
};

NeedleContactSpec parse_needle_contact_spec(const Case& c);

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
