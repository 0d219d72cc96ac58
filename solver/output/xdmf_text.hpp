// XDMF 3 text for the datasets of a ResultFile (see result_file.hpp for the HDF5 layout).
// The XDMF holds no data, only references "file.h5:/dataset" (relative to the XDMF's
// folder). Time-series fields reference one dataset per time (HDF5 virtual datasets onto
// the [capacity, ...] arrays): ParaView's Xdmf3 readers skip HyperSlab DataItems in
// attributes ("Skipping unrecognized array type [None]", ParaView 5.11), so no hyperslabs.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace needlefem::output {

struct XdmfDataset {
  // HDF5 dataset path, e.g. "/static/node/temperature"; with per_time, a pattern whose
  // "{}" is replaced by the time index, e.g. "/series/steps/{}/displacement".
  std::string path;
  std::size_t entities = 0;        // nodes or cells
  int components = 1;              // 1 is written without a component dimension
  bool integer = false;            // 32-bit int, else 64-bit float
  bool per_time = false;
};

struct XdmfAttribute {
  std::string name;
  bool at_nodes = true;            // Center="Node", else Center="Cell"
  XdmfDataset data;
};

struct XdmfTopology {
  std::string name;                // grid name
  std::string topology_type;       // "Tetrahedron_10", "Tetrahedron", "Triangle_6", "Triangle"
  XdmfDataset connectivity;        // [cells, nodes per cell], integer
  std::vector<XdmfAttribute> attributes;
  std::vector<std::pair<std::string, std::string>> information;  // <Information Name Value>
};

struct XdmfDocument {
  std::string h5_file_name;        // referenced relative to the XDMF file
  XdmfDataset coordinates;         // [nodes, 3] float
  // One grid per topology. With several grids each time step is a spatial collection.
  std::vector<XdmfTopology> grids;
};

// The XDMF text. With `times` empty, one static grid (or spatial collection) without the
// time-series attributes; otherwise a temporal collection with one entry per listed time
// (times[i] is the time of index i of the time-series datasets).
std::string xdmf_text(const XdmfDocument& document, const std::vector<double>& times);

// Writes `text` to a temporary file next to `path`, then renames it over `path`, so a
// reader (or a process killed meanwhile) never sees a half-written file. On failure the
// temporary is removed and std::runtime_error says "PATH: cannot write: REASON" with the
// system's reason (e.g. "no space left on device").
void replace_file_atomically(const std::filesystem::path& path, const std::string& text);

// Several files replaced as one: every temporary is written before any is renamed, so a full
// disk leaves all the old files as they were (not one new and one old).
void replace_files_atomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

}  // namespace needlefem::output
