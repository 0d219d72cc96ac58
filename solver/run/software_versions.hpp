// What built the binary that wrote a summary.json: needlefem's version and git commit (refreshed
// at every build by git_commit.cmake; "unknown" outside a git checkout) and the versions of the
// libraries it was compiled against (PETSc, SUNDIALS, gmsh API, HDF5), so that a study report can
// say which software produced each run.
#pragma once

#include <nlohmann/json.hpp>

namespace needlefem::run {

// {"needlefem": "0.1.0", "commit": "7ad91a0c1f2e" (with "-dirty" for uncommitted changes),
//  "petsc": "3.18.5", "sundials": "6.4.1", "gmsh_api": "4.8.0", "hdf5": "1.10.8"}
nlohmann::json software_versions();

}  // namespace needlefem::run
