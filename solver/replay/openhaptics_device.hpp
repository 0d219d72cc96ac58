// OpenHaptics HD back end (3D Systems / SensAble Phantom devices). Compiled only when CMake
// finds HD/hd.h and libHD; then `make_device("openhaptics://[NAME]")` opens it.
//
// The device runs its own servo loop (hdStartScheduler, 1 kHz by default). An asynchronous
// callback at HD_MAX_SCHEDULER_PRIORITY renders the most recent replay frame each tick inside
// hdBeginFrame/hdEndFrame: HD_CURRENT_FORCE in N and, on 6-DOF output devices
// (HD_OUTPUT_DOF == 6), HD_CURRENT_TORQUE, which HD expects in mN m. Forces are sent in the
// trajectory's world frame: align it with the device base frame (x right, y up, z toward the
// user) when writing the trajectory. The pose in the frame is not commanded (the user holds
// the handle). The callback never throws: an HD error is stored and reported by the next send().
#pragma once

#include <HD/hd.h>

#include <array>
#include <atomic>
#include <mutex>
#include <string>

#include "replay/device.hpp"

namespace needlefem::replay {

class OpenHapticsDevice : public HapticDevice {
 public:
  // device_name empty = HD_DEFAULT_DEVICE. Throws std::runtime_error with HD's error text.
  explicit OpenHapticsDevice(const std::string& device_name);
  ~OpenHapticsDevice() override;
  OpenHapticsDevice(const OpenHapticsDevice&) = delete;
  OpenHapticsDevice& operator=(const OpenHapticsDevice&) = delete;

  bool send(const DeviceFrame& frame) override;
  std::string description() const override { return description_; }

 private:
  static HDCallbackCode HDCALLBACK servo_tick(void* self);

  std::string description_;
  HHD handle_ = HD_INVALID_HANDLE;
  HDSchedulerHandle callback_ = 0;
  bool renders_torque_ = false;
  std::mutex latest_mutex_;                // guards the two arrays below
  std::array<HDdouble, 3> latest_force_n_{};
  std::array<HDdouble, 3> latest_torque_mn_m_{};
  std::array<HDdouble, 3> servo_force_n_{};      // servo thread's copy, kept when the lock is busy
  std::array<HDdouble, 3> servo_torque_mn_m_{};
  std::atomic<HDerror> servo_error_{HD_SUCCESS};
};

}  // namespace needlefem::replay
