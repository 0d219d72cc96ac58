// UDP back end and its packet encoding; the packet format is documented in udp_device.hpp.
#include "replay/udp_device.hpp"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <bit>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fmt/core.h>

namespace needlefem::replay {

namespace {

constexpr std::array<std::uint8_t, 4> packet_magic = {'N', 'F', 'H', 'R'};
constexpr std::uint16_t flag_final = 1u << 0;
constexpr std::uint16_t flag_clamped = 1u << 1;

class PacketWriter {
 public:
  explicit PacketWriter(UdpPacket& packet) : packet_(packet) {}
  void unsigned_integer(std::uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) packet_[offset_++] = static_cast<std::uint8_t>(value >> (8 * i));
  }
  void real(double value) { unsigned_integer(std::bit_cast<std::uint64_t>(value), 8); }
  template <std::size_t N>
  void reals(const std::array<double, N>& values) {
    for (double v : values) real(v);
  }
  std::size_t offset() const { return offset_; }

 private:
  UdpPacket& packet_;
  std::size_t offset_ = 0;
};

class PacketReader {
 public:
  explicit PacketReader(const std::uint8_t* data) : data_(data) {}
  std::uint64_t unsigned_integer(int bytes) {
    std::uint64_t value = 0;
    for (int i = 0; i < bytes; ++i) value |= std::uint64_t{data_[offset_++]} << (8 * i);
    return value;
  }
  double real() { return std::bit_cast<double>(unsigned_integer(8)); }
  template <std::size_t N>
  void reals(std::array<double, N>& values) {
    for (double& v : values) v = real();
  }

 private:
  const std::uint8_t* data_;
  std::size_t offset_ = 0;
};

}  // namespace

UdpPacket encode_packet(const DeviceFrame& frame) {
  UdpPacket packet{};
  PacketWriter out(packet);
  for (std::uint8_t byte : packet_magic) out.unsigned_integer(byte, 1);
  out.unsigned_integer(udp_packet_version, 2);
  out.unsigned_integer((frame.final_frame ? flag_final : 0) | (frame.force_clamped ? flag_clamped : 0), 2);
  out.unsigned_integer(frame.sequence, 8);
  out.unsigned_integer(frame.timestamp_ns, 8);
  out.real(frame.trajectory_time_s);
  out.reals(frame.position_m);
  out.reals(frame.orientation);
  out.reals(frame.force_n);
  out.reals(frame.torque_n_m);
  return packet;
}

std::optional<DeviceFrame> decode_packet(const std::uint8_t* data, std::size_t size) {
  if (size != udp_packet_size || std::memcmp(data, packet_magic.data(), packet_magic.size()) != 0) return std::nullopt;
  PacketReader in(data + packet_magic.size());
  if (in.unsigned_integer(2) != udp_packet_version) return std::nullopt;
  const auto flags = in.unsigned_integer(2);
  DeviceFrame frame;
  frame.final_frame = flags & flag_final;
  frame.force_clamped = flags & flag_clamped;
  frame.sequence = in.unsigned_integer(8);
  frame.timestamp_ns = in.unsigned_integer(8);
  frame.trajectory_time_s = in.real();
  in.reals(frame.position_m);
  in.reals(frame.orientation);
  in.reals(frame.force_n);
  in.reals(frame.torque_n_m);
  return frame;
}

UdpDevice::UdpDevice(const std::string& host, const std::string& port) : host_(host), port_(port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  if (const int status = getaddrinfo(host.c_str(), port.c_str(), &hints, &found); status != 0)
    throw std::runtime_error(fmt::format("udp://{}:{}: cannot resolve: {}", host, port, gai_strerror(status)));
  int last_errno = 0;
  for (const addrinfo* candidate = found; candidate != nullptr && socket_ < 0; candidate = candidate->ai_next) {
    socket_ = ::socket(candidate->ai_family, candidate->ai_socktype | SOCK_CLOEXEC, candidate->ai_protocol);
    if (socket_ >= 0 && ::connect(socket_, candidate->ai_addr, candidate->ai_addrlen) != 0) {
      last_errno = errno;
      ::close(socket_);
      socket_ = -1;
    } else if (socket_ < 0) {
      last_errno = errno;
    }
  }
  freeaddrinfo(found);
  if (socket_ < 0)
    throw std::runtime_error(fmt::format("udp://{}:{}: cannot open socket: {}", host, port, std::strerror(last_errno)));
}

UdpDevice::~UdpDevice() {
  if (socket_ >= 0) ::close(socket_);
}

bool UdpDevice::send(const DeviceFrame& frame) {
  const UdpPacket packet = encode_packet(frame);
  if (::send(socket_, packet.data(), packet.size(), MSG_DONTWAIT) == static_cast<ssize_t>(packet.size())) return true;
  if (errno == ECONNREFUSED) ++refused_;
  return false;
}

}  // namespace needlefem::replay
