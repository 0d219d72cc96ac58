// Reading .msh files: boundary faces come out oriented outward of their curved element.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "model/read_msh.hpp"
#include "model/tet_geometry.hpp"

using namespace needlefem;

namespace {

// A TET10 of the compliant tip's neck meshed with gmsh seed 4 (coordinates in mm, gmsh node
// order): its curved volume is positive but its four corners span an inverted straight
// tetrahedron, so orienting its faces by the corners points them inward.
constexpr std::array<std::array<double, 3>, 10> kNeckTet{{
    {0.01288202, -0.0991668, 0.91067196},   {0.00503023, -0.0998734, 0.67046141},
    {0.07264824, -0.06871851, 0.66765364},  {-0.2715753, -0.03424629, 0.78839187},
    {-0.017271, -0.09849727, 0.80593202},   {0.02884168, -0.0957505, 0.68069892},
    {0.03496221, -0.09368908, 0.80314615},  {-0.16194812, -0.14363235, 0.84033588},
    {-0.10248561, -0.18396348, 0.69030444}, {-0.1380613, -0.13224914, 0.71083671},
}};

// One tissue tet and its face (0, 1, 2) as the physical surface "cavity", in .msh 4.1 ASCII;
// the face is listed with the given corner order, mid-side nodes following it.
std::filesystem::path write_single_tet_msh(const std::filesystem::path& file, std::array<int, 3> face) {
  std::ofstream out(file);
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"cavity\"\n3 2 \"tissue\"\n"
         "$EndPhysicalNames\n$Entities\n0 0 1 1\n1 -1 -1 -1 1 1 1 1 1 0\n1 -1 -1 -1 1 1 1 1 2 0\n"
         "$EndEntities\n$Nodes\n1 10 1 10\n3 1 0 10\n";
  for (int i = 1; i <= 10; ++i) out << i << "\n";
  for (const auto& p : kNeckTet) out << fmt::format("{} {} {}\n", p[0], p[1], p[2]);
  // gmsh edge nodes of the tet: (0,1)=4 (1,2)=5 (2,0)=6; the face's mid nodes follow its corners.
  auto edge_node = [](int a, int b) {
    if ((a == 0 && b == 1) || (a == 1 && b == 0)) return 4;
    if ((a == 1 && b == 2) || (a == 2 && b == 1)) return 5;
    return 6;
  };
  out << "$EndNodes\n$Elements\n2 2 1 2\n2 1 9 1\n1";
  for (int k = 0; k < 3; ++k) out << " " << face[k] + 1;
  for (int k = 0; k < 3; ++k) out << " " << edge_node(face[k], face[(k + 1) % 3]) + 1;
  out << "\n3 1 11 1\n2";
  for (int i = 1; i <= 10; ++i) out << " " << i;
  out << "\n$EndElements\n";
  return file;
}

// The (corner) face normal's direction in the tet's own index order: +1 when the face is the
// cyclic order (0, 2, 1), the outward one of a positively oriented tet; -1 for (0, 1, 2).
int orientation_against_outward(const TetMesh& mesh) {
  const std::vector<int>& f = mesh.surface_faces.at("cavity");
  for (int shift = 0; shift < 3; ++shift) {
    const std::array<int, 3> cyclic{f[shift], f[(shift + 1) % 3], f[(shift + 2) % 3]};
    if (cyclic == std::array<int, 3>{0, 2, 1}) return 1;
    if (cyclic == std::array<int, 3>{0, 1, 2}) return -1;
  }
  return 0;
}

}  // namespace

TEST(ReadMsh, FacesOfACurvedTetWithInvertedCornersPointOutOfTheCurvedElement) {
  const auto dir = std::filesystem::temp_directory_path() / "needlefem_test_read_msh";
  std::filesystem::create_directories(dir);
  for (const std::array<int, 3> listed : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 1}}) {
    const TetMesh mesh = read_msh(write_single_tet_msh(dir / "neck_tet.msh", listed));
    ASSERT_EQ(mesh.tet_count(), 1u);
    const int* t = mesh.tet(0);
    ASSERT_GT(tet_volume(mesh, 0), 0.0);  // the curved element is positive ...
    ASSERT_LT(oriented_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]), 0.0);  // ... its corners not
    // Node indices follow the file, so tet-local and mesh indices coincide here.
    for (int i = 0; i < 10; ++i) ASSERT_EQ(t[i], i);
    EXPECT_EQ(orientation_against_outward(mesh), 1) << "face listed as " << listed[0] << listed[1] << listed[2];
    // Mid-side nodes stay with their edges after any flip: (0,2)=6, (2,1)=5, (1,0)=4.
    const std::vector<int>& f = mesh.surface_faces.at("cavity");
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3], mid = f[3 + k];
      EXPECT_EQ(mid, a + b == 1 ? 4 : a + b == 3 ? 5 : 6);
    }
  }
}
