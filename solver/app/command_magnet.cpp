// `needlefem magnet`: paper 000's block magnet and compliant-needle hinge as JSON.
//   --turning-angle-deg A...  -> flux density (Eq. 2.8), pull force (Eq. 2.1-2.2), magnet distance (Eq. 2.3 root)
//   --distance-mm X...        -> flux density (Eq. 2.3), pull force, turning angle (Eq. 2.7)
// Defaults are the paper's worked example (l = 1 mm, L = 3.5 mm, d = 0.2 mm, pole 50 x 60 mm,
// steel neck, pull along the head, no tissue, turning 15 and 30 deg: 0.0391 and 0.0553 T), so
// `needlefem magnet` alone prints it. The paper gives no residual flux density or thickness for
// its magnet; the defaults (N42 NdFeB, 20 mm) are stated in --help and echoed.
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "steering/hinge.hpp"
#include "steering/magnet.hpp"

namespace needlefem::app {

namespace {

struct MagnetOptions {
  double neck_length_mm = 1.0;
  double neck_diameter_mm = 0.2;
  double head_length_mm = 3.5;
  double youngs_modulus_gpa = 200.0;
  double tissue_spring_constant_pa = 0.0;
  double force_angle_deg = 0.0;
  double residual_flux_density_t = 1.3;
  double pole_width_mm = 50.0;
  double pole_length_mm = 60.0;
  double thickness_mm = 20.0;
  double correction_factor = 0.85;
  std::vector<double> turning_angles_deg;
  std::vector<double> distances_mm;
};

constexpr double deg = std::numbers::pi / 180.0;
// Paper 000's worked example: these angles need 0.0391 and 0.0553 T.
const std::vector<double> kWorkedExampleAnglesDeg{15.0, 30.0};

nlohmann::json run(const MagnetOptions& o) {
  const steering::CompliantNeedleHinge hinge{o.neck_length_mm * 1e-3, o.neck_diameter_mm * 1e-3,
                                             o.head_length_mm * 1e-3, o.youngs_modulus_gpa * 1e9,
                                             o.tissue_spring_constant_pa};
  const steering::BlockMagnet magnet{o.residual_flux_density_t, o.pole_width_mm * 1e-3, o.pole_length_mm * 1e-3,
                                     o.thickness_mm * 1e-3, o.correction_factor};
  hinge.validate();
  magnet.validate();
  const double gap_area = magnet.pole_area_m2();
  const double phi = o.force_angle_deg * deg;

  nlohmann::json out;
  out["needle"] = {{"neck_length_mm", o.neck_length_mm},
                   {"neck_diameter_mm", o.neck_diameter_mm},
                   {"head_length_mm", o.head_length_mm},
                   {"youngs_modulus_gpa", o.youngs_modulus_gpa},
                   {"tissue_spring_constant_pa", o.tissue_spring_constant_pa},
                   {"force_angle_deg", o.force_angle_deg},
                   {"hinge_stiffness_n_m_per_rad", hinge.hinge_stiffness_n_m_per_rad()},
                   {"tissue_stiffness_n_m_per_rad", hinge.tissue_stiffness_n_m_per_rad()}};
  out["magnet"] = {{"residual_flux_density_t", o.residual_flux_density_t},
                   {"pole_width_mm", o.pole_width_mm},
                   {"pole_length_mm", o.pole_length_mm},
                   {"thickness_mm", o.thickness_mm},
                   {"correction_factor", o.correction_factor},
                   {"gap_area_m2", gap_area},
                   {"flux_density_at_face_t", steering::axial_flux_density_t(magnet, 0.0)}};

  auto& results = out["results"] = nlohmann::json::array();
  for (double angle_deg : o.turning_angles_deg) {
    const double flux = steering::flux_density_for_turning_angle_t(hinge, angle_deg * deg, gap_area, phi);
    // A permanent magnet's field never exceeds its residual flux density Br, at any distance:
    // a turning angle that needs more cannot be had from it, and a number above Br is no answer.
    if (!(flux < o.residual_flux_density_t))
      throw std::invalid_argument(fmt::format("--turning-angle-deg {:.6g}: needs a flux density of {:.3g} T, above the "
                                              "magnet's residual flux density Br = {:.3g} T", angle_deg, flux,
                                              o.residual_flux_density_t));
    nlohmann::json row = {{"turning_angle_deg", angle_deg},
                          {"flux_density_t", flux},
                          {"force_n", steering::gap_force_n(flux, gap_area)}};
    if (flux < steering::axial_flux_density_t(magnet, 0.0))
      row["distance_mm"] = steering::distance_for_flux_density_m(magnet, flux) * 1e3;
    else
      row["distance_mm"] = nullptr;  // this magnet is too weak even at its face
    results.push_back(row);
  }
  for (double distance_mm : o.distances_mm) {
    if (!(distance_mm >= 0.0)) throw std::invalid_argument(fmt::format("--distance-mm must be >= 0, got {}", distance_mm));
    const double flux = steering::axial_flux_density_t(magnet, distance_mm * 1e-3);
    results.push_back({{"distance_mm", distance_mm},
                       {"flux_density_t", flux},
                       {"force_n", steering::gap_force_n(flux, gap_area)},
                       {"turning_angle_deg", steering::turning_angle_for_flux_density_rad(hinge, flux, gap_area, phi) / deg}});
  }
  return out;
}

}  // namespace

void add_magnet_command(CLI::App& app) {
  auto o = std::make_shared<MagnetOptions>();
  auto* command = app.add_subcommand(
      "magnet",
      "Paper 000's magnet-steered compliant needle: flux density, pull force, magnet distance and head turning\n"
      "angle (Eq. 2.1-2.3, 2.7, 2.8 with the gap area A_g), printed as JSON. Defaults: the paper's worked example\n"
      "(15 and 30 deg need 0.0391 and 0.0553 T); `needlefem magnet` alone prints it.");
  auto* by_angle = command->add_option("--turning-angle-deg", o->turning_angles_deg,
                                       "Wanted head turning angle(s) -> flux density, force, magnet distance "
                                       "[15 30 without --distance-mm: the worked example]");
  auto* by_distance = command->add_option("--distance-mm", o->distances_mm,
                                          "Magnet distance(s) on the pole axis -> flux density, force, turning angle");
  by_angle->excludes(by_distance);
  command->add_option("--neck-length-mm", o->neck_length_mm, "Hinge (weakened neck) length l")->capture_default_str();
  command->add_option("--neck-diameter-mm", o->neck_diameter_mm, "Hinge diameter d")->capture_default_str();
  command->add_option("--head-length-mm", o->head_length_mm, "Magnetised head length L")->capture_default_str();
  command->add_option("--youngs-modulus-gpa", o->youngs_modulus_gpa, "Neck Young's modulus E (steel)")
      ->capture_default_str();
  command->add_option("--tissue-spring-constant-pa", o->tissue_spring_constant_pa,
                      "Tissue spring constant mu_t per unit length (N/m^2); 0 = in air")
      ->capture_default_str();
  command->add_option("--force-angle-deg", o->force_angle_deg, "Angle phi between the pull and the head")
      ->capture_default_str();
  command->add_option("--residual-flux-density-t", o->residual_flux_density_t,
                      "Magnet residual flux density Br (not in paper 000; N42 NdFeB)")
      ->capture_default_str();
  command->add_option("--pole-width-mm", o->pole_width_mm, "Magnet pole width W")->capture_default_str();
  command->add_option("--pole-length-mm", o->pole_length_mm, "Magnet pole length L")->capture_default_str();
  command->add_option("--thickness-mm", o->thickness_mm, "Magnet thickness T along the magnetisation (not in paper 000)")
      ->capture_default_str();
  command->add_option("--correction-factor", o->correction_factor, "Correction on Eq. 2.3 (paper: 0.8-0.9)")
      ->capture_default_str();
  command->callback([o] {
    if (o->turning_angles_deg.empty() && o->distances_mm.empty()) o->turning_angles_deg = kWorkedExampleAnglesDeg;
    fmt::print("{}\n", run(*o).dump(2));
  });
}

}  // namespace needlefem::app
