// Deformation stage of paper 000's insertion force (Eq. 3.2, F_t = ΔU/Δx while the tissue only
// deforms): the tissue's elastic energy U against the needle's displacement x, from a mechanics
// run of the tied brain-tip scene (`needlefem run`: history.csv columns time_s and
// elastic_energy_j; the run's insertion speed v from the case echoed in its summary.json, x = v t).
//
// The samples are fitted with a power law U(x) = c x^p (least squares on ln U = ln c + p ln x over
// the samples with x, U > 0), which gives the force F_def(x) = dU/dx = c p x^(p-1) everywhere,
// including beyond the run's last sample (an extrapolation: the fit reports that range). For a
// linear elastic response p = 2 and F_def = k x with k = 2c; stiffening tissue gives p > 2.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace needlefem::insertion {

struct EnergySamples {
  std::vector<double> displacement_m;
  std::vector<double> energy_j;
  double insertion_speed_m_per_s = 0.0;  // of the run the samples come from
  // The run's contact.mode ("tied": cavity moved with the needle; "frictional": contact FEM);
  // runs from before contact existed echo none and were tied.
  std::string contact_mode;
};

// Reads FOLDER/history.csv and FOLDER/summary.json for a history file FOLDER/history.csv. Throws
// std::runtime_error "FILE: reason" for a missing file, column or speed, or unparsable numbers.
EnergySamples read_energy_history(const std::filesystem::path& history_csv);

struct DeformationEnergy {
  double coefficient = 0.0;  // c, J / m^p
  double exponent = 0.0;     // p > 1
  double largest_sample_m = 0.0;         // the fit is an extrapolation beyond this displacement
  double max_relative_fit_error = 0.0;   // max |c x^p - U| / U over the fitted samples

  double energy_j(double displacement_m) const;
  double force_n(double displacement_m) const;  // dU/dx
  double displacement_at_force_m(double force_n) const;  // inverse of force_n
};

// Throws std::runtime_error when fewer than two samples have x, U > 0 or the fit gives p <= 1
// (a force that does not grow with displacement has no rupture point).
DeformationEnergy fit_deformation_energy(const EnergySamples& samples);

}  // namespace needlefem::insertion
