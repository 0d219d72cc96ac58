// The case parsed once into the specs of the stages a run goes through (run_case.cpp; `needlefem
// mesh` shows its scene, load_run_scene): each stage gets its own spec rather than the case and
// its keys.
#pragma once

#include <optional>

#include "case/specs/contact_spec.hpp"
#include "case/specs/integration_spec.hpp"
#include "case/specs/loading_spec.hpp"
#include "case/specs/mechanics_spec.hpp"
#include "case/specs/mesh_spec.hpp"
#include "case/specs/motion_spec.hpp"
#include "case/specs/output_spec.hpp"
#include "case/specs/pressure_spec.hpp"
#include "case/specs/scene_kind.hpp"
#include "case/specs/thresholds_spec.hpp"
#include "steering/steering_case.hpp"

namespace needlefem {
class Case;
}
namespace needlefem::contact {
struct ContactParameters;
struct NeedleSpecs;
}

namespace needlefem::run {

// The mesh spec alone parses scene.mesh_file, mesh.refinement_level and needle.edge_radius_um:
// the mechanics (the file its errors name), the contact (its face sizes) and the needle in
// contact take them from it; the run, the loading and the boundary take the scene's kind from it.
// The boundary (in `mechanics`) holds the loading (loading()) and takes contact.mode from `contact`.
struct RunSpecs {
  MechanicsSpec mechanics;
  ContactSpec contact;
  MeshSpec mesh;  // with the needle tip and the tissue cube a CAD tip's rules check it against
  NeedleDeflectionCheckSpec needle_deflection_check;
  ObstacleSpec obstacle;
  PressureSpec pressure;
  IntegrationSpec integration;
  ThresholdsSpec thresholds;
  OutputSpec output;
  // The needle's motion, where the run builds a needle: the needle in contact, or a mesh scene's
  // needle obstacle. (A tied cavity's motion is the boundary spec's, in `mechanics`.)
  std::optional<MotionSpec> needle_motion;
  // The magnet and hinge of a compliant tip turning in tissue (head_turns_in_tissue), with the
  // schedule's rules checked: the hinge coupling's input (run/hinge_coupling.hpp).
  std::optional<steering::SteeringSetup> hinge_steering;

  // How long and how the scene is loaded: the boundary's copy, the one the Dirichlet conditions use.
  const LoadingSpec& loading() const { return mechanics.boundary.loading; }
};

// Throws the CaseErrors of the stages' parsers, the needle's motion's and the steering's last.
RunSpecs parse_run_specs(const Case& c);

// True when the case's needle is the compliant tip in frictional contact: its head turns on the
// hinge while the needle moves (run/hinge_coupling.hpp).
bool head_turns_in_tissue(const RunSpecs& specs);

// True for the brain-tip scene with contact.mode = "frictional": the needle is in contact with
// the cavity (physics/contact/needle_contact.hpp), which is rounded to it, and the contact is a
// load of the run. A tied cavity moves with the needle by Dirichlet conditions instead.
bool needle_in_contact(const RunSpecs& specs);

// The [contact] law in SI units for each contact of the run (the needle's, a mesh scene's
// obstacle): the penalty scaled by `reference_modulus` μ₀, the tissue's instantaneous shear
// modulus, the multiplier updates spread over the scene's loading history (mechanics::history_end),
// the face sizes by the mesh's refinement level.
contact::ContactParameters run_contact_parameters(const RunSpecs& specs, double reference_modulus);

// What the run's needle (in contact, or a mesh scene's needle obstacle) is built from: the mesh
// spec with the needle's motion. Only for runs that build a needle (specs.needle_motion is set).
contact::NeedleSpecs run_needle_specs(const RunSpecs& specs);

}  // namespace needlefem::run
