// The physical model of one `needlefem run` pass, built in this one place: the tissue's mechanics
// system on the scene's mesh (physics/mechanics/mechanics_system.hpp) with every surface load the
// case puts on it, added in this order (the system sums their residuals in it):
//   the needle in contact   brain-tip scene, contact.mode = "frictional" (needle_contact.hpp);
//   the pressure s(t) p     mesh scene, groups.pressure (surface_pressure.hpp);
//   the obstacle's contact  mesh scene, obstacle.kind (scene_obstacle.hpp).
// Each contact follows the [contact] law scaled by the material's instantaneous shear modulus
// (run_contact_parameters). The run's outputs only observe these loads (run/needle_output.hpp,
// run/mesh_scene_loads.hpp).
// Here in run/ rather than in physics/: which loads a run has is decided by the run's specs
// (run_specs.hpp: needle_in_contact, the scene's kind); physics/ holds each load and knows no run.
#pragma once

#include <memory>

#include "run/run_specs.hpp"

namespace needlefem {
struct TetMesh;
}
namespace needlefem::contact {
class HeadTilt;
class Needle;
class NeedleContact;
class PenaltyContact;
}
namespace needlefem::material {
class Material;
}
namespace needlefem::mechanics {
class MechanicsSystem;
class SurfacePressure;
}

namespace needlefem::run {

struct RunModel {
  std::unique_ptr<mechanics::MechanicsSystem> system;
  // The loads added to `system`, null where the case has none. Shared with the outputs that
  // report them, which outlive the system (the summary is written after PETSc has gone).
  std::shared_ptr<const contact::NeedleContact> needle;
  std::shared_ptr<const mechanics::SurfacePressure> pressure;
  std::shared_ptr<const contact::PenaltyContact> obstacle;
};

// The model of `specs` on `mesh` (which must outlive it; PETSc must be initialised). `needle`: the
// needle the cavity was rounded to (load_run_scene; null without needle contact), in contact as it
// is, or built again with its head turned by `head_tilt` (the compliant tip's passes,
// run/hinge_coupling.hpp). Throws the CaseErrors of the system, the needle and the obstacle.
RunModel build_run_model(const RunSpecs& specs, const TetMesh& mesh, const material::Material& material,
                         std::shared_ptr<const contact::Needle> needle,
                         std::shared_ptr<const contact::HeadTilt> head_tilt);

}  // namespace needlefem::run
