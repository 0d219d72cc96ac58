// The haptic device seen by the replay loop: one frame per servo tick, nothing more.
// Back ends: UDP (udp_device.hpp, documented packet format), an in-process recorder for tests
// (recording_device.hpp), and OpenHaptics HD (openhaptics_device.hpp, built only where the SDK
// is found at configure time).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "replay/trajectory.hpp"

namespace needlefem::replay {

struct DeviceFrame {
  std::uint64_t sequence = 0;      // 0, 1, 2, ... per frame sent, including the final one
  std::uint64_t timestamp_ns = 0;  // the frame's deadline on CLOCK_MONOTONIC
  double trajectory_time_s = 0.0;  // trajectory time the frame was sampled at
  Vec3 position_m{};
  Quaternion orientation{1.0, 0.0, 0.0, 0.0};
  Vec3 force_n{};                  // already clamped to the device limit
  Vec3 torque_n_m{};
  bool force_clamped = false;
  bool final_frame = false;        // the zero-force frame sent when replay ends or is interrupted
};

class HapticDevice {
 public:
  virtual ~HapticDevice() = default;
  // Called from the paced loop: must not block. Returns false when the frame was not delivered
  // (the reason is counted by the back end, never thrown: one lost frame must not stop replay).
  virtual bool send(const DeviceFrame& frame) = 0;
  virtual std::string description() const = 0;
};

// "udp://HOST:PORT" or "openhaptics://[DEVICE_NAME]" (when built with the SDK).
// Throws std::invalid_argument for an unknown or malformed address.
std::unique_ptr<HapticDevice> make_device(const std::string& address);

// The in-process test device: keeps every frame it is sent.
class RecordingDevice : public HapticDevice {
 public:
  bool send(const DeviceFrame& frame) override {
    frames.push_back(frame);
    return true;
  }
  std::string description() const override { return "in-process recorder"; }
  std::vector<DeviceFrame> frames;
};

}  // namespace needlefem::replay
