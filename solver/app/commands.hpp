// Each needlefem sub-command lives in its own file and adds itself to the CLI here.
// A command's callback returns normally on success and throws on failure; main() turns
// every exception into one line on stderr and a non-zero exit code.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace needlefem::app {

// Options shared by commands that read a case file.
struct CaseOptions {
  std::string case_file;
  std::vector<std::string> overrides;  // --set key=value
  std::string out_dir;
  void add_to(CLI::App& command, const std::string& default_out);
};

// A sub-command that reads one case: `name CASE [--set K=V ...] [--out DIR]`, then calls `run`.
void add_case_command(CLI::App& app, const std::string& name, const std::string& description,
                      const std::string& default_out, void (*run)(const CaseOptions&));

// Arguments after "--", passed unchanged to PETSc and SUNDIALS.
const std::vector<std::string>& backend_options();

void add_mesh_command(CLI::App& app);
void add_keys_command(CLI::App& app);
void add_material_test_command(CLI::App& app);
void add_magnet_command(CLI::App& app);
void add_replay_command(CLI::App& app);
void add_steer_command(CLI::App& app);
void add_prbm_check_command(CLI::App& app);
void add_force_trajectory_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_converge_command(CLI::App& app);
void add_reestimate_command(CLI::App& app);

}  // namespace needlefem::app
