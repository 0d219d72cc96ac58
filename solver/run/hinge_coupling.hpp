// `needlefem run` of paper 000's compliant needle in the tissue (needle.kind = "compliant",
// contact.mode = "frictional"; paper 000's Fig. 7): the magnet pulls the head, which turns about
// the neck against the hinge spring and the tissue around it.
//
// Model. The head and the stem are rigid bodies in frictional contact with the tissue
// (physics/contact/hinged_needle.hpp); the neck is the pseudo-rigid-body torsion spring
// K = E I / l of steering/hinge.hpp (Eq. 2.6), measured against a finite-element model of the
// tip by `needlefem prbm-check`. The magnet is that of `needlefem steer` (steering.* keys): its
// schedule gives the distance and the pull's direction e (azimuth ψ) at time t, read at the depth
// steering.insertion_speed_mm_per_s · t; Eq. 2.3 gives B, Eq. 2.1-2.2 the pull F, acting as the
// paper assumes at the constant angle φ (steering.force_angle_deg) to the head's normal. The
// head's tilt θ (a rotation vector normal to the shaft) balances the moments about the pivot:
//   K θ = M_magnet + M_contact,   M_magnet = F cos φ (L + l)/2 · e_z × e,
// M_contact the (x, y) moment of the tissue's contact tractions on the head about the pivot
// (contact::NeedleContact::load_on_head; the moment about the shaft, which the neck's torsion
// carries, is reported, not balanced).
//
// Coupling: waveform relaxation on the whole history. Pass 1 prescribes the tilt of Eq. 2.7 with
// the case's tissue term (steering.tissue_spring_constant_n_per_m2) at the output times, linear
// in between; every pass solves the tissue with its tilt θ prescribed and gives M_contact at the
// output times. The tilt is balanced when |(M_magnet + M_contact)/K - θ| is within 0.1 % of the
// largest turning angle (and 1e-5 rad) at every output time; otherwise the next pass takes
//   θ' = (M_magnet + M_contact + k θ)/(K + k),
// k the tissue's rotational stiffness fitted to the pass (below), which has the same fixed point
// as θ' = (M_magnet + M_contact)/K but moves the tissue's linear part to the left: the plain
// update contracts only by k/K (measured 1 % for paper 000's needle in brain tissue, 0.14 deg off
// at 15 deg after the first pass), this one by the tissue's departure from linearity and by how
// well a pass repeats the contact moment (0.014 deg off after the second pass), so the second pass
// usually ends it. The files of the last pass stand, and summary.json says how far its
// tilt was from the balance. The balance holds at the output times: between them the tilt is
// linear in time (output.interval_s sets the sampling). All passes share one PETSc session.
//
// Outputs besides those of any run: DIR/hinge.csv (per output time: magnet distance, B, F, the
// FEM's head angle, Eq. 2.7's in air and with the fitted tissue term, the magnet's and the
// tissue's moments along the tilt's axis, the balance residual) and summary.json "hinge"
// (passes, residual, largest angle, K, and the tissue spring constant μ_t fitted to the FEM:
// M_t = μ_t/3 (l/2 + L)³ θ, Eq. 2.4, least squares over the output times, which `needlefem
// steer` takes as steering.tissue_spring_constant_n_per_m2).
#pragma once

#include <functional>

#include <nlohmann/json.hpp>

#include "run/run_case.hpp"
#include "run/run_specs.hpp"

namespace needlefem::run {

// One run of the case with the head's tilt prescribed (options.head_tilt); returns its summary.
using RunPass = std::function<nlohmann::json(const RunSpecs&, const RunOptions&)>;

// Runs passes until the tilt balances the hinge (see above); returns the final summary, also
// written to out_dir/summary.json. Throws CaseError for a magnet schedule that turns the head
// before the tissue has been loaded (at the first output time). The magnet and hinge are
// specs.hinge_steering (head_turns_in_tissue(specs) must hold).
nlohmann::json run_hinged_case(const RunSpecs& specs, const RunOptions& options, const RunPass& run_pass);

}  // namespace needlefem::run
