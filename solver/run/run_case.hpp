// `needlefem run`: one case from start to finish.
//   mesh (model/scene_model) -> MechanicsSystem with the case's loads (physics/mechanics, built
//   by run/run_model) -> IdaIntegrator advancing to every output time (run/output_schedule) ->
//   at each time the tissue fields (physics/fields) appended to DIR/result.h5 + .xdmf, a row of
//   DIR/history.csv (per-time maxima with positions, reaction force per named boundary surface,
//   elastic and kinetic energy; the needle's loads, run/needle_output.hpp; the mesh scene's
//   pressure and obstacle loads, run/mesh_scene_loads.hpp) and a progress line on `progress`;
//   finally DIR/summary.json (written atomically).
// DIR/summary.json says "status": "running" (with the case) from the start until it is replaced
// at the end, so a run killed outright never leaves a summary of another run or one that claims
// "completed"; its result.h5 then lists every completed output time (result.xdmf may lag one).
// A failure (IDA giving up, an inverted element, a full disk) leaves every completed output
// time readable in result.h5/.xdmf and history.csv (the XDMF lists exactly the times result.h5
// counts as complete), writes summary.json with "status": "failed" (or "interrupted") and the
// reason, and rethrows. The run holds an exclusive lock on DIR from before it changes anything
// there; a second run into a DIR that a live run holds is refused and leaves it untouched.
#pragma once

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/scene_model.hpp"
#include "run/run_specs.hpp"

namespace needlefem {
class Case;
}
namespace needlefem::contact {
class HeadTilt;
class Needle;
}

namespace needlefem::run {

struct RunOptions {
  std::filesystem::path out_dir;
  std::vector<std::string> petsc_options;  // passed unchanged to PETSc (e.g. -nf_ksp_type gmres)
  std::FILE* progress = stderr;            // one line per output time; nullptr for none
  // Raised (InterruptGuard: SIGINT, SIGTERM), the run stops after the IDA step in progress:
  // summary.json says "interrupted", the completed output times stay, Interrupted is thrown.
  const std::atomic<bool>* stop = nullptr;
  // The compliant tip's head tilt over time (run/hinge_coupling.hpp sets it for each pass).
  std::shared_ptr<const contact::HeadTilt> head_tilt;
};

// The scene a run solves: load_scene_model's mesh with its cavity moved onto the rounded needle
// in contact (contact::round_cavity_to_needle) and its quality measured again. `needlefem mesh`
// shows the same mesh. `needle` (optional): set to that needle (null without needle contact).
SceneModel load_run_scene(const RunSpecs& specs, const std::filesystem::path& out_dir,
                          std::FILE* progress, std::shared_ptr<const contact::Needle>* needle = nullptr);

// Returns the summary written to out_dir/summary.json. The compliant tip in frictional contact
// runs as the passes of run/hinge_coupling.hpp.
nlohmann::json run_case(const Case& c, const RunOptions& options);

}  // namespace needlefem::run
