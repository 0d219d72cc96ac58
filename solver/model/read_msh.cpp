#include "model/read_msh.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <new>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>
#include <gmsh.h>

#include "mesh/gmsh_session.hpp"
#include "model/tet_geometry.hpp"

namespace needlefem {

namespace {

constexpr double kMPerMm = 1e-3;
constexpr int kGmshTet4 = 4, kGmshTet10 = 11, kGmshTri3 = 2, kGmshTri6 = 9;

struct FaceKey {
  std::array<int, 3> corners;
  bool operator==(const FaceKey& o) const { return corners == o.corners; }
};
struct FaceKeyHash {
  std::size_t operator()(const FaceKey& k) const {
    return (static_cast<std::size_t>(k.corners[0]) * 73856093u) ^ (static_cast<std::size_t>(k.corners[1]) * 19349663u) ^
           (static_cast<std::size_t>(k.corners[2]) * 83492791u);
  }
};
FaceKey key_of(int a, int b, int c) {
  std::array<int, 3> k{a, b, c};
  std::sort(k.begin(), k.end());
  return {k};
}

bool is_tissue(const std::string& region) { return region.rfind("tissue", 0) == 0; }

// Whether tet e's fourth vertex lies on the side the face (a, b, c) points to by the right-hand
// rule: the sign of the element's volume with its vertices taken as (a, b, c, opposite), i.e.
// the permutation's parity times the sign of the element's exact (curved) volume. The straight
// tetrahedron of the corners would not do: at the compliant tip's 0.2 mm neck a valid TET10
// was measured with inverted corners (-5.3e-4 against +1.0e-3 mm^3 curved), which flipped
// its cavity face inward.
bool opposite_on_normal_side(const TetMesh& mesh, std::size_t e, int a, int b, int c) {
  const int* t = mesh.tet(e);
  std::array<int, 4> order{};  // local positions of a, b, c, opposite
  const std::array<int, 3> face{a, b, c};
  for (int k = 0; k < 3; ++k) order[k] = static_cast<int>(std::find(t, t + 4, face[k]) - t);
  order[3] = 6 - order[0] - order[1] - order[2];  // positions 0..3 sum to 6
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += order[i] > order[j] ? 1 : 0;
  const bool even = inversions % 2 == 0;
  return (tet_volume(mesh, e) > 0) == even;
}

// The elements of one physical group of the open gmsh model, per element type.
struct ElementBlock {
  int type;
  std::size_t count;
  std::vector<std::size_t> node_tags;
};
struct PhysicalGroup {
  std::string name;
  std::vector<ElementBlock> blocks;
};

std::vector<PhysicalGroup> physical_groups(int dim, const std::string& unnamed_prefix) {
  std::vector<PhysicalGroup> out;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  for (const auto& [group_dim, tag] : groups) {
    PhysicalGroup group;
    gmsh::model::getPhysicalName(group_dim, tag, group.name);
    if (group.name.empty()) group.name = fmt::format("{}_{}", unnamed_prefix, tag);
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(group_dim, tag, entities);
    for (int entity : entities) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, group_dim, entity);
      for (std::size_t t = 0; t < types.size(); ++t)
        group.blocks.push_back({types[t], element_tags[t].size(), std::move(node_tags[t])});
    }
    out.push_back(std::move(group));
  }
  return out;
}

// Reads the whole file with gmsh (nodes and every element block), throwing what gmsh throws.
void read_with_gmsh(const std::filesystem::path& file) {
  const GmshSession session("probe");
  gmsh::open(file.string());
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  gmsh::model::mesh::getElements(types, element_tags, element_nodes, -1, -1);
}

}  // namespace

void require_readable_msh(const std::filesystem::path& file) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::runtime_error(file.string() + ": cannot check the mesh (pipe)");
  std::fflush(nullptr);  // nothing buffered may be written twice
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    throw std::runtime_error(file.string() + ": cannot check the mesh (fork)");
  }
  if (child == 0) {
    ::close(pipe_fds[0]);
    std::string message;
    try {
      read_with_gmsh(file);
    } catch (const std::string& gmsh_message) {
      message = "gmsh: " + gmsh_message;
    } catch (const std::bad_alloc&) {
      message = "gmsh ran out of memory reading it (a damaged count in $Nodes or $Elements?)";
    } catch (const std::exception& e) {
      message = e.what();
    }
    if (!message.empty()) {
      [[maybe_unused]] const auto written = ::write(pipe_fds[1], message.data(), message.size());
    }
    ::_exit(message.empty() ? 0 : 1);  // no atexit handlers, no flushing the parent's buffers
  }
  ::close(pipe_fds[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof buffer)) != 0;) {
    if (n > 0) message.append(buffer, static_cast<std::size_t>(n));
    else if (errno != EINTR) break;
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  if (WIFSIGNALED(status))
    throw std::runtime_error(fmt::format("{}: gmsh's reader crashed on it ({}); is the .msh damaged?", file.string(),
                                         strsignal(WTERMSIG(status))));
  throw std::runtime_error(fmt::format("{}: {}", file.string(), message.empty() ? "gmsh cannot read it" : message));
}

namespace {

std::runtime_error mesh_error(const std::filesystem::path& file, const std::string& reason) {
  return std::runtime_error(file.string() + ": " + reason);
}

// What the .msh holds: every node (gmsh tags, coordinates in mm) and the triangles of each
// physical surface (node tags); the tetrahedra of each physical volume go into `mesh` (node tags,
// regions, nodes per tet).
struct MshContent {
  std::vector<std::size_t> node_tags;
  std::vector<double> coords;
  std::vector<std::pair<std::string, std::vector<std::size_t>>> surfaces;
};

MshContent read_groups(const std::filesystem::path& file, TetMesh& mesh) {
  MshContent content;
  int element_type = 0;
  try {
    gmsh::open(file.string());
    std::vector<double> parametric;
    gmsh::model::mesh::getNodes(content.node_tags, content.coords, parametric, -1, -1, false, false);
    for (const auto& group : physical_groups(3, "volume")) {
      const int region = static_cast<int>(mesh.region_names.size());
      mesh.region_names.push_back(group.name);
      for (const auto& [type, count, nodes] : group.blocks) {
        if (type != kGmshTet10 && type != kGmshTet4)
          throw mesh_error(file, fmt::format("region '{}' has gmsh element type {}; only 4- and 10-node tetrahedra "
                                             "are supported", group.name, type));
        if (element_type && element_type != type) throw mesh_error(file, "mixes 4- and 10-node tetrahedra");
        element_type = type;
        for (std::size_t tag : nodes) mesh.tet_nodes.push_back(static_cast<int>(tag));
        mesh.tet_region.insert(mesh.tet_region.end(), count, region);
      }
    }
    for (const auto& group : physical_groups(2, "surface")) {
      std::vector<std::size_t> face_nodes;
      for (const auto& [type, count, nodes] : group.blocks) {
        if (type != kGmshTri3 && type != kGmshTri6)
          throw mesh_error(file, fmt::format("surface '{}' has gmsh element type {}; expected triangles", group.name, type));
        face_nodes.insert(face_nodes.end(), nodes.begin(), nodes.end());
      }
      content.surfaces.emplace_back(group.name, std::move(face_nodes));
    }
  } catch (const std::string& message) {
    throw mesh_error(file, "gmsh: " + message);
  }
  if (std::none_of(mesh.region_names.begin(), mesh.region_names.end(), is_tissue))
    throw mesh_error(file, "no physical volume whose name starts with 'tissue'");
  if (mesh.tet_region.empty()) throw mesh_error(file, "no tetrahedra in the physical volumes");
  mesh.nodes_per_tet = element_type == kGmshTet10 ? 10 : 4;
  return content;
}

// Numbers the nodes the tetrahedra use compactly, in gmsh's node order, and stores them (metres)
// in `mesh`, its tetrahedra renumbered. Returns each gmsh tag's node (-1: in no tetrahedron).
std::unordered_map<std::size_t, int> number_nodes(const MshContent& content, TetMesh& mesh) {
  std::unordered_map<std::size_t, std::size_t> position;
  for (std::size_t i = 0; i < content.node_tags.size(); ++i) position[content.node_tags[i]] = i;
  std::vector<int> index_of(content.node_tags.size(), -1);
  for (int& tag : mesh.tet_nodes) {
    const std::size_t p = position.at(static_cast<std::size_t>(tag));
    if (index_of[p] < 0) index_of[p] = 0;
    tag = static_cast<int>(p);
  }
  int next = 0;
  const auto& x = content.coords;
  for (std::size_t p = 0; p < index_of.size(); ++p)
    if (index_of[p] == 0) {
      index_of[p] = next++;
      mesh.nodes.push_back({x[3 * p] * kMPerMm, x[3 * p + 1] * kMPerMm, x[3 * p + 2] * kMPerMm});
    }
  for (int& p : mesh.tet_nodes) p = index_of[p];
  std::unordered_map<std::size_t, int> node_of_tag;
  for (const auto& [tag, p] : position) node_of_tag[tag] = index_of[p];
  return node_of_tag;
}

// Every tet face, with its owner tet: tissue tets first (faces are oriented outward of the
// tissue), or needle tets first (outward of the needle).
using FaceOwners = std::unordered_map<FaceKey, std::size_t, FaceKeyHash>;
FaceOwners face_owners(const TetMesh& mesh, bool tissue_first) {
  FaceOwners owner;
  static const int face_corners[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
      if (is_tissue(mesh.region_names[mesh.tet_region[e]]) != ((pass == 0) == tissue_first)) continue;
      const int* t = mesh.tet(e);
      for (const auto& f : face_corners) owner.emplace(key_of(t[f[0]], t[f[1]], t[f[2]]), e);
    }
  return owner;
}

// The surface groups as faces of `mesh`, oriented outward of the tissue (of the needle for
// surfaces named "needle*").
void add_surfaces(const std::filesystem::path& file, const MshContent& content,
                  const std::unordered_map<std::size_t, int>& node_of_tag, TetMesh& mesh) {
  const FaceOwners tissue_owner = face_owners(mesh, true);
  FaceOwners needle_owner;
  const int per_face = mesh.nodes_per_face();
  for (const auto& [name, tags] : content.surfaces) {
    std::vector<int>& faces = mesh.surface_faces[name];
    const bool needle_side = name.rfind("needle", 0) == 0;
    if (needle_side && needle_owner.empty()) needle_owner = face_owners(mesh, false);
    const FaceOwners& owner = needle_side ? needle_owner : tissue_owner;
    for (std::size_t f = 0; f + per_face <= tags.size(); f += per_face) {
      std::array<int, 6> v{};
      for (int k = 0; k < per_face; ++k) {
        const auto it = node_of_tag.find(tags[f + k]);
        if (it == node_of_tag.end() || it->second < 0)
          throw mesh_error(file, fmt::format("surface '{}' has a node that belongs to no tetrahedron", name));
        v[k] = it->second;
      }
      const auto own = owner.find(key_of(v[0], v[1], v[2]));
      if (own == owner.end()) throw mesh_error(file, fmt::format("surface '{}' has a face that bounds no tetrahedron", name));
      if (opposite_on_normal_side(mesh, own->second, v[0], v[1], v[2])) {
        // Flip to point outward.
        std::swap(v[1], v[2]);
        if (per_face == 6) std::swap(v[3], v[5]);
      }
      faces.insert(faces.end(), v.begin(), v.begin() + per_face);
    }
  }
}

}  // namespace

TetMesh read_msh(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw mesh_error(file, "mesh file not found");
  TetMesh mesh;
  GmshSession session("read");
  const MshContent content = read_groups(file, mesh);
  const auto node_of_tag = number_nodes(content, mesh);
  add_surfaces(file, content, node_of_tag, mesh);
  return mesh;
}

}  // namespace needlefem
