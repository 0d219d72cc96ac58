// Trajectory file: write/read round trip, and clear one-line errors for malformed files both
// from the reader and from `needlefem replay` (non-zero exit).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdio>
#include <functional>
#include <string>

#include "fixtures.hpp"
#include "replay/trajectory.hpp"

namespace needlefem::replay {
namespace {

using testing::ramp_trajectory;
using testing::temporary_path;

TEST(TrajectoryFile, RoundTripIsExact) {
  const auto file = temporary_path("round_trip.h5");
  const Trajectory written = ramp_trajectory();
  write_trajectory(file, written);
  const Trajectory read = read_trajectory(file);
  EXPECT_EQ(read.time_s, written.time_s);
  EXPECT_EQ(read.position_m, written.position_m);
  EXPECT_EQ(read.force_n, written.force_n);
  EXPECT_EQ(read.torque_n_m, written.torque_n_m);
  EXPECT_EQ(read.source_case, written.source_case);
  ASSERT_EQ(read.orientation.size(), written.orientation.size());
  for (std::size_t i = 0; i < read.orientation.size(); ++i)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(read.orientation[i][c], written.orientation[i][c], 1e-15);
  EXPECT_FALSE(std::filesystem::exists(file.string() + ".tmp"));
  std::filesystem::remove(file);
}

// Writes a valid file, lets `damage` edit it with the HDF5 C API, and returns the path.
std::filesystem::path damaged_file(const std::string& name, const std::function<void(hid_t)>& damage) {
  const auto file = temporary_path(name);
  write_trajectory(file, ramp_trajectory());
  const hid_t id = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  damage(id);
  H5Fclose(id);
  return file;
}

void replace_dataset(hid_t file, const char* name, const std::vector<hsize_t>& dims, const std::vector<double>& values) {
  H5Ldelete(file, name, H5P_DEFAULT);
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t dataset = H5Dcreate2(file, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(dataset);
  H5Sclose(space);
}

struct Malformed {
  std::string name;
  std::function<void(hid_t)> damage;
  std::string expected_message;  // after "FILE: "
};

std::vector<Malformed> malformed_cases() {
  const std::size_t n = ramp_trajectory().size();
  return {
      {"non_monotonic.h5",
       [n](hid_t f) {
         std::vector<double> time(n);
         for (std::size_t i = 0; i < n; ++i) time[i] = 0.01 * i;
         time[17] = time[15];
         replace_dataset(f, "time_s", {n}, time);
       },
       "dataset 'time_s': not strictly increasing at sample 17"},
      {"wrong_shape.h5", [n](hid_t f) { replace_dataset(f, "position_m", {n, 2}, std::vector<double>(2 * n, 0.0)); },
       "dataset 'position_m': shape [201,2] but the format needs [n,3]"},
      {"missing.h5", [](hid_t f) { H5Ldelete(f, "force_n", H5P_DEFAULT); }, "dataset 'force_n': missing"},
      {"short.h5", [](hid_t f) { replace_dataset(f, "torque_n_m", {5, 3}, std::vector<double>(15, 0.0)); },
       "dataset 'torque_n_m': 5 samples but 'time_s' has 201"},
      {"non_finite.h5",
       [n](hid_t f) {
         std::vector<double> force(3 * n, 0.0);
         force[3 * 40 + 1] = std::nan("");
         replace_dataset(f, "force_n", {n, 3}, force);
       },
       "dataset 'force_n': non-finite value at sample 40"},
  };
}

TEST(TrajectoryFile, MalformedFilesGiveOneLineErrors) {
  for (const auto& bad : malformed_cases()) {
    const auto file = damaged_file(bad.name, bad.damage);
    try {
      read_trajectory(file);
      ADD_FAILURE() << bad.name << " was accepted";
    } catch (const TrajectoryError& error) {
      EXPECT_EQ(std::string(error.what()).rfind(file.string() + ": " + bad.expected_message, 0), 0u)
          << "got: " << error.what();
      EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos);
    }
    std::filesystem::remove(file);
  }
}

TEST(TrajectoryFile, RejectsFilesOfAnotherFormat) {
  const auto not_hdf5 = temporary_path("not_hdf5.h5");
  std::FILE* text = std::fopen(not_hdf5.c_str(), "w");
  std::fputs("time,force\n", text);
  std::fclose(text);
  EXPECT_THROW(
      {
        try {
          read_trajectory(not_hdf5);
        } catch (const TrajectoryError& e) {
          EXPECT_EQ(std::string(e.what()), not_hdf5.string() + ": not an HDF5 file");
          throw;
        }
      },
      TrajectoryError);
  std::filesystem::remove(not_hdf5);
  const auto foreign = temporary_path("foreign.h5");
  const hid_t f = H5Fcreate(foreign.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(f);
  EXPECT_THROW(read_trajectory(foreign), TrajectoryError);
  std::filesystem::remove(foreign);
}

// Runs `needlefem replay FILE ...`; returns the exit status and stderr.
std::pair<int, std::string> run_replay_command(const std::string& arguments) {
  const auto error_file = temporary_path("stderr.txt");
  const std::string command = std::string(NEEDLEFEM_EXE_PATH) + " replay " + arguments + " > /dev/null 2> " +
                              error_file.string();
  const int status = std::system(command.c_str());
  std::string errors;
  if (std::FILE* in = std::fopen(error_file.c_str(), "r")) {
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, in)) errors.append(buffer, n);
    std::fclose(in);
  }
  std::filesystem::remove(error_file);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, errors};
}

TEST(ReplayCommand, MalformedTrajectoryExitsNonZeroWithOneLine) {
  for (const auto& bad : malformed_cases()) {
    const auto file = damaged_file(bad.name, bad.damage);
    const auto [status, errors] = run_replay_command(file.string() + " --driver udp://127.0.0.1:9");
    EXPECT_EQ(status, 1) << bad.name;
    EXPECT_EQ(errors.rfind("needlefem: error: " + file.string() + ": " + bad.expected_message, 0), 0u)
        << "stderr: " << errors;
    EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1) << errors;
    std::filesystem::remove(file);
  }
}

TEST(ReplayCommand, UnknownDriverIsRejected) {
  const auto file = temporary_path("driver.h5");
  write_trajectory(file, ramp_trajectory());
  const auto [status, errors] = run_replay_command(file.string() + " --driver serial:///dev/ttyS0");
  EXPECT_EQ(status, 1);
  EXPECT_NE(errors.find("unknown scheme"), std::string::npos) << errors;
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace needlefem::replay
