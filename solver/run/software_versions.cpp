#include "run/software_versions.hpp"

#include <H5public.h>
#include <gmsh.h>
#include <petscversion.h>
#include <sundials/sundials_config.h>

#include <fmt/core.h>

#include "git_commit.hpp"  // generated in the build tree (solver/run/git_commit.cmake)

namespace needlefem::run {

nlohmann::json software_versions() {
  return {{"needlefem", kNeedlefemVersion},
          {"commit", kGitCommit},
          {"petsc", fmt::format("{}.{}.{}", PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR, PETSC_VERSION_SUBMINOR)},
          {"sundials", SUNDIALS_VERSION},
          {"gmsh_api", GMSH_API_VERSION},
          {"hdf5", fmt::format("{}.{}.{}", H5_VERS_MAJOR, H5_VERS_MINOR, H5_VERS_RELEASE)}};
}

}  // namespace needlefem::run
