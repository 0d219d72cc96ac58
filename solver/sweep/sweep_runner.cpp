#include "sweep/sweep_runner.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "case/mesh_resolution.hpp"
#include "sweep/sweep_table.hpp"
#include "wall_clock/seconds_since.hpp"

extern char** environ;

namespace needlefem::sweep {

namespace fs = std::filesystem;

namespace {


struct LauncherRank {
  int rank = 0, size = 1;
  bool launched = false;
};

// The rank an MPI launcher gave this process, from its environment (OpenMPI, then PMI as set
// by MPICH's hydra, Intel MPI and `srun --mpi=pmi2`).
LauncherRank launcher_rank() {
  for (const auto& [rank, size] : {std::pair{"OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"}, std::pair{"PMI_RANK", "PMI_SIZE"}}) {
    const char* r = std::getenv(rank);
    const char* s = std::getenv(size);
    if (r && s) return {std::atoi(r), std::max(1, std::atoi(s)), true};
  }
  return {};
}

// The environment for children: under a launcher, without its variables (they would make the
// child's MPI_Init join the launcher's job instead of starting a singleton). Unless the user set
// it, OMP_NUM_THREADS gives each child the cores divided by the runs at a time: the element loops
// and the Cholesky factor use every core by default, and `jobs` runs doing so at once would
// oversubscribe the machine. (BLAS runs on one thread in every needlefem process: main.cpp.)
std::vector<std::string> child_environment(bool launched, int jobs) {
  std::vector<std::string> out;
  bool omp_threads_set = false;
  for (char** entry = environ; *entry; ++entry) {
    const std::string variable(*entry);
    const bool launcher = variable.starts_with("OMPI_") || variable.starts_with("PMIX_") ||
                          variable.starts_with("PMI_") || variable.starts_with("HYDRA_") ||
                          variable.starts_with("MPI_LOCAL");
    const bool keep = variable.starts_with("OMPI_ALLOW_RUN_AS_ROOT");  // the singleton needs it as root
    omp_threads_set = omp_threads_set || variable.starts_with("OMP_NUM_THREADS=");
    if (!launched || !launcher || keep) out.push_back(variable);
  }
  const long cores = std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN));
  const long threads = std::max(1L, cores / std::max(1, jobs));
  if (!omp_threads_set) out.push_back(fmt::format("OMP_NUM_THREADS={}", threads));
  return out;
}

std::vector<char*> c_array(std::vector<std::string>& texts) {
  std::vector<char*> out;
  for (auto& t : texts) out.push_back(t.data());
  out.push_back(nullptr);
  return out;
}

// Starts `argv` with stdout and stderr to `log`; the child dies with this process.
pid_t start_child(std::vector<std::string> argv, std::vector<std::string> environment, const fs::path& log) {
  auto args = c_array(argv);
  auto env = c_array(environment);
  const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log_fd < 0) throw std::runtime_error(fmt::format("cannot write {}: {}", log.string(), std::strerror(errno)));
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {  // only async-signal-safe calls from here to exec
    if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent) ::_exit(127);
    ::dup2(log_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    ::execve(args[0], args.data(), env.data());
    ::_exit(127);
  }
  ::close(log_fd);
  if (pid < 0) throw std::runtime_error(fmt::format("cannot start a run: {}", std::strerror(errno)));
  return pid;
}

// The reason a run failed, from its log: the last "needlefem: error:" line, else the last line.
std::string last_error(const fs::path& log, int wait_status) {
  std::ifstream in(log);
  std::string line, error, last;
  const std::string prefix = "needlefem: error: ";
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    last = line;
    if (line.starts_with(prefix)) error = line.substr(prefix.size());
  }
  const std::string how = WIFSIGNALED(wait_status) ? fmt::format("killed by signal {}", WTERMSIG(wait_status))
                                                   : fmt::format("exit status {}", WEXITSTATUS(wait_status));
  if (!error.empty()) return error;
  return last.empty() ? how : fmt::format("{} ({})", how, last);
}

std::string duration(double seconds) {
  const long s = std::lround(seconds);
  if (s < 60) return fmt::format("{:.1f} s", seconds);
  if (s < 3600) return fmt::format("{}m{:02}s", s / 60, s % 60);
  return fmt::format("{}h{:02}m", s / 3600, s % 3600 / 60);
}

class Progress {
 public:
  Progress(std::FILE* stream, const std::string& label, const LauncherRank& rank, std::size_t total, std::size_t done)
      : stream_(stream), total_(total), done_(done),
        prefix_(rank.size > 1 ? fmt::format("{}[{}/{}]", label, rank.rank, rank.size) : label) {}

  void line(const std::string& text) const {
    if (!stream_) return;
    fmt::print(stream_, "{}: {}\n", prefix_, text);
    std::fflush(stream_);
  }
  void finished(const std::string& what, std::size_t still_to_run) {
    ++done_;
    ++finished_;
    const double elapsed = seconds_since(start_);
    line(fmt::format("[{}/{}] {} | elapsed {}, ETA {}", done_, total_, what, duration(elapsed),
                     duration(elapsed / static_cast<double>(finished_) * static_cast<double>(still_to_run))));
  }

 private:
  std::FILE* stream_;
  std::size_t total_, done_, finished_ = 0;
  std::string prefix_;
  WallClock::time_point start_ = WallClock::now();
};

std::string maxima_text(const nlohmann::json& summary) {
  const auto value = [&](const char* key) { return summary["max"].value(key, nlohmann::json::object()).value("value", 0.0); };
  if (!summary.contains("max")) return "";
  return fmt::format(": verdict {} (point maxima: log strain {:.4g}, strain rate {:.4g} 1/s, von Mises {:.4g} Pa)",
                     summary.value("verdict", "none"), value("log_strain"), value("strain_rate_per_s"),
                     value("von_mises_pa"));
}

// A point's expected run time, up to a common factor, to start the longest runs first: the
// simulated time over the cube of the element size (scene.kind "block": block.element_mm), times
// 2 per mesh.refinement_level (each level halves the sizes near the needle, and a brain-tip run
// took about twice as long per level in docs/accuracy.md §10). Starting the longest first keeps a long
// run from being last with the other cores idle (paper 001's study: its slow case takes 0.2 s of
// history, the others 0.1 or 0.05 s; `needlefem converge`: the finest level).
double expected_cost(const DesignPoint& p) {
  const auto number = [&](const char* section, const char* key) {
    const auto table = p.resolved.find(section);
    if (table == p.resolved.end() || !table->contains(key) || !(*table)[key].is_number()) return 1.0;
    return (*table)[key].get<double>();
  };
  const auto kind = p.resolved.find("scene");
  const bool block = kind != p.resolved.end() && kind->value("kind", "") == "block";
  const double element = block ? number("block", "element_mm") : number("tissue", "core_element_mm");
  const double level = number("mesh", "refinement_level");
  return number("motion", "duration_s") / (element * element * element) * std::exp2(level);
}

// How many possible design points are on a mesh coarser than the converged setting
// (case/mesh_resolution.hpp), with the first one's sizes; "" when none is.
std::string coarse_mesh_summary(const SweepPlan& plan) {
  std::size_t possible = 0, coarse = 0;
  const DesignPoint* first = nullptr;
  for (const auto& p : plan.points) {
    if (!p.valid()) continue;
    ++possible;
    if (p.coarse_mesh.empty()) continue;
    ++coarse;
    if (!first) first = &p;
  }
  if (!first) return "";
  return fmt::format("{} of the {} possible design points: {}", coarse, possible, coarse_mesh_warning(first->coarse_mesh));
}

// The points this rank runs, most expensive first (the ones done or impossible are counted in
// `outcome` instead).
std::deque<std::size_t> queue_points(const SweepPlan& plan, const SweepOptions& options, const LauncherRank& rank,
                                     SweepOutcome& outcome) {
  std::deque<std::size_t> queue;
  std::size_t valid_index = 0;
  for (std::size_t i = 0; i < plan.points.size(); ++i) {
    const DesignPoint& p = plan.points[i];
    if (!p.valid()) {
      ++outcome.impossible;
      continue;
    }
    if (valid_index++ % static_cast<std::size_t>(rank.size) != static_cast<std::size_t>(rank.rank)) continue;
    ++outcome.total;
    const std::string status = read_point(p, options.out_dir).status;
    if (status == "completed" || (status == "failed" && !options.retry_failed)) ++outcome.already_done;
    else queue.push_back(i);
  }
  std::stable_sort(queue.begin(), queue.end(), [&](std::size_t a, std::size_t b) {
    return expected_cost(plan.points[a]) > expected_cost(plan.points[b]);
  });
  return queue;
}

// The lines before the first run: impossible points with their rules, the counts, a coarse-mesh
// warning (returned, for the last line too), the folder names' legend, and with --list the queue.
std::string announce(Progress& progress, const SweepPlan& plan, const SweepOptions& options, const LauncherRank& rank,
                     const SweepOutcome& outcome, const std::deque<std::size_t>& queue) {
  if (rank.rank == 0)
    for (const auto& p : plan.points)
      for (const auto& v : p.violations) progress.line(fmt::format("impossible, not run: {}: rule '{}': {}", p.name, v.rule, v.message));
  progress.line(fmt::format("{} design points ({} impossible); {} to run here, {} already done, {} to run with {} job{}",
                            plan.points.size(), outcome.impossible, outcome.total, outcome.already_done, queue.size(),
                            options.jobs, options.jobs > 1 ? "s" : ""));
  const std::string coarse_warning = coarse_mesh_summary(plan);
  if (!coarse_warning.empty()) progress.line("warning: " + coarse_warning);
  if (!plan.name_labels.empty()) {
    std::vector<std::string> legend;
    for (std::size_t k = 0; k < plan.swept_keys.size(); ++k)
      legend.push_back(fmt::format("{} = {}", plan.name_labels[k], plan.swept_keys[k]));
    progress.line(fmt::format("point folders are named by label and value: {}; sweep.csv has each value in a column",
                              fmt::join(legend, ", ")));
  }
  if (options.list_only)
    for (std::size_t i : queue) progress.line(fmt::format("to run: {} ({})", plan.points[i].name,
                                                          fmt::join(plan.points[i].grids, ",")));
  return coarse_warning;
}

// Starts `needlefem run` on a point in its own folder (its case.toml written there, a stale
// summary removed); returns the child's pid.
pid_t start_point(const DesignPoint& p, const SweepOptions& options, const std::vector<std::string>& environment) {
  const fs::path dir = point_directory(options.out_dir, p);
  fs::create_directories(dir);
  fs::remove(dir / "summary.json");
  write_file_atomically(dir / "case.toml", p.case_text);
  std::vector<std::string> argv{options.executable.string(), "run", (dir / "case.toml").string(), "--out", dir.string()};
  if (!options.backend_options.empty()) {
    argv.push_back("--");
    argv.insert(argv.end(), options.backend_options.begin(), options.backend_options.end());
  }
  return start_child(argv, environment, dir / "run.log");
}

// A point's run ended with `status`: its record (a failure recorded for it when it wrote no
// summary of its own).
PointRecord finished_point(const DesignPoint& p, const SweepOptions& options, int status) {
  const fs::path dir = point_directory(options.out_dir, p);
  PointRecord record = read_point(p, options.out_dir);
  if (record.status == "pending") {
    record = {"failed", nullptr, last_error(dir / "run.log", status)};
    write_file_atomically(dir / "summary.json",
                          nlohmann::json{{"status", "failed"}, {"error", record.error}, {"case", p.resolved}}.dump(2) + "\n");
  }
  return record;
}

}  // namespace

SweepOutcome run_sweep(const SweepPlan& plan, const SweepOptions& options) {
  if (options.jobs < 1) throw std::invalid_argument("sweep: --jobs must be at least 1");
  const LauncherRank rank = launcher_rank();
  SweepOutcome outcome;
  outcome.rank = rank.rank;
  outcome.ranks = rank.size;
  fs::create_directories(options.out_dir);
  std::deque<std::size_t> queue = queue_points(plan, options, rank, outcome);
  Progress progress(options.progress, options.label, rank, outcome.total, outcome.already_done);
  const std::string coarse_warning = announce(progress, plan, options, rank, outcome, queue);
  if (options.write_tables) write_tables(plan, options.out_dir);
  if (options.list_only) return outcome;

  const auto environment = child_environment(rank.launched, options.jobs);
  struct Running {
    std::size_t point;
    WallClock::time_point start;
  };
  std::map<pid_t, Running> running;
  while (!queue.empty() || !running.empty()) {
    while (!queue.empty() && running.size() < static_cast<std::size_t>(options.jobs)) {
      const DesignPoint& p = plan.points[queue.front()];
      running[start_point(p, options, environment)] = {queue.front(), WallClock::now()};
      queue.pop_front();
      progress.line(fmt::format("started {}", p.name));
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(fmt::format("sweep: waiting for runs: {}", std::strerror(errno)));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const DesignPoint& p = plan.points[it->second.point];
    const double seconds = seconds_since(it->second.start);
    running.erase(it);
    const PointRecord record = finished_point(p, options, status);
    if (record.status == "completed") ++outcome.completed;
    else ++outcome.failed;
    if (options.write_tables) write_tables(plan, options.out_dir);
    progress.finished(record.status == "completed"
                          ? fmt::format("completed {} in {}{}", p.name, duration(seconds), maxima_text(record.summary))
                          : fmt::format("FAILED {} after {}: {}", p.name, duration(seconds), record.error),
                      queue.size() + running.size());
  }
  const std::string tables = options.write_tables ? fmt::format("; tables {} and {}", (options.out_dir / "sweep.csv").string(),
                                                                 (options.out_dir / "sweep.h5").string())
                                                   : "";
  progress.line(fmt::format("finished: {} completed, {} failed, {} already done, {} impossible{}{}", outcome.completed,
                            outcome.failed, outcome.already_done, outcome.impossible, tables,
                            coarse_warning.empty() ? "" : "; warning: " + coarse_warning));
  return outcome;
}

}  // namespace needlefem::sweep
