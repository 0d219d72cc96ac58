#include "output/xdmf_text.hpp"

#include <cerrno>
#include <cstdio>
#include <stdexcept>

#include <fmt/format.h>

#include "io_errors/io_errors.hpp"

namespace needlefem::output {
namespace {

std::string dimensions(const XdmfDataset& data) {
  std::string text = fmt::format("{}", data.entities);
  if (data.components > 1) text += fmt::format(" {}", data.components);
  return text;
}

std::string number_type(const XdmfDataset& data) {
  return data.integer ? R"(NumberType="Int" Precision="4")" : R"(NumberType="Float" Precision="8")";
}

std::string data_item(const XdmfDocument& document, const XdmfDataset& data,
                      std::size_t time_index, const std::string& indent) {
  const std::string path = data.per_time ? fmt::format(fmt::runtime(data.path), time_index) : data.path;
  return fmt::format("{}<DataItem Dimensions=\"{}\" {} Format=\"HDF\">{}:{}</DataItem>\n", indent,
                     dimensions(data), number_type(data), document.h5_file_name, path);
}

std::string attribute_type(int components) {
  switch (components) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 9: return "Tensor";
    default: throw std::logic_error(fmt::format("XDMF: no attribute type with {} components", components));
  }
}

// Without a time, per-time attributes are left out: the file then shows the mesh and the
// static fields (the state of a run killed before its first output time).
std::string grid(const XdmfDocument& document, const XdmfTopology& topology,
                 const double* time, std::size_t time_index, const std::string& indent) {
  std::string text = fmt::format("{}<Grid Name=\"{}\" GridType=\"Uniform\">\n", indent, topology.name);
  const std::string inner = indent + "  ";
  if (time) text += fmt::format("{}<Time Value=\"{:.17g}\"/>\n", inner, *time);
  for (const auto& [name, value] : topology.information)
    text += fmt::format("{}<Information Name=\"{}\" Value=\"{}\"/>\n", inner, name, value);
  text += fmt::format("{}<Topology TopologyType=\"{}\" NumberOfElements=\"{}\">\n", inner,
                      topology.topology_type, topology.connectivity.entities);
  text += data_item(document, topology.connectivity, 0, inner + "  ");
  text += fmt::format("{}</Topology>\n{}<Geometry GeometryType=\"XYZ\">\n", inner, inner);
  text += data_item(document, document.coordinates, 0, inner + "  ");
  text += fmt::format("{}</Geometry>\n", inner);
  for (const XdmfAttribute& attribute : topology.attributes) {
    if (attribute.data.per_time && !time) continue;
    text += fmt::format("{}<Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"{}\">\n", inner,
                        attribute.name, attribute_type(attribute.data.components),
                        attribute.at_nodes ? "Node" : "Cell");
    text += data_item(document, attribute.data, time_index, inner + "  ");
    text += fmt::format("{}</Attribute>\n", inner);
  }
  return text + indent + "</Grid>\n";
}

// One time (or the static state): a single grid, or a spatial collection of all grids.
std::string state(const XdmfDocument& document, const double* time, std::size_t time_index,
                  const std::string& indent) {
  if (document.grids.size() == 1) return grid(document, document.grids.front(), time, time_index, indent);
  std::string text = fmt::format("{}<Grid Name=\"surfaces\" GridType=\"Collection\" "
                                 "CollectionType=\"Spatial\">\n", indent);
  if (time) text += fmt::format("{}  <Time Value=\"{:.17g}\"/>\n", indent, *time);
  for (const XdmfTopology& topology : document.grids)
    text += grid(document, topology, time, time_index, indent + "  ");
  return text + indent + "</Grid>\n";
}

}  // namespace

std::string xdmf_text(const XdmfDocument& document, const std::vector<double>& times) {
  std::string text =
      "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
  if (times.empty()) {
    text += state(document, nullptr, 0, "    ");
  } else {
    text += "    <Grid Name=\"time_series\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t i = 0; i < times.size(); ++i) text += state(document, &times[i], i, "      ");
    text += "    </Grid>\n";
  }
  return text + "  </Domain>\n</Xdmf>\n";
}

void replace_files_atomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files) {
  const auto temporary = [](const std::filesystem::path& path) { return path.string() + ".tmp"; };
  const auto remove_temporaries = [&] {
    for (const auto& [path, text] : files) std::remove(temporary(path).c_str());
  };
  const auto fail = [&](const std::filesystem::path& path, int error) {
    remove_temporaries();  // the old files stay, and no temporary is left behind
    throw std::runtime_error(fmt::format("{}: cannot write: {}", path.string(), io::system_reason(error)));
  };
  // Every temporary first: a full disk shows here, before any file has changed.
  for (const auto& [path, text] : files) {
    std::FILE* file = std::fopen(temporary(path).c_str(), "wb");
    if (!file) fail(path, errno);
    int error = 0;
    if (std::fwrite(text.data(), 1, text.size(), file) != text.size() || std::fflush(file) != 0) error = errno;
    if (std::fclose(file) != 0 && error == 0) error = errno;  // a full disk may only show at close
    if (error != 0) fail(path, error);
  }
  for (const auto& [path, text] : files)
    if (std::rename(temporary(path).c_str(), path.c_str()) != 0) fail(path, errno);
}

void replace_file_atomically(const std::filesystem::path& path, const std::string& text) {
  replace_files_atomically({{path, text}});
}

}  // namespace needlefem::output
