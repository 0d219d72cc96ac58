// One case's results: an HDF5 file plus an XDMF companion next to it that ParaView opens.
//
// HDF5 layout (all names fixed; readers such as postprocess/ rely on them):
//   /                          attribute "case": the resolved case as TOML text
//   /mesh/coordinates_mm       [nodes, 3]   node coordinates in MILLIMETRES (TetMesh is in
//                                           metres; the file is for viewing, as the .msh is)
//   /mesh/tets                 [tets, 10|4] node indices in XDMF/VTK order (gmsh's local
//                                           nodes 8 and 9 swapped for TET10)
//   /mesh/region               [tets]       region index; attribute "names" lists the regions
//   /mesh/surfaces/<name>      [faces, 6|3] named boundary faces (TRI6/TRI3; gmsh and VTK
//                                           agree on triangle node order)
//   /static/{node,cell}/<f>    [n] or [n, components]
//   /series/time               [capacity]   output times in seconds
//   /series/time_count         [1]          number of COMPLETED output times
//   /series/{node,cell}/<f>    [capacity, n] or [capacity, n, components]
//   /series/steps/<i>/<f>      [n] or [n, components]: time i of field f, a virtual
//                              dataset onto /series/*/<f> (what the XDMF references)
// Every field dataset carries attributes "unit" and "type". Fields are stored in the mesh's units
// where they have a length (displacement in mm, velocity in mm/s), so that ParaView's Warp By
// Vector at scale 1 moves the millimetre mesh by the displacement; the XDMF grid lists each
// field's unit as <Information Name="unit:FIELD" Value="UNIT"/>.
//
// Tensors are written with all 9 components, row-major (xx xy xz yx yy yz zx zy zz),
// AttributeType "Tensor". Symmetric tensors are passed in as 6 values (xx yy zz xy yz xz,
// VTK's order) and expanded. Why not XDMF "Tensor6": ParaView's two XDMF readers disagree
// about it (XDMFReader expands it from xx xy xz yy yz zz, Xdmf3Reader passes the 6 values
// through and VTK then reads them as xx yy zz xy yz xz), so the same file would show
// different components depending on the reader. Measured with ParaView 5.11.
//
// Crash safety (a process killed at any instant leaves a readable .h5 and .xdmf listing
// every completed output time). HDF5's SWMR mode was measured NOT to give this with HDF5
// 1.10.8: a killed SWMR writer leaves the superblock flagged "open for write", and every
// ordinary reader (ParaView, h5py without swmr=True) then refuses the file until `h5clear`.
// Design used instead: all HDF5 metadata is written once. Time-series datasets are
// contiguous, sized for `output_capacity` times and allocated when created (sparse on disk:
// fill values are never written), the per-time virtual datasets the XDMF references are
// created for every time up front (~0.8 kB of metadata per field and time, measured), and
// the file is flushed before the first output time.
// An output time then only writes raw bytes into space that already exists (sieve buffer
// off, so writes reach the OS at once): fields, then /series/time[i], then time_count. Only
// after that is the XDMF rewritten to a temporary file and renamed over the old one
// (atomic), listing times 0..i. The XDMF of a fresh file appears only once the mesh is
// flushed, and a stale one is removed before the .h5 is truncated. tests/output checks this
// by SIGKILLing a writer and by comparing the file's metadata bytes before and after.
// A write that fails (a full disk) takes its output time back: time_count is set back when the
// XDMF cannot be written, so the .h5 and both XDMF files list the same completed times (only a
// kill between the two can leave the XDMF one time behind, never ahead). Every error is one
// line: "PATH: cannot WHAT: REASON", REASON being the system's ("no space left on device").
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "model/tet_mesh.hpp"

namespace needlefem::output {

enum class FieldCentre { node, cell };
enum class FieldType { scalar, vector, symmetric_tensor, tensor };

struct FieldSpec {
  std::string name;  // unique among the fields of a file; used as HDF5 and XDMF name
  FieldCentre centre = FieldCentre::node;
  FieldType type = FieldType::scalar;
  std::string unit;  // of the stored values, written as an attribute, e.g. "Pa", "mm", "1"
  double scale = 1.0;  // stored value = caller's value x scale (1e3: the solver's metres to mm)
};

// Values per node/cell the caller passes: 1, 3, 6 (symmetric tensor) or 9.
int input_components(FieldType type);
// Values per node/cell stored in the file: 1, 3, 9, 9.
int stored_components(FieldType type);

class ResultFile {
 public:
  // Creates (truncates) `h5_path` and writes the mesh and the case. `time_series` declares
  // every field written at each output time, `output_capacity` the most output times the
  // file will hold (appending more is an error). Both may be empty/0 for a mesh-only file.
  ResultFile(const std::filesystem::path& h5_path, const TetMesh& mesh,
             const std::string& resolved_case_toml, std::vector<FieldSpec> time_series = {},
             std::size_t output_capacity = 0);
  ~ResultFile();  // closes (see close())
  ResultFile(const ResultFile&) = delete;
  ResultFile& operator=(const ResultFile&) = delete;

  // A time-independent field; only before the first append_time(). `values` holds
  // input_components(spec.type) values per node or cell, entity-major.
  void write_static_field(const FieldSpec& spec, std::span<const double> values);

  // One completed output time: one value array per declared time-series field, in the
  // declaration order. When this returns, the .h5 and .xdmf list this time; when it throws,
  // neither does.
  void append_time(double time_s, const std::vector<std::span<const double>>& values);

  // Flushes, writes the final XDMF and closes the file. Throws on HDF5 errors; the
  // destructor calls it and swallows errors.
  void close();

  std::size_t completed_times() const;
  const std::filesystem::path& h5_path() const;
  std::filesystem::path xdmf_path() const;  // h5 path with extension .xdmf

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The 10-node tet permutation from gmsh's local node order to XDMF/VTK's: entry k is the
// gmsh local index of the node written at VTK position k.
inline constexpr int kTet10GmshOfVtk[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

}  // namespace needlefem::output
