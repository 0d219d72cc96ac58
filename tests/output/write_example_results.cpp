// Writes the two files the ParaView check opens (tests/output/CMakeLists.txt):
//   DIR/static_mesh.h5/.xdmf (+ _surfaces.xdmf): a TET10 cube with static fields,
//   DIR/series.h5/.xdmf: the same mesh with three output times.
// Field values are chosen so that their ranges are known in closed form (see CMakeLists.txt).
#include <cstdio>
#include <exception>
#include <filesystem>

#include "output/result_file.hpp"
#include "test_meshes.hpp"

using namespace needlefem;
using namespace needlefem::output;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    const TetMesh mesh = testing::kuhn_cube(0.010, true);  // 27 nodes, 6 TET10, 10 mm edge
    const std::size_t nodes = mesh.nodes.size(), cells = mesh.tet_count();

    {
      ResultFile file(dir / "static_mesh.h5", mesh, "[example]\nkind = \"static\"\n");
      std::vector<double> node_index(nodes), position(nodes * 3), identity(cells * 9, 0.0);
      for (std::size_t n = 0; n < nodes; ++n) {
        node_index[n] = static_cast<double>(n);
        for (int c = 0; c < 3; ++c) position[3 * n + c] = mesh.nodes[n][c];
      }
      for (std::size_t e = 0; e < cells; ++e) identity[9 * e] = identity[9 * e + 4] = identity[9 * e + 8] = 1.0;
      file.write_static_field({"node_index", FieldCentre::node, FieldType::scalar, "1"}, node_index);
      file.write_static_field({"position", FieldCentre::node, FieldType::vector, "m"}, position);
      file.write_static_field({"identity", FieldCentre::cell, FieldType::tensor, "1"}, identity);
      file.close();
    }
    {
      ResultFile file(dir / "series.h5", mesh, "[example]\nkind = \"series\"\n",
                      {{"displacement", FieldCentre::node, FieldType::vector, "m"},
                       {"pressure", FieldCentre::node, FieldType::scalar, "Pa"},
                       {"stress", FieldCentre::cell, FieldType::symmetric_tensor, "Pa"}},
                      5);
      std::vector<double> node_index(nodes);
      for (std::size_t n = 0; n < nodes; ++n) node_index[n] = static_cast<double>(n);
      file.write_static_field({"node_index", FieldCentre::node, FieldType::scalar, "1"}, node_index);
      for (double t : {0.0, 0.5, 1.0}) {
        // displacement t(1, 2, 3); pressure 100 t + node index; stress t(xx..xz = 1..6).
        std::vector<double> displacement(nodes * 3), pressure(nodes), stress(cells * 6);
        for (std::size_t n = 0; n < nodes; ++n) {
          for (int c = 0; c < 3; ++c) displacement[3 * n + c] = t * (c + 1);
          pressure[n] = 100 * t + static_cast<double>(n);
        }
        for (std::size_t e = 0; e < cells; ++e)
          for (int k = 0; k < 6; ++k) stress[6 * e + k] = t * (k + 1);
        file.append_time(t, {displacement, pressure, stress});
      }
      file.close();
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "write_example_results: %s\n", error.what());
    return 1;
  }
  return 0;
}
