// ResultFile: mesh, fields and case read back from the HDF5 file with plain HDF5 calls.
#include "output/result_file.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <set>
#include <sstream>

#include "h5_read.hpp"
#include "test_meshes.hpp"

namespace needlefem::output {
namespace {

using testing::H5Reader;

// ---------------------------------------------------------------------------------------
// Isoparametric 10-node tet volume, V = ∫ det(∂x/∂ξ) dξ over the reference tet. det J is a
// cubic in ξ, so any quadrature exact to degree 3 gives V exactly (to round-off). The edge
// table says which vertex pair local node 4 + k sits on: that is the only thing that
// differs between gmsh's and VTK's node orders.
using EdgeTable = std::array<std::array<int, 2>, 6>;
constexpr EdgeTable kGmshEdgeTable{{{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}};
constexpr EdgeTable kVtkEdgeTable{{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};  // VTK_QUADRATIC_TETRA

struct QuadraturePoint {
  std::array<double, 3> xi;
  double weight;
};

// Keast's 5-point rule, degree 3 (weights sum to 1/6).
std::vector<QuadraturePoint> keast_degree3() {
  std::vector<QuadraturePoint> rule{{{0.25, 0.25, 0.25}, -2.0 / 15.0}};
  const double a = 1.0 / 6.0, b = 0.5;
  for (const auto& xi : {std::array{a, a, a}, std::array{b, a, a}, std::array{a, b, a}, std::array{a, a, b}})
    rule.push_back({xi, 3.0 / 40.0});
  return rule;
}

// Collapsed (Duffy) 3x3x3 Gauss-Legendre rule: ξ1 = u, ξ2 = v(1-u), ξ3 = w(1-u)(1-v),
// dξ = (1-u)²(1-v) du dv dw; exact for degree 3 on the tet. Independent of Keast's.
std::vector<QuadraturePoint> collapsed_gauss_3x3x3() {
  const double g[3] = {0.5 - std::sqrt(0.15), 0.5, 0.5 + std::sqrt(0.15)};
  const double w[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  std::vector<QuadraturePoint> rule;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const double u = g[i], v = g[j], t = g[k];
        rule.push_back({{u, v * (1 - u), t * (1 - u) * (1 - v)}, w[i] * w[j] * w[k] * (1 - u) * (1 - u) * (1 - v)});
      }
  return rule;
}

double tet10_volume(const std::array<Point3, 10>& x, const EdgeTable& edges, const std::vector<QuadraturePoint>& rule) {
  double volume = 0;
  for (const QuadraturePoint& q : rule) {
    const double L[4] = {1 - q.xi[0] - q.xi[1] - q.xi[2], q.xi[0], q.xi[1], q.xi[2]};
    // dL_i/dξ_j: L0 = 1 - ξ1 - ξ2 - ξ3, L(j+1) = ξ(j+1).
    const double dL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    double J[3][3] = {};
    auto add = [&](const Point3& p, const double (&dN)[3]) {
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) J[r][c] += p[r] * dN[c];
    };
    for (int v = 0; v < 4; ++v) {  // N = L(2L - 1)
      const double dN[3] = {(4 * L[v] - 1) * dL[v][0], (4 * L[v] - 1) * dL[v][1], (4 * L[v] - 1) * dL[v][2]};
      add(x[v], dN);
    }
    for (int e = 0; e < 6; ++e) {  // N = 4 La Lb
      const int a = edges[e][0], b = edges[e][1];
      double dN[3];
      for (int c = 0; c < 3; ++c) dN[c] = 4 * (dL[a][c] * L[b] + L[a] * dL[b][c]);
      add(x[4 + e], dN);
    }
    const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                       J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                       J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    volume += q.weight * det;
  }
  return volume;
}

std::filesystem::path scratch(const std::string& name) {
  std::filesystem::path dir = std::filesystem::current_path() / "output_test_files";
  std::filesystem::create_directories(dir);
  return dir / name;
}

// The volume test's mesh: a 10 mm Kuhn cube with curved edges. Moves whose effect on the
// total volume is known in closed form: (a) the main-diagonal node is inside the cube:
// moving it reshapes all six tets but not their union; (b) a mid-node on a face diagonal
// moved by δ along the outward normal bulges the face by the height δ·N(ξ) over both
// triangles sharing the edge, adding δ·∫N dA = δ·(A1 + A2)/3 = δ·edge²/3 (an edge shape
// function integrates to A/3 over a triangle); (c) a mid-node moved along its own cube
// edge keeps every face plane and the union unchanged, but curves the parametrisation.
struct CurvedCube {
  TetMesh mesh;
  double exact_volume;
};

CurvedCube curved_cube() {
  const double edge = 0.010;
  CurvedCube cube{testing::kuhn_cube(edge, true), edge * edge * edge};
  auto move = [&](int a, int b, Point3 by) {
    Point3& p = cube.mesh.nodes[testing::edge_node(cube.mesh, a, b)];
    for (int c = 0; c < 3; ++c) p[c] += by[c];
  };
  move(0, 7, {0.0011, -0.0007, 0.0004});            // (a) main diagonal
  const double bulge_z = 0.0009, dent_x = -0.0006;
  move(4, 7, {0, 0, bulge_z});                      // (b) top face z = edge, outward +z
  move(1, 7, {dent_x, 0, 0});                       // (b) face x = edge, outward +x: a dent
  move(0, 1, {0.0013, 0, 0});                       // (c) along the x edge
  cube.exact_volume += (bulge_z + dent_x) * edge * edge / 3;
  return cube;
}

TEST(ResultFile, Tet10VolumeInWrittenNodeOrderEqualsMeshVolume) {
  const CurvedCube cube = curved_cube();
  const std::filesystem::path path = scratch("volume.h5");
  ResultFile(path, cube.mesh, "[case]\n").close();

  H5Reader file(path.string());
  const std::vector<double> xyz_mm = file.read<double>("/mesh/coordinates_mm");
  const std::vector<int> tets = file.read<int>("/mesh/tets");
  ASSERT_EQ(file.dims("/mesh/tets"), (std::vector<hsize_t>{6, 10}));

  double written_total = 0, gmsh_total = 0;
  for (std::size_t e = 0; e < cube.mesh.tet_count(); ++e) {
    std::array<Point3, 10> written, gmsh;
    for (int k = 0; k < 10; ++k) {
      const int n = tets[e * 10 + k];
      written[k] = {xyz_mm[3 * n] / 1000, xyz_mm[3 * n + 1] / 1000, xyz_mm[3 * n + 2] / 1000};
      gmsh[k] = cube.mesh.nodes[cube.mesh.tet(e)[k]];
    }
    const double written_volume = tet10_volume(written, kVtkEdgeTable, collapsed_gauss_3x3x3());
    const double gmsh_volume = tet10_volume(gmsh, kGmshEdgeTable, keast_degree3());
    EXPECT_GT(gmsh_volume, 0) << "tet " << e;
    EXPECT_NEAR(written_volume, gmsh_volume, 1e-12 * std::abs(gmsh_volume)) << "tet " << e;
    written_total += written_volume;
    gmsh_total += gmsh_volume;
  }
  EXPECT_NEAR(gmsh_total, cube.exact_volume, 1e-12 * cube.exact_volume);
  EXPECT_NEAR(written_total, cube.exact_volume, 1e-12 * cube.exact_volume);
  RecordProperty("written_volume_relative_error", std::to_string(std::abs(written_total / cube.exact_volume - 1)));
  std::printf("exact volume %.17g m^3, written (VTK order) %.17g, relative error %.3g\n", cube.exact_volume,
              written_total, std::abs(written_total / cube.exact_volume - 1));

  // Reading the written connectivity as if it were gmsh-ordered must get it wrong: the
  // check above is sensitive to the 8/9 swap on this mesh.
  double misread_total = 0;
  for (std::size_t e = 0; e < cube.mesh.tet_count(); ++e) {
    std::array<Point3, 10> written;
    for (int k = 0; k < 10; ++k) {
      const int n = tets[e * 10 + k];
      written[k] = {xyz_mm[3 * n] / 1000, xyz_mm[3 * n + 1] / 1000, xyz_mm[3 * n + 2] / 1000};
    }
    misread_total += std::abs(tet10_volume(written, kGmshEdgeTable, keast_degree3()) -
                              tet10_volume(written, kVtkEdgeTable, keast_degree3()));
  }
  EXPECT_GT(misread_total, 1e-3 * cube.exact_volume);
}

TEST(ResultFile, Tet4MeshRegionsCaseAndCoordinatesInMillimetres) {
  const TetMesh mesh = testing::kuhn_cube(0.002, false);
  const std::filesystem::path path = scratch("tet4.h5");
  const std::string case_toml = "[needle]\nradius_mm = 0.5\n";
  ResultFile(path, mesh, case_toml).close();

  H5Reader file(path.string());
  EXPECT_EQ(file.read<int>("/mesh/tets"), mesh.tet_nodes);
  EXPECT_EQ(file.read<int>("/mesh/region"), mesh.tet_region);
  EXPECT_EQ(file.text_attribute("/mesh/region", "names"), mesh.region_names);
  EXPECT_EQ(file.text_attribute("/", "case"), std::vector<std::string>{case_toml});
  EXPECT_EQ(file.text_attribute("/mesh/coordinates_mm", "unit"), std::vector<std::string>{"mm"});
  const std::vector<double> xyz_mm = file.read<double>("/mesh/coordinates_mm");
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(xyz_mm[3 * n + c], 1000 * mesh.nodes[n][c], 1e-12);

  std::ifstream xdmf(path.parent_path() / "tet4.xdmf");
  std::stringstream text;
  text << xdmf.rdbuf();
  EXPECT_NE(text.str().find(R"(TopologyType="Tetrahedron" NumberOfElements="6")"), std::string::npos);
  EXPECT_NE(text.str().find(R"(Value="0=tissue, 1=needle")"), std::string::npos);
}

TEST(ResultFile, StaticAndTimeSeriesFieldsReadBack) {
  const TetMesh mesh = testing::kuhn_cube(0.001, true);
  const std::size_t nodes = mesh.nodes.size(), cells = mesh.tet_count();
  const std::filesystem::path path = scratch("fields.h5");
  {
    ResultFile file(path, mesh, "",
                    {{"displacement", FieldCentre::node, FieldType::vector, "m"},
                     {"stress", FieldCentre::cell, FieldType::symmetric_tensor, "Pa"}},
                    4);
    std::vector<double> temperature(nodes), gradient(cells * 9);
    for (std::size_t n = 0; n < nodes; ++n) temperature[n] = 300 + n;
    for (std::size_t k = 0; k < gradient.size(); ++k) gradient[k] = 0.5 * k;
    file.write_static_field({"temperature", FieldCentre::node, FieldType::scalar, "K"}, temperature);
    file.write_static_field({"gradient", FieldCentre::cell, FieldType::tensor, "1"}, gradient);
    for (int step = 0; step < 3; ++step) {
      std::vector<double> displacement(nodes * 3), stress(cells * 6);
      for (std::size_t k = 0; k < displacement.size(); ++k) displacement[k] = step + 0.01 * k;
      for (std::size_t c = 0; c < cells; ++c)  // xx yy zz xy yz xz
        for (int k = 0; k < 6; ++k) stress[6 * c + k] = 100.0 * step + 10.0 * c + k;
      file.append_time(0.25 * step, {displacement, stress});
      EXPECT_EQ(file.completed_times(), step + 1u);
    }
    EXPECT_THROW(file.write_static_field({"late", FieldCentre::node, FieldType::scalar, ""}, temperature),
                 std::logic_error);
    EXPECT_THROW(file.append_time(1.0, {temperature, temperature}), std::invalid_argument);
  }
  H5Reader file(path.string());
  EXPECT_EQ(file.read<double>("/static/node/temperature")[5], 305);
  EXPECT_EQ(file.read<double>("/static/cell/gradient")[13], 6.5);
  EXPECT_EQ(file.text_attribute("/static/node/temperature", "unit"), std::vector<std::string>{"K"});
  EXPECT_EQ(file.read<long long>("/series/time_count"), std::vector<long long>{3});
  EXPECT_EQ(file.read<double>("/series/time", -1).at(2), 0.5);
  EXPECT_EQ(file.dims("/series/node/displacement"), (std::vector<hsize_t>{4, nodes, 3}));
  EXPECT_EQ(file.read<double>("/series/node/displacement", 2)[7], 2.07);
  // Symmetric tensor of cell 1 at step 2 expanded to xx xy xz yx yy yz zx zy zz.
  const std::vector<double> stress = file.read<double>("/series/cell/stress", 2);
  const double base = 200 + 10;
  const std::vector<double> expected{base + 0, base + 3, base + 5, base + 3, base + 1,
                                     base + 4, base + 5, base + 4, base + 2};
  EXPECT_EQ(std::vector<double>(stress.begin() + 9, stress.begin() + 18), expected);
}

TEST(ResultFile, CapacityAndInputErrors) {
  const TetMesh mesh = testing::kuhn_cube(0.001, false);
  const std::filesystem::path path = scratch("errors.h5");
  std::vector<double> pressure(mesh.nodes.size(), 1.0);
  EXPECT_THROW(ResultFile(path, mesh, "", {{"p", FieldCentre::node, FieldType::scalar, "Pa"}}, 0),
               std::invalid_argument);
  ResultFile file(path, mesh, "", {{"p", FieldCentre::node, FieldType::scalar, "Pa"}}, 1);
  EXPECT_THROW(file.write_static_field({"p", FieldCentre::node, FieldType::scalar, "Pa"}, pressure),
               std::invalid_argument);  // name taken
  EXPECT_THROW(file.write_static_field({"bad/name", FieldCentre::node, FieldType::scalar, ""}, pressure),
               std::invalid_argument);
  EXPECT_THROW(file.write_static_field({"short", FieldCentre::cell, FieldType::scalar, ""}, pressure),
               std::invalid_argument);  // node count given for a cell field
  file.append_time(0.0, {pressure});
  EXPECT_THROW(file.append_time(1.0, {pressure}), std::length_error);
}

// /dev/full answers every write with ENOSPC: a symlink to it gives one file a full disk.
void link_to_full_disk(const std::filesystem::path& link) {
  std::filesystem::remove(link);
  std::filesystem::create_symlink("/dev/full", link);
}

// The distinct output times an XDMF file lists.
std::set<double> xdmf_times(const std::filesystem::path& xdmf) {
  std::ifstream in(xdmf);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  std::set<double> times;
  const std::regex time_value(R"(<Time Value="([^"]+)\"/>)");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), time_value); it != std::sregex_iterator(); ++it)
    times.insert(std::stod((*it)[1]));
  return times;
}

// A failed HDF5 write is one line: the file's path and the system's reason (HDF5's stack
// once went to stderr, and the error said only "HDF5: cannot create").
TEST(ResultFile, FullDiskIsNamedWithThePathInOneLine) {
  const TetMesh mesh = testing::kuhn_cube(0.001, false);
  const std::filesystem::path path = scratch("full_disk.h5");
  link_to_full_disk(path);
  ::testing::internal::CaptureStderr();
  try {
    ResultFile file(path, mesh, "", {{"p", FieldCentre::node, FieldType::scalar, "Pa"}}, 2);
    ADD_FAILURE() << "a result file on a full disk was created";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + ": cannot create the file: no space left on device");
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  std::filesystem::remove(path);
}

// When the XDMF of an output time cannot be written, result.h5 takes that time back: both
// XDMF files and time_count list the same completed times, never one more in either.
TEST(ResultFile, AnXdmfThatCannotBeWrittenTakesItsTimeBack) {
  const TetMesh mesh = testing::kuhn_cube(0.001, true);
  const std::filesystem::path path = scratch("xdmf_full.h5");
  const std::filesystem::path surfaces_tmp = scratch("xdmf_full_surfaces.xdmf.tmp");
  std::vector<double> pressure(mesh.nodes.size(), 1.0);
  {
    ResultFile file(path, mesh, "", {{"p", FieldCentre::node, FieldType::scalar, "Pa"}}, 4);
    file.append_time(0.0, {pressure});
    file.append_time(0.5, {pressure});
    link_to_full_disk(surfaces_tmp);
    try {
      file.append_time(1.0, {pressure});
      ADD_FAILURE() << "an output time was appended with its XDMF on a full disk";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("xdmf_full_surfaces.xdmf: cannot write: no space left on device"),
                std::string::npos) << e.what();
    }
    EXPECT_EQ(file.completed_times(), 2u);
    EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(surfaces_tmp))) << "temporary left behind";
    EXPECT_FALSE(std::filesystem::exists(scratch("xdmf_full.xdmf.tmp"))) << "temporary left behind";
    EXPECT_EQ(H5Reader(path.string()).read<long long>("/series/time_count"), std::vector<long long>{2});
    const std::set<double> two{0.0, 0.5};
    EXPECT_EQ(xdmf_times(file.xdmf_path()), two);
    EXPECT_EQ(xdmf_times(scratch("xdmf_full_surfaces.xdmf")), two);
    file.append_time(1.0, {pressure});  // space again: the file goes on from where it was
  }
  EXPECT_EQ(H5Reader(path.string()).read<long long>("/series/time_count"), std::vector<long long>{3});
  EXPECT_EQ(xdmf_times(scratch("xdmf_full.xdmf")), (std::set<double>{0.0, 0.5, 1.0}));
}

}  // namespace
}  // namespace needlefem::output
