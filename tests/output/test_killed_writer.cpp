// Crash safety: a child process appends output times in a loop and is SIGKILLed at several
// moments. Each time the parent opens the .h5 read-only (plain open, as ParaView does) and
// checks that every time the .xdmf lists is complete and holds exactly the values written,
// and that no HDF5 metadata byte changed after the first output time (only raw data did).
//
// Leaves killed_writer.h5/.xdmf in the working directory for the ParaView check.
#include "output/result_file.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "h5_read.hpp"
#include "test_meshes.hpp"

namespace needlefem::output {
namespace {

using testing::H5Reader;

const std::vector<FieldSpec> kSeries{{"displacement", FieldCentre::node, FieldType::vector, "m"},
                                     {"pressure", FieldCentre::node, FieldType::scalar, "Pa"},
                                     {"stress", FieldCentre::cell, FieldType::symmetric_tensor, "Pa"}};

double time_of(long step) { return 1e-3 * static_cast<double>(step); }

// The value the writer stores for component k of entity e of field f at a step (distinct
// for every field, entity, component and step).
double value(std::size_t f, long step, std::size_t e, int k) {
  return static_cast<double>(step) + 1e-3 * static_cast<double>(e) + 1e-6 * k + 10.0 * static_cast<double>(f);
}

// What the writer passes in: input components (6 for the symmetric tensor).
std::vector<double> field_values(std::size_t f, long step, std::size_t entities) {
  const int components = input_components(kSeries[f].type);
  std::vector<double> values(entities * components);
  for (std::size_t e = 0; e < entities; ++e)
    for (int k = 0; k < components; ++k) values[e * components + k] = value(f, step, e, k);
  return values;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

[[noreturn]] void write_until_killed(const std::filesystem::path& h5, const std::filesystem::path& snapshot,
                                     const TetMesh& mesh, long capacity) {
  ResultFile file(h5, mesh, "[killed]\n", kSeries, capacity);
  for (long step = 0; step < capacity; ++step) {
    std::vector<std::vector<double>> arrays;
    for (std::size_t f = 0; f < kSeries.size(); ++f)
      arrays.push_back(field_values(f, step, kSeries[f].centre == FieldCentre::node ? mesh.nodes.size() : mesh.tet_count()));
    file.append_time(time_of(step), {arrays.begin(), arrays.end()});
    std::this_thread::sleep_for(std::chrono::microseconds(500));  // keeps the run longer than the kills
    if (step == 0) {  // whole or absent, whenever the kill comes
      const std::filesystem::path partial = snapshot.string() + ".partial";
      std::ofstream(partial, std::ios::binary) << read_text(h5);
      std::filesystem::rename(partial, snapshot);
    }
  }
  std::_Exit(3);  // ran out of capacity: the parent failed to kill in time
}

struct KillResult {
  std::size_t xdmf_times = 0;
  long long time_count = 0;
};

void check_killed_file(const std::filesystem::path& h5, const std::filesystem::path& snapshot, const TetMesh& mesh,
                       KillResult& result) {
  const std::string xdmf = read_text(std::filesystem::path(h5).replace_extension(".xdmf"));
  EXPECT_NE(xdmf.find("</Xdmf>"), std::string::npos) << "XDMF incomplete";
  std::vector<double> times;
  const std::regex time_pattern(R"(<Time Value="([^"]+)\"/>)");
  for (auto it = std::sregex_iterator(xdmf.begin(), xdmf.end(), time_pattern); it != std::sregex_iterator(); ++it)
    times.push_back(std::stod((*it)[1]));
  // The i-th time's fields must reference step i (and nothing beyond).
  const std::regex slab_pattern(R"(:/series/steps/(\d+)/)");
  std::size_t slab = 0;
  for (auto it = std::sregex_iterator(xdmf.begin(), xdmf.end(), slab_pattern); it != std::sregex_iterator(); ++it, ++slab)
    EXPECT_EQ(std::stoul((*it)[1]), slab / kSeries.size());
  EXPECT_EQ(slab, times.size() * kSeries.size());
  result.xdmf_times = times.size();

  H5Reader file(h5.string());  // plain read-only open must work after the kill
  result.time_count = file.read<long long>("/series/time_count").at(0);
  EXPECT_GE(result.time_count, static_cast<long long>(times.size()));
  EXPECT_LE(result.time_count, static_cast<long long>(times.size()) + 1);
  const std::vector<double> stored_times = file.read<double>("/series/time");
  std::size_t values_checked = 0, wrong_values = 0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    EXPECT_EQ(times[i], time_of(static_cast<long>(i)));
    EXPECT_EQ(stored_times[i], times[i]);
    for (std::size_t f = 0; f < kSeries.size(); ++f) {
      const bool at_nodes = kSeries[f].centre == FieldCentre::node;
      const std::string path = std::string("/series/") + (at_nodes ? "node/" : "cell/") + kSeries[f].name;
      const std::vector<double> stored = file.read<double>(path, static_cast<long>(i));
      const std::size_t entities = at_nodes ? mesh.nodes.size() : mesh.tet_count();
      const int components = stored_components(kSeries[f].type);
      if (stored.size() != entities * components) {
        ADD_FAILURE() << path << ": " << stored.size() << " values at time " << i;
        continue;
      }
      // Symmetric tensors are stored in full; component k of the 9 comes from input index:
      constexpr int kVoigtOfFull[9] = {0, 3, 5, 3, 1, 4, 5, 4, 2};
      for (std::size_t e = 0; e < entities; ++e)
        for (int k = 0; k < components; ++k) {
          const int input_k = kSeries[f].type == FieldType::symmetric_tensor ? kVoigtOfFull[k] : k;
          ++values_checked;
          wrong_values += stored[e * components + k] != value(f, static_cast<long>(i), e, input_k);
        }
    }
  }
  EXPECT_EQ(wrong_values, 0u) << "of " << values_checked << " values at the listed times";
  EXPECT_GT(values_checked, 0u);

  // Metadata never changed after the first output time: every byte outside the raw data of
  // the time-series datasets equals the snapshot the writer took then.
  std::vector<std::pair<haddr_t, hsize_t>> raw{file.raw_extent("/series/time"), file.raw_extent("/series/time_count")};
  for (const FieldSpec& spec : kSeries)
    raw.push_back(file.raw_extent(std::string("/series/") + (spec.centre == FieldCentre::node ? "node/" : "cell/") + spec.name));
  const std::string before = read_text(snapshot), after = read_text(h5);
  EXPECT_EQ(before.size(), after.size());
  std::vector<bool> is_raw(after.size(), false);
  for (const auto& [offset, size] : raw)
    for (hsize_t b = offset; b < offset + size && b < is_raw.size(); ++b) is_raw[b] = true;
  std::size_t metadata_bytes = 0, changed = 0;
  for (std::size_t b = 0; b < std::min(before.size(), after.size()); ++b)
    if (!is_raw[b]) {
      ++metadata_bytes;
      changed += before[b] != after[b];
    }
  EXPECT_EQ(changed, 0u) << "of " << metadata_bytes << " metadata bytes";
  EXPECT_GT(metadata_bytes, 1000u);
  std::printf("  checked %zu values, %zu metadata bytes unchanged of %zu\n", values_checked, metadata_bytes - changed,
              metadata_bytes);
}

TEST(ResultFileCrash, SigkilledWriterLeavesEveryListedTimeReadable) {
  const TetMesh mesh = testing::kuhn_cube(0.001, true);
  const std::filesystem::path h5 = std::filesystem::current_path() / "killed_writer.h5";
  const std::filesystem::path snapshot = std::filesystem::current_path() / "killed_writer.snapshot";
  const long capacity = 2000;
  // Kill moments spread over the run, so that the kill lands in field writes, flushes
  // and XDMF rewrites alike.
  for (int delay_ms : {0, 7, 40, 130, 210, 290, 380}) {
    std::filesystem::remove(snapshot);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) write_until_killed(h5, snapshot, mesh, capacity);
    // The delay counts from the first output time (file setup time varies with the machine).
    const auto start = std::chrono::steady_clock::now();
    while (!std::filesystem::exists(snapshot) && std::chrono::steady_clock::now() - start < std::chrono::seconds(20))
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    ASSERT_EQ(kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "writer ended before the kill";
    ASSERT_TRUE(std::filesystem::exists(snapshot)) << "no first output time within 20 s";
    KillResult result;
    check_killed_file(h5, snapshot, mesh, result);
    std::printf("killed after %d ms: XDMF lists %zu times, time_count %lld\n", delay_ms, result.xdmf_times,
                result.time_count);
    EXPECT_GE(result.xdmf_times, 1u);
  }
  std::filesystem::remove(snapshot);
}

}  // namespace
}  // namespace needlefem::output
