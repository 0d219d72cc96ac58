// What `needlefem run` reports of the needle of the brain-tip scene in frictional contact
// (contact.mode = "frictional", physics/contact/needle_contact.hpp; run/run_model.hpp builds the
// contact and adds it to the mechanics system), at every output time:
//   history.csv  needle_force_{x,y,z}_n, needle_moment_{x,y,z}_n_m (on the needle, moment about
//                the centre of its rear face; z = axial force and torque about the axis),
//                contact_area_mm2 (reference area of the cavity in contact),
//                needle_lateral_force_{xi,eta}_n (the force across the axis in the needle's own
//                frame, turned with it: what steers a bevel tip; geometry/needle_tip.hpp's ξ, η);
//   result.h5    node fields contact_pressure (Pa) and contact_slip (mm): values at the cavity
//                nodes, 0 at every other node (result.h5 holds tet cells only, so the cavity
//                faces carry no cells of their own; ParaView shows them on the tissue surface);
//   summary.json "needle": largest |axial force|, |torque| and lateral force over the output times
//                with their histories, and "contact": the initial gap of the cavity against the
//                needle and the penalty parameters;
//                with needle.deflection_check, "needle"."deflection_check": the steel tip's
//                largest elastic deflection under the contact loads over the output times
//                (physics/contact/needle_elasticity.hpp), beside the contact's own resolution
//                (the smallest elastic slip s₀) and the needle's travel.
// The compliant tip (hinged_needle.hpp) adds, at every output time, the load on its head alone:
//   history.csv  head_angle_deg (the tilt's length), head_tilt_{x,y}_rad (the tilt vector),
//                head_moment_{x,y}_n_m (the contact's moment on the head about the pivot);
//   summary.json "head": those moments and tilts over the output times (run/hinge_coupling.hpp
//                balances them against the hinge spring and the magnet).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <petscvec.h>

#include "output/result_file.hpp"
#include "physics/contact/needle_contact.hpp"
#include "physics/contact/needle_elasticity.hpp"

namespace needlefem {
struct NeedleDeflectionCheckSpec;
}
namespace needlefem::mechanics {
class MechanicsSystem;
}

namespace needlefem::run {

class NeedleOutput {
 public:
  // The needle's `contact`, a load of the run model's `system` (which must outlive every
  // evaluate()), with the deflection `check` on the needle region of `mesh`. Throws CaseError
  // (needle.deflection_check) for the compliant tip and for a needle region the check cannot use.
  NeedleOutput(const NeedleDeflectionCheckSpec& check, const TetMesh& mesh, const mechanics::MechanicsSystem& system,
               std::shared_ptr<const contact::NeedleContact> contact);

  static std::vector<output::FieldSpec> field_specs();
  std::string history_header() const;  // starts with a comma

  // Evaluates the needle load and the surface fields of the state (y, y') at time t.
  void evaluate(double t, Vec y, Vec ydot);
  // Of the last evaluate(): node field values in field_specs() order, and the history cells.
  const std::vector<double>& pressure() const { return fields_.pressure; }
  const std::vector<double>& slip() const { return fields_.slip; }
  std::string history_cells() const;  // starts with a comma
  const contact::NeedleLoad& load() const { return load_; }

  nlohmann::json summary() const;
  // Frees the deflection check's PETSc objects (call before PETSc is finalised; summary() keeps
  // what it found).
  void release_solvers() { elasticity_.reset(); }

 private:
  const mechanics::MechanicsSystem& system_;
  std::shared_ptr<const contact::NeedleContact> contact_;
  contact::NeedleContact::InitialGap initial_gap_;
  contact::NeedleLoad load_;
  contact::NeedleContact::SurfaceFields fields_;
  std::vector<double> times_, axial_force_, torque_, lateral_force_magnitude_;
  std::array<double, 2> lateral_force_{};  // (ξ, η) in the needle's frame, of the last evaluate()
  contact::NeedleLoad head_load_;                       // compliant tip, of the last evaluate()
  std::array<double, 2> head_tilt_{};                   // rad, of the last evaluate()
  std::vector<std::array<double, 2>> head_moments_, head_tilts_;  // over the output times
  std::unique_ptr<contact::NeedleElasticity> elasticity_;  // needle.deflection_check
  contact::NeedleElasticity::Deflection largest_deflection_;
  double largest_deflection_time_ = 0.0, needle_travel_m_ = 0.0, elasticity_seconds_ = 0.0;
  double youngs_modulus_pa_ = 0.0, poisson_ratio_ = 0.0;
  bool deflection_check_ = false;
  std::size_t needle_dofs_ = 0, needle_elements_ = 0;
};

}  // namespace needlefem::run
