// Driver address parsing: picks the back end named by the address scheme.
#include "replay/device.hpp"

#include <stdexcept>

#include "replay/udp_device.hpp"
#ifdef NEEDLEFEM_HAVE_OPENHAPTICS
#include "replay/openhaptics_device.hpp"
#endif

namespace needlefem::replay {

std::unique_ptr<HapticDevice> make_device(const std::string& address) {
  const std::string udp_scheme = "udp://";
  const std::string openhaptics_scheme = "openhaptics://";
  if (address.starts_with(udp_scheme)) {
    const std::string rest = address.substr(udp_scheme.size());
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == rest.size())
      throw std::invalid_argument("driver '" + address + "': expected udp://HOST:PORT");
    std::string host = rest.substr(0, colon);
    if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);  // [::1]
    const std::string port = rest.substr(colon + 1);
    // getaddrinfo would take a service name, and wraps a number above 65535 to another port.
    const bool digits = port.size() <= 5 && port.find_first_not_of("0123456789") == std::string::npos;
    if (!digits || std::stoi(port) < 1 || std::stoi(port) > 65535)
      throw std::invalid_argument("driver '" + address + "': port '" + port + "' is not a UDP port (1-65535)");
    return std::make_unique<UdpDevice>(host, port);
  }
  if (address.starts_with(openhaptics_scheme)) {
#ifdef NEEDLEFEM_HAVE_OPENHAPTICS
    return std::make_unique<OpenHapticsDevice>(address.substr(openhaptics_scheme.size()));
#else
    throw std::invalid_argument("driver '" + address +
                                "': this build has no OpenHaptics support (HD/hd.h and libHD were not found when "
                                "CMake configured it)");
#endif
  }
  throw std::invalid_argument("driver '" + address + "': unknown scheme; use udp://HOST:PORT or openhaptics://[NAME]");
}

}  // namespace needlefem::replay
