// needlefem: command-line entry point. Parses the command line with CLI11 and dispatches
// to the sub-commands; turns every error into one line on stderr and exit code 1 (128 + the
// signal for a run that SIGINT or SIGTERM stopped).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/core.h>
#include <sys/personality.h>
#include <unistd.h>

#include "app/commands.hpp"
#include "integration/blas_threads.hpp"
#include "interrupt/interrupt_guard.hpp"
#include "io_errors/io_errors.hpp"

namespace needlefem::app {

namespace {
std::vector<std::string> g_backend_options;
}

const std::vector<std::string>& backend_options() { return g_backend_options; }

void CaseOptions::add_to(CLI::App& command, const std::string& default_out) {
  out_dir = default_out;
  command.add_option("case", case_file, "Case file (TOML); keys: `needlefem keys`")->required();
  command.add_option("--set", overrides, "Override a case key, e.g. --set needle.radius_mm=0.83")
      ->type_name("KEY=VALUE");
  command.add_option("--out", out_dir, "Output directory")->capture_default_str();
  // The key list is long (every key with its help): it has a command of its own rather than
  // burying this command's few options.
  command.footer("Case keys: `needlefem keys` lists them all with type, unit, range and default;\n"
                 "`needlefem keys PREFIX` only those starting with PREFIX (e.g. needle, motion.).");
}

void add_case_command(CLI::App& app, const std::string& name, const std::string& description,
                      const std::string& default_out, void (*run)(const CaseOptions&)) {
  auto* command = app.add_subcommand(name, description);
  auto options = std::make_shared<CaseOptions>();
  options->add_to(*command, default_out);
  command->callback([options, run] { run(*options); });
}

// gmsh's high-order optimiser works in the order of memory addresses, so with the address space
// randomised (ASLR) the nodes it moves differ in their last digits from one process to the next
// (up to 6e-6 mm on ~1200 nodes of the 0.4 mm brain tip), and frictional contact turns that into
// other step sequences (the default case took 27-37 s) and maxima in the 4th digit. Without
// randomisation, and with gmsh on a thread of its own (mesh/gmsh_session.hpp), a case run twice
// repeats bit for bit. `replay`, which talks to devices over the network, keeps it; where the
// kernel refuses (a seccomp profile), runs go on randomised. True when the process must restart.
bool stop_address_randomisation(int argc, char** argv) {
  if (argc > 1 && std::string_view(argv[1]) == "replay") return false;
  const int current = personality(0xffffffff);
  if (current == -1 || (current & ADDR_NO_RANDOMIZE)) return false;
  return personality(static_cast<unsigned long>(current) | ADDR_NO_RANDOMIZE) != -1;
}

}  // namespace needlefem::app

int main(int argc, char** argv) {
  using namespace needlefem;
  // OpenBLAS reads OPENBLAS_NUM_THREADS once, when it loads. Its idle threads spin after every
  // call, even a vector operation of PETSc's, and take the cores from the threads with work. The
  // element loops and the Cholesky factor thread with OpenMP themselves, so BLAS runs on one
  // thread (where a double-precision factorisation's BLAS-3 calls are the work, it asks for more:
  // blas_threads.hpp). Measured on 2 cores: tied brain-tip benchmark 22.1 s with two OpenBLAS
  // threads against 20.5 s with one; the default frictional case, whose MUMPS LU factorisations
  // lose BLAS's threads, 60.3 against 56.1 s. OpenMP keeps libgomp's default wait (spin about
  // 3 ms, then sleep): a GMRES iteration enters some 20 parallel regions (threaded vector
  // operations, element loops, triangular solves), and with OMP_WAIT_POLICY=passive, which
  // this once set when OpenBLAS's threads also spun, each woke its sleeping thread through the
  // kernel: Table I r = 0.83 mm, 10 deg, 0.15 mm 25.0-28.0 s of integration passive against
  // 23.0-24.3 s in alternating runs (the same 497 Newton and GMRES iterations). OpenBLAS's kernels for a CPU it
  // does not know are SSE3 ones (blas_threads.hpp). Unless the user chose them, start again
  // with these settings.
  bool restart = app::stop_address_randomisation(argc, argv);
  const char* blas_core = openblas_core_for_unrecognised_cpu();
  for (const auto& [variable, value] : {std::pair{"OPENBLAS_NUM_THREADS", "1"}, std::pair{"OPENBLAS_CORETYPE", blas_core}})
    if (value && !std::getenv(variable)) restart = setenv(variable, value, 1) == 0 || restart;
  if (restart) execv("/proc/self/exe", argv);  // returns only on failure: then run on with the defaults
  io::start_hdf5_without_termination();  // before MPI: io_errors.hpp
  // Everything after a bare "--" belongs to PETSc/SUNDIALS, untouched.
  std::vector<std::string> args(argv + 1, argv + argc);
  std::vector<std::string> own;
  bool backend = false;
  for (auto& a : args) {
    if (!backend && a == "--") {
      backend = true;
      continue;
    }
    (backend ? app::g_backend_options : own).push_back(a);
  }

  CLI::App cli{"needlefem: nonlinear finite-element solver for needle insertion into soft tissue.\n"
               "Case files are TOML; `needlefem keys` lists every key with unit, range and default.\n"
               "Options after `--` are passed unchanged to PETSc and SUNDIALS."};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", "needlefem 0.1.0");
  app::add_mesh_command(cli);
  app::add_keys_command(cli);
  app::add_material_test_command(cli);
  app::add_magnet_command(cli);
  app::add_replay_command(cli);
  app::add_steer_command(cli);
  app::add_prbm_check_command(cli);
  app::add_force_trajectory_command(cli);
  app::add_run_command(cli);
  app::add_sweep_command(cli);
  app::add_converge_command(cli);

  try {
    std::vector<std::string> reversed(own.rbegin(), own.rend());
    cli.parse(reversed);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e);
  } catch (const Interrupted& e) {
    fmt::print(stderr, "needlefem: {}\n", e.what());
    return 128 + e.signal_number;
  } catch (const std::exception& e) {
    fmt::print(stderr, "needlefem: error: {}\n", e.what());
    return 1;
  } catch (const std::string& e) {  // gmsh throws std::string
    fmt::print(stderr, "needlefem: error: gmsh: {}\n", e);
    return 1;
  }
  return 0;
}
