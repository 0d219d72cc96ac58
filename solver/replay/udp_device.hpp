// UDP back end: one datagram per frame to HOST:PORT.
//
// Packet format, version 1: 136 bytes, all fields little-endian, doubles IEEE-754 binary64.
//   offset size  field
//        0    4  magic "NFHR" (bytes 0x4E 0x46 0x48 0x52)
//        4    2  version, uint16 = 1
//        6    2  flags, uint16: bit 0 = final frame (force and torque are zero, replay ended or was
//                interrupted), bit 1 = force was clamped to the device limit
//        8    8  sequence number, uint64, 0, 1, 2, ... (gaps mean lost datagrams)
//       16    8  timestamp, uint64 ns, the frame's deadline on the sender's CLOCK_MONOTONIC
//       24    8  trajectory time, s
//       32   24  position x, y, z, m
//       56   32  orientation quaternion w, x, y, z
//       88   24  force x, y, z, N
//      112   24  torque x, y, z, N m
// Python: struct.unpack("<4sHHQQd3d4d3d3d", packet).
//
// Sending never blocks (MSG_DONTWAIT). A refused datagram (ECONNREFUSED: the ICMP "port
// unreachable" of an earlier one, when no receiver listens) or a full socket buffer counts as a
// failed frame and replay goes on.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "replay/device.hpp"

namespace needlefem::replay {

inline constexpr std::size_t udp_packet_size = 136;
inline constexpr std::uint16_t udp_packet_version = 1;
using UdpPacket = std::array<std::uint8_t, udp_packet_size>;

UdpPacket encode_packet(const DeviceFrame& frame);
// std::nullopt for a datagram of the wrong size, magic or version.
std::optional<DeviceFrame> decode_packet(const std::uint8_t* data, std::size_t size);

class UdpDevice : public HapticDevice {
 public:
  // Resolves host (name or IPv4/IPv6 literal) and connects a datagram socket; throws
  // std::runtime_error when the address cannot be resolved or the socket not created.
  UdpDevice(const std::string& host, const std::string& port);
  ~UdpDevice() override;
  UdpDevice(const UdpDevice&) = delete;
  UdpDevice& operator=(const UdpDevice&) = delete;

  bool send(const DeviceFrame& frame) override;
  std::string description() const override { return "udp://" + host_ + ":" + port_; }
  std::uint64_t refused_count() const { return refused_; }

 private:
  std::string host_, port_;
  int socket_ = -1;
  std::uint64_t refused_ = 0;
};

}  // namespace needlefem::replay
