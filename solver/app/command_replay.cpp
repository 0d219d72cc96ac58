// `needlefem replay TRAJ.h5 --driver udp://HOST:PORT`: streams a precomputed needle trajectory
// to a haptic device at its servo rate and prints a JSON timing report (solver/replay/player.hpp).
// Ctrl-C stops cleanly: the loop ends, a zero-force frame is sent, the report is printed.
#include <memory>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "interrupt/interrupt_guard.hpp"
#include "replay/device.hpp"
#include "replay/player.hpp"
#include "replay/trajectory.hpp"

namespace needlefem::app {

void add_replay_command(CLI::App& app) {
  struct Options {
    std::string trajectory_file;
    std::string driver;
    replay::ReplayOptions replay;
  };
  auto o = std::make_shared<Options>();
  auto* command = app.add_subcommand(
      "replay",
      "Stream a trajectory file (time, needle pose, force, torque; format in solver/replay/trajectory.hpp) to a\n"
      "haptic device at its servo rate, paced on the monotonic clock, interpolated, force-clamped. Prints a JSON\n"
      "report (frames, late/dropped frames, period-error percentiles). Ctrl-C stops with zero force.");
  command->add_option("trajectory", o->trajectory_file, "Trajectory HDF5 file")->required();
  command->add_option("--driver", o->driver,
                      "Device: udp://HOST:PORT (packet format in solver/replay/udp_device.hpp) or "
                      "openhaptics://[NAME] (builds with the OpenHaptics SDK)")
      ->required();
  command->add_option("--rate,--rate-hz", o->replay.rate_hz, "Device servo rate (Hz)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--force-limit-n", o->replay.force_limit_n, "Device force limit; larger forces are clamped (N)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_flag("--loop", o->replay.loop, "Repeat the trajectory until stopped");
  command->add_option("--duration-s", o->replay.duration_s, "Stop after this long (0: one pass, or forever with --loop)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command->callback([o] {
    const replay::Trajectory trajectory = replay::read_trajectory(o->trajectory_file);
    const auto device = replay::make_device(o->driver);
    InterruptGuard interrupt;
    const replay::ReplayReport report =
        replay::replay(trajectory, *device, o->replay, InterruptGuard::stop_flag());
    nlohmann::json out = report.to_json(o->replay);
    out["trajectory"] = o->trajectory_file;
    out["driver"] = device->description();
    fmt::print("{}\n", out.dump(2));
  });
}

}  // namespace needlefem::app
