// OpenHaptics HD back end; see openhaptics_device.hpp.
#include "replay/openhaptics_device.hpp"

#include <stdexcept>

#include <fmt/core.h>

namespace needlefem::replay {

namespace {

void throw_on_hd_error(const char* action) {
  const HDErrorInfo error = hdGetError();
  if (HD_DEVICE_ERROR(error))
    throw std::runtime_error(fmt::format("openhaptics: {}: {} (HD error {:#x}, internal {})", action,
                                         hdGetErrorString(error.errorCode), error.errorCode, error.internalErrorCode));
}

}  // namespace

OpenHapticsDevice::OpenHapticsDevice(const std::string& device_name) {
  handle_ = hdInitDevice(device_name.empty() ? HD_DEFAULT_DEVICE : device_name.c_str());
  throw_on_hd_error("cannot initialise the device");
  description_ = fmt::format("openhaptics://{} ({})", device_name, hdGetString(HD_DEVICE_MODEL_TYPE));
  HDint output_dof = 3;
  hdGetIntegerv(HD_OUTPUT_DOF, &output_dof);
  renders_torque_ = output_dof == 6;
  hdEnable(HD_FORCE_OUTPUT);
  callback_ = hdScheduleAsynchronous(servo_tick, this, HD_MAX_SCHEDULER_PRIORITY);
  hdStartScheduler();
  try {
    throw_on_hd_error("cannot start the servo loop");
  } catch (...) {
    hdUnschedule(callback_);
    hdDisableDevice(handle_);
    throw;
  }
}

OpenHapticsDevice::~OpenHapticsDevice() {
  hdStopScheduler();
  hdUnschedule(callback_);
  hdDisableDevice(handle_);
}

bool OpenHapticsDevice::send(const DeviceFrame& frame) {
  {
    std::lock_guard lock(latest_mutex_);
    latest_force_n_ = frame.force_n;
    for (int i = 0; i < 3; ++i) latest_torque_mn_m_[i] = 1e3 * frame.torque_n_m[i];
  }
  return servo_error_.load() == HD_SUCCESS;
}

HDCallbackCode HDCALLBACK OpenHapticsDevice::servo_tick(void* self_pointer) {
  auto* self = static_cast<OpenHapticsDevice*>(self_pointer);
  // Never wait in the servo loop: if the replay thread holds the lock, render last tick's values.
  if (std::unique_lock lock(self->latest_mutex_, std::try_to_lock); lock.owns_lock()) {
    self->servo_force_n_ = self->latest_force_n_;
    self->servo_torque_mn_m_ = self->latest_torque_mn_m_;
  }
  hdBeginFrame(self->handle_);
  hdSetDoublev(HD_CURRENT_FORCE, self->servo_force_n_.data());
  if (self->renders_torque_) hdSetDoublev(HD_CURRENT_TORQUE, self->servo_torque_mn_m_.data());
  hdEndFrame(self->handle_);
  const HDErrorInfo error = hdGetError();
  if (HD_DEVICE_ERROR(error)) {
    self->servo_error_.store(error.errorCode);
    return HD_CALLBACK_DONE;
  }
  return HD_CALLBACK_CONTINUE;
}

}  // namespace needlefem::replay
