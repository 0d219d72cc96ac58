#include "model/tet_mesh.hpp"

#include <algorithm>

namespace needlefem {

int TetMesh::region_index(const std::string& name) const {
  auto it = std::find(region_names.begin(), region_names.end(), name);
  return it == region_names.end() ? -1 : static_cast<int>(it - region_names.begin());
}

}  // namespace needlefem
