// Discretisation error of one quantity from three systematically refined meshes: observed
// order, Richardson extrapolation and Roache's grid convergence index (GCI), following the
// procedure of Celik et al. (2008), "Procedure for estimation and reporting of uncertainty due
// to discretization in CFD applications", J. Fluids Eng. 130:078001, and Roache (1998),
// "Verification and Validation in Computational Science and Engineering", Hermosa.
//
// f1 is the finest mesh's value, f2 the middle, f3 the coarsest; the element size shrinks by
// the constant ratio r = h2/h1 = h3/h2 (r = 2: each mesh.refinement_level halves the sizes):
//   e32 = f3 - f2,  e21 = f2 - f1,  R = e21/e32
//   observed order      p  = ln|e32/e21| / ln r                    (Celik's step 3, r21 = r32)
//   Richardson          f_ext = (r^p f1 - f2)/(r^p - 1)            (step 4)
//   fine-grid GCI       GCI = Fs |e21/f1| / (r^p - 1),  Fs = 1.25  (step 5; Roache's Fs for 3 meshes)
//   band                [f1 - GCI |f1|, f1 + GCI |f1|]
// Celik takes |ln|e32/e21||; the signed logarithm here makes growing differences (p < 0) show
// as such instead of as a positive order.
// The band is centred on f1, the value the finest run reports: GCI bounds f1's error, and
// f_ext is only as good as the assumption that all three meshes are in the asymptotic range.
//
// Cases (checked in this order):
//   converged   |e21| and |e32| both <= 1e-12 |f1|: the quantity does not depend on the mesh;
//               GCI 0, no order ("n/a"), f_ext = f1.
//   oscillatory R < 0: no order, no extrapolation. Band half-width Fs_osc (max - min)/2 with
//               Fs_osc = 3: Stern et al. (2001, J. Fluids Eng. 123:793) bound oscillatory
//               convergence by half the spread of the solutions, and Roache's factor 3 is the
//               one he gives where the order has not been verified.
//   divergent   |e21| >= |e32| (p <= 0): the differences do not shrink; treated as oscillatory.
//               That band bounds the error only where the steps are the meshes' scatter, which
//               the same case over mesh.seed measures; where a step exceeds that spread it is a
//               trend, and three levels give it no band (Stern et al. 2001 give divergence no estimate).
//               postprocess/standing.py makes that check from the converge and seed tables.
//   monotone    0 <= R < 1. The observed order is reported as measured. Above the formal
//               order 2 (that of the strains and stresses of quadratic elements, the
//               displacement gradients) f_ext uses 2: a larger p would claim more than the
//               discretisation delivers. From 2.05 on the band is also at least Fs times the
//               data range Δ_M = max - min of the three values, as in Eça & Hoekstra's procedure
//               (2014, J. Comput. Phys. 262:104; Δ_M their data-range estimator): an order that
//               high says the first step was not in the asymptotic range, not that the second
//               is, and with p = 2 alone the band (Fs |e21| / 3) missed the fourth level on the
//               study's tips whose three levels claimed it (docs/accuracy.md §14). Below 0.5 the meshes
//               are not in the asymptotic range: f_ext and GCI keep the observed order (raising
//               it would narrow the band: at p = 0.11, the strain rate's order in
//               docs/study.md's core-size study, r^p - 1 = 0.08 puts f_ext 13 |e21| from f1)
//               and Fs becomes 3, Roache's factor for an order that has not been verified. The
//               note says when either acted.
//   incomplete  a value is missing (NaN): nothing is estimated.
// Verdict against an upper limit: pass if the band's upper end < limit, fail if its lower end
// > limit, undecided otherwise (the limit lies inside the band, or the value is missing).
#pragma once

#include <string>
#include <vector>

namespace needlefem::convergence {

struct Settings {
  double ratio = 2.0;                     // r, element-size ratio between consecutive meshes
  double safety_factor = 1.25;            // Fs for three meshes with an observed order
  double oscillatory_safety_factor = 3.0; // Fs_osc on half the spread when there is no order
  double min_order = 0.5;                 // below: not asymptotic, Fs_osc instead of Fs
  double max_order = 2.0;                 // formal order: f_ext and GCI use at most this
  double data_range_order = 2.05;         // from this observed order on, the band is at least Fs Δ_M
  double mesh_independent_tolerance = 1e-12;  // relative to |f1|
};

enum class Behaviour { converged, monotone, oscillatory, divergent, incomplete };
enum class Verdict { pass, fail, undecided };

struct Estimate {
  double coarse = 0, medium = 0, fine = 0;  // f3, f2, f1
  Behaviour behaviour = Behaviour::incomplete;
  double observed_order = 0;  // p from the data (NaN when there is none)
  double order = 0;           // p used in f_ext and GCI: at most max_order (NaN when none)
  double extrapolated = 0;    // f_ext (NaN when none)
  double half_width = 0;      // GCI |f1|, the band's half-width in the quantity's unit
  double gci_fine = 0;        // relative: half_width / |f1| (NaN when f1 = 0)
  double band_low = 0, band_high = 0;
  std::string note;           // why there is no order, or that it is outside [min_order, max_order]
};

// The three values in mesh order: coarsest, middle, finest.
Estimate estimate(double coarse, double medium, double fine, const Settings& settings = {});

// Verdict of an estimate against an upper limit.
Verdict verdict(const Estimate& estimate, double limit);

// "n/a" for a mesh-independent quantity, the behaviour's name when there is no order, else
// the observed order in shortest form.
std::string order_text(const Estimate& estimate);
// A value as the tables write it (9 significant digits), "" when it is not finite.
std::string number_text(double value);
// The table cells of an estimate: observed order (order_text, "" when incomplete), f_extrapolated,
// gci_fine, band_low, band_high.
std::vector<std::string> estimate_cells(const Estimate& estimate);
const char* to_string(Behaviour behaviour);
const char* to_string(Verdict verdict);

}  // namespace needlefem::convergence
