#include "io_errors/io_errors.hpp"

#include <cctype>
#include <cstring>
#include <regex>

namespace needlefem::io {

void stop_hdf5_error_printing() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

void start_hdf5_without_termination() {
  H5dont_atexit();
  H5open();
}

std::string hdf5_failure_reason() {
  struct Found {
    int error = 0;            // the first errno recorded, from the innermost call outwards
    std::string innermost;    // the description where the failure arose
  } found;
  const auto visit = [](unsigned, const H5E_error2_t* entry, void* data) -> herr_t {
    auto& f = *static_cast<Found*>(data);
    const std::string description = entry->desc ? entry->desc : "";
    if (f.innermost.empty()) f.innermost = description;
    static const std::regex errno_field(R"(errno = (\d+))");
    if (std::smatch match; f.error == 0 && std::regex_search(description, match, errno_field))
      f.error = std::stoi(match[1]);
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, visit, &found);
  if (found.error != 0) return system_reason(found.error);
  return found.innermost.empty() ? "unknown HDF5 error" : "HDF5: " + found.innermost;
}

std::string system_reason(int error) {
  std::string text = std::strerror(error);
  if (!text.empty()) text[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
  return text;
}

}  // namespace needlefem::io
