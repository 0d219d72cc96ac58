// TOML of the block scenes the mechanics tests mesh (sizes in mm as in case files).
#pragma once

#include <string>

namespace needlefem::mechanics::testing {

inline std::string block_case(const std::string& faces, const std::string& gradient, const std::string& material,
                              double element_mm = 0.5, int order = 2, const std::string& formulation = "mixed",
                              const std::string& size_mm = "[1.0, 1.0, 1.0]") {
  return "[scene]\nkind = \"block\"\n[block]\nsize_mm = " + size_mm + "\nelement_mm = " + std::to_string(element_mm) +
         "\n" + faces + "applied_gradient = " + gradient + "\n[loading]\nramp_s = 1e-6\n[mesh]\norder = " +
         std::to_string(order) + "\n[element]\nformulation = \"" + formulation + "\"\n[material]\n" + material;
}

inline const std::string kAllFacesDisplaced =
    "x_min = \"displacement\"\nx_max = \"displacement\"\ny_min = \"displacement\"\ny_max = \"displacement\"\n"
    "z_min = \"displacement\"\nz_max = \"displacement\"\n";

}  // namespace needlefem::mechanics::testing
