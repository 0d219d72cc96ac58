// Minimal HDF5 reading for the output tests (plain read-only open, as any viewer does).
#pragma once

#include <hdf5.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace needlefem::output::testing {

class H5Reader {
 public:
  explicit H5Reader(const std::string& path) : file_(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {
    if (file_ < 0) throw std::runtime_error("cannot open " + path + " read-only");
  }
  ~H5Reader() { H5Fclose(file_); }
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  std::vector<hsize_t> dims(const std::string& dataset) const {
    hid_t d = open(dataset), space = H5Dget_space(d);
    std::vector<hsize_t> result(H5Sget_simple_extent_ndims(space));
    H5Sget_simple_extent_dims(space, result.data(), nullptr);
    H5Sclose(space);
    H5Dclose(d);
    return result;
  }

  // The whole dataset, or with `slab` >= 0 only [slab, ...] of its leading dimension.
  template <class T>
  std::vector<T> read(const std::string& dataset, long slab = -1) const {
    std::vector<hsize_t> extent = dims(dataset);
    std::vector<hsize_t> start(extent.size(), 0), count = extent;
    if (slab >= 0) {
      start[0] = static_cast<hsize_t>(slab);
      count[0] = 1;
    }
    std::size_t total = 1;
    for (hsize_t c : count) total *= c;
    std::vector<T> values(total);
    hid_t d = open(dataset), file_space = H5Dget_space(d);
    H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
    hid_t memory_space = H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr);
    const hid_t type = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE
                       : std::is_same_v<T, int> ? H5T_NATIVE_INT : H5T_NATIVE_LLONG;
    const herr_t status = H5Dread(d, type, memory_space, file_space, H5P_DEFAULT, values.data());
    H5Sclose(memory_space);
    H5Sclose(file_space);
    H5Dclose(d);
    if (status < 0) throw std::runtime_error("cannot read " + dataset);
    return values;
  }

  // Variable-length string attribute(s) of an object ("/" for the root group).
  std::vector<std::string> text_attribute(const std::string& object, const std::string& name) const {
    hid_t attribute = H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (attribute < 0) throw std::runtime_error("no attribute " + object + "@" + name);
    hid_t space = H5Aget_space(attribute), type = H5Aget_type(attribute);
    std::vector<char*> texts(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    H5Aread(attribute, type, texts.data());
    std::vector<std::string> result(texts.begin(), texts.end());
    H5Dvlen_reclaim(type, space, H5P_DEFAULT, texts.data());
    H5Tclose(type);
    H5Sclose(space);
    H5Aclose(attribute);
    return result;
  }

  // File offset and size of a contiguous dataset's raw data.
  std::pair<haddr_t, hsize_t> raw_extent(const std::string& dataset) const {
    hid_t d = open(dataset);
    std::pair<haddr_t, hsize_t> result{H5Dget_offset(d), H5Dget_storage_size(d)};
    H5Dclose(d);
    return result;
  }

 private:
  hid_t open(const std::string& dataset) const {
    hid_t d = H5Dopen2(file_, dataset.c_str(), H5P_DEFAULT);
    if (d < 0) throw std::runtime_error("no dataset " + dataset);
    return d;
  }
  hid_t file_;
};

}  // namespace needlefem::output::testing
