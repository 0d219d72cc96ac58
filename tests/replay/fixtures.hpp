// Shared test helpers: a synthetic trajectory, temporary files, and a loopback UDP receiver.
#pragma once

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "replay/trajectory.hpp"
#include "replay/udp_device.hpp"

namespace needlefem::replay::testing {

// duration_s long, sampled every 10 ms: the needle advances 1 mm/s along z while turning about
// it at pi/10 rad/s; the force along -z ramps linearly from 0 to peak_force_n.
inline Trajectory ramp_trajectory(double duration_s = 2.0, double peak_force_n = 5.0) {
  Trajectory t;
  const int intervals = static_cast<int>(std::lround(duration_s / 0.01));
  for (int i = 0; i <= intervals; ++i) {
    const double time = i * 0.01;
    const double angle = std::numbers::pi / 10.0 * time;
    t.time_s.push_back(time);
    t.position_m.push_back({0.0, 0.0, 1e-3 * time});
    t.orientation.push_back({std::cos(angle / 2), 0.0, 0.0, std::sin(angle / 2)});
    t.force_n.push_back({0.0, 0.0, -peak_force_n * time / duration_s});
    t.torque_n_m.push_back({0.0, 0.0, -1e-4 * time});
  }
  t.source_case = "synthetic ramp (tests/replay/fixtures.hpp)";
  return t;
}

inline std::filesystem::path temporary_path(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("needlefem_test_" + std::to_string(::getpid()) + "_" + name);
}

// Binds 127.0.0.1 on a port the OS picks and collects decoded packets on a thread until a final
// frame arrives or stop() is called.
class LoopbackReceiver {
 public:
  LoopbackReceiver() {
    socket_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    const int buffer_bytes = 8 << 20;
    ::setsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &buffer_bytes, sizeof buffer_bytes);
    const timeval timeout{0, 100'000};
    ::setsockopt(socket_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = 0;
    socklen_t length = sizeof address;
    if (::bind(socket_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
        ::getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &length) != 0)
      throw std::runtime_error("cannot bind a loopback UDP socket");
    port_ = ntohs(address.sin_port);
    thread_ = std::thread([this] { receive(); });
  }
  ~LoopbackReceiver() {
    stopping_ = true;
    if (thread_.joinable()) thread_.join();
    ::close(socket_);
  }
  // Waits (up to 2 s) for the final frame still in flight, then stops receiving.
  void stop() {
    for (int waited_ms = 0; !final_received_ && waited_ms < 2000; ++waited_ms)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    stopping_ = true;
    if (thread_.joinable()) thread_.join();
  }
  int port() const { return port_; }
  std::string address() const { return "udp://127.0.0.1:" + std::to_string(port_); }
  // Waits (up to `timeout_ms`) until a frame has arrived; false if none did.
  bool wait_for_first_frame(int timeout_ms) const {
    for (int waited_ms = 0; !first_received_ && waited_ms < timeout_ms; ++waited_ms)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return first_received_;
  }
  // Valid after stop().
  const std::vector<DeviceFrame>& frames() const { return frames_; }
  std::size_t malformed() const { return malformed_; }

 private:
  void receive() {
    std::uint8_t buffer[2048];
    while (!stopping_) {
      const ssize_t n = ::recv(socket_, buffer, sizeof buffer, 0);
      if (n < 0) continue;  // timeout: look at the stop flag
      if (auto frame = decode_packet(buffer, static_cast<std::size_t>(n))) {
        frames_.push_back(*frame);
        first_received_ = true;
        if (frame->final_frame) {
          final_received_ = true;
          return;
        }
      } else {
        ++malformed_;
      }
    }
  }
  int socket_ = -1;
  int port_ = 0;
  std::atomic<bool> stopping_{false};
  std::atomic<bool> final_received_{false};
  std::atomic<bool> first_received_{false};
  std::vector<DeviceFrame> frames_;
  std::size_t malformed_ = 0;
  std::thread thread_;
};

}  // namespace needlefem::replay::testing
