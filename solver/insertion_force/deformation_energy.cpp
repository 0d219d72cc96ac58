// Elastic-energy history of a mechanics run and its power-law fit; see deformation_energy.hpp.
#include "insertion_force/deformation_energy.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "output/history_table.hpp"

namespace needlefem::insertion {

namespace {

// The run's insertion speed and contact mode from the case echoed in its summary.json.
void read_run_summary(const std::filesystem::path& summary_file, EnergySamples& samples) {
  const std::string file = summary_file.string();
  std::ifstream in(summary_file);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open (it gives the run's insertion speed)", file));
  try {
    const nlohmann::json echo = nlohmann::json::parse(in).at("case");
    samples.insertion_speed_m_per_s = echo.at("motion").at("insertion_speed_mm_per_s").get<double>() * 1e-3;
    const auto contact = echo.find("contact");
    samples.contact_mode = contact != echo.end() && contact->contains("mode") ? contact->at("mode").get<std::string>()
                                                                               : std::string("tied");
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(fmt::format("{}: no case.motion.insertion_speed_mm_per_s ({})", file, e.what()));
  }
}

}  // namespace

EnergySamples read_energy_history(const std::filesystem::path& history_csv) {
  const output::HistoryTable history = output::read_history_table(history_csv);
  const std::size_t time_column = history.column("time_s");
  const std::size_t energy_column = history.column("elastic_energy_j");
  EnergySamples samples;
  read_run_summary(history_csv.parent_path() / "summary.json", samples);
  for (const auto& row : history.rows) {
    samples.displacement_m.push_back(row[time_column] * samples.insertion_speed_m_per_s);
    samples.energy_j.push_back(row[energy_column]);
  }
  return samples;
}

double DeformationEnergy::energy_j(double x) const { return x > 0.0 ? coefficient * std::pow(x, exponent) : 0.0; }

double DeformationEnergy::force_n(double x) const {
  return x > 0.0 ? coefficient * exponent * std::pow(x, exponent - 1.0) : 0.0;
}

double DeformationEnergy::displacement_at_force_m(double force) const {
  return force > 0.0 ? std::pow(force / (coefficient * exponent), 1.0 / (exponent - 1.0)) : 0.0;
}

DeformationEnergy fit_deformation_energy(const EnergySamples& samples) {
  // Least squares of ln U = ln c + p ln x.
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  DeformationEnergy fit;
  for (std::size_t i = 0; i < samples.energy_j.size(); ++i) {
    const double x = samples.displacement_m[i], u = samples.energy_j[i];
    if (!(x > 0.0 && u > 0.0)) continue;
    const double lx = std::log(x), lu = std::log(u);
    n += 1;
    sx += lx;
    sy += lu;
    sxx += lx * lx;
    sxy += lx * lu;
    fit.largest_sample_m = std::max(fit.largest_sample_m, x);
  }
  const double spread = n * sxx - sx * sx;
  if (n < 2 || !(spread > 0.0))
    throw std::runtime_error("deformation energy: needs at least two samples with positive displacement and energy");
  fit.exponent = (n * sxy - sx * sy) / spread;
  fit.coefficient = std::exp((sy - fit.exponent * sx) / n);
  if (!(fit.exponent > 1.0))
    throw std::runtime_error(fmt::format(
        "deformation energy: the fitted U ~ x^{:.3g} gives a force that does not grow with displacement", fit.exponent));
  for (std::size_t i = 0; i < samples.energy_j.size(); ++i) {
    const double x = samples.displacement_m[i], u = samples.energy_j[i];
    if (x > 0.0 && u > 0.0)
      fit.max_relative_fit_error = std::max(fit.max_relative_fit_error, std::abs(fit.energy_j(x) - u) / u);
  }
  return fit;
}

}  // namespace needlefem::insertion
