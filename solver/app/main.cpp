// needlefem: command-line entry point. Parses the command line with CLI11 and dispatches
// to the sub-commands; turns every error into one line on stderr and exit code 1 (128 + the
// signal for a run that SIGINT or SIGTERM stopped).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>

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

}  // namespace needlefem::app

int main(int argc, char** argv) {
  using namespace needlefem;
  // BLAS on one thread unless OPENBLAS_NUM_THREADS says otherwise: OpenBLAS's idle threads spin
  // after every call and take the cores from the OpenMP element loops (integration/blas_threads.hpp).
  start_blas_on_one_thread();
  if (const std::string note = openblas_coretype_note(); !note.empty())
    fmt::print(stderr, "needlefem: note: {}\n", note);
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
  app::add_reestimate_command(cli);

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
