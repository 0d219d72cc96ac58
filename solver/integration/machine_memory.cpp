#include "integration/machine_memory.hpp"

#include <algorithm>
#include <fstream>
#include <string>

#include <unistd.h>

namespace needlefem {

namespace {

std::size_t page_bytes() { return static_cast<std::size_t>(sysconf(_SC_PAGE_SIZE)); }

}  // namespace

std::size_t usable_memory_bytes() {
  std::size_t bytes = static_cast<std::size_t>(sysconf(_SC_PHYS_PAGES)) * page_bytes();
  for (const char* limit_file : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(limit_file);
    std::string limit;
    if (!(in >> limit) || limit.empty() || limit.find_first_not_of("0123456789") != std::string::npos) continue;
    bytes = std::min<std::size_t>(bytes, std::stoull(limit));  // "max" (no limit) is skipped above
    break;
  }
  return bytes;
}

std::size_t resident_bytes() {
  std::ifstream in("/proc/self/statm");
  std::size_t total_pages = 0, resident_pages = 0;
  in >> total_pages >> resident_pages;
  return resident_pages * page_bytes();
}

}  // namespace needlefem
