// `needlefem material-test`: drives one material through a homogeneous history at a single
// material point (no mesh) and prints CSV on stdout; the material's full description, with
// its instantaneous and long-term shear moduli, goes to stderr.
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "case/case.hpp"
#include "physics/material/material.hpp"
#include "physics/material/material_point.hpp"

namespace needlefem::app {

namespace {

struct MaterialTestOptions {
  std::string preset;
  std::string case_file;
  std::vector<std::string> overrides;
  std::string history = "uniaxial";
  std::optional<double> target;
  material::LoadProgram program;
};

const std::map<std::string, material::LoadHistory> kHistories{
    {"uniaxial", material::LoadHistory::Uniaxial},
    {"shear", material::LoadHistory::Shear},
    {"relaxation", material::LoadHistory::Relaxation},
    {"constant-rate", material::LoadHistory::ConstantRate}};

// --to when not given: a useful default range for each history.
double default_target(material::LoadHistory history) {
  switch (history) {
    case material::LoadHistory::Uniaxial: return 1.5;
    case material::LoadHistory::Shear: return 1.0;
    case material::LoadHistory::Relaxation: return 1.1;
    case material::LoadHistory::ConstantRate: return 0.7;
  }
  return 1.0;
}

void run(MaterialTestOptions options) {
  const material::Material tissue =
      options.case_file.empty()
          ? material::material_preset(options.preset.empty() ? "miller-brain" : options.preset)
          : material::material_from_spec(parse_material_spec(Case::load(options.case_file, options.overrides)));
  options.program.history = kHistories.at(options.history);
  options.program.target = options.target.value_or(default_target(options.program.history));

  const auto rows = material::run_material_point(tissue, options.program);
  // Every column finite (the strain rate of an instantaneous history is inf by definition, never NaN).
  for (const auto& row : rows)
    for (const double value : {row.time_s, row.stretch, row.shear, row.nominal_stress_pa, row.cauchy_stress_pa,
                               row.log_strain, std::isnan(row.strain_rate_per_s) ? row.strain_rate_per_s : 0.0})
      if (!std::isfinite(value))
        throw std::invalid_argument(fmt::format("material-test: --to {:.6g}: the {} history gives a non-finite value "
                                                "(NaN or inf); choose a smaller --to",
                                                options.program.target, options.history));
  fmt::print(stderr, "# material {}\n", tissue.description());
  fmt::print("time_s,stretch,shear,nominal_stress_pa,cauchy_stress_pa,log_strain,strain_rate_per_s\n");
  for (const auto& row : rows)
    fmt::print("{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}\n", row.time_s, row.stretch, row.shear,
               row.nominal_stress_pa, row.cauchy_stress_pa, row.log_strain, row.strain_rate_per_s);
}

}  // namespace

void add_material_test_command(CLI::App& app) {
  auto options = std::make_shared<MaterialTestOptions>();
  auto* command = app.add_subcommand(
      "material-test",
      "Drive a tissue material through a homogeneous history at one material point and print CSV:\n"
      "time_s,stretch,shear,nominal_stress_pa,cauchy_stress_pa,log_strain,strain_rate_per_s.\n"
      "The hyperelastic constants of the presets (and material.c.._instantaneous_pa in a case) are\n"
      "INSTANTANEOUS moduli: the response to a sudden load, before any Prony relaxation. The fully\n"
      "relaxed (long-term) shear modulus is g_inf times the instantaneous one; both are printed on stderr.\n"
      "Axial histories load along x with traction-free lateral faces; laws with a volumetric/isochoric\n"
      "split are driven exactly incompressible (J = 1), the co-rotational law with its Poisson ratio.\n"
      "nominal = force per undeformed area, cauchy = true stress, both along the loading axis (shear rows:\n"
      "the shear stress). log_strain = ln(stretch) (shear: max principal asinh(shear/2)); strain_rate =\n"
      "d(ln stretch)/dt (inf for the instantaneous elastic histories, 0 for --long-term).");
  auto* preset = command->add_option("--material", options->preset,
                                     "Material preset: miller-brain (default; C10 = C01 = 263 Pa, C20 = C02 = 491 Pa) "
                                     "or miller-brain-c10-c20 (C10 = 263, C20 = 491 Pa); instantaneous moduli, "
                                     "Prony g = 0.450, 0.365 at tau = 0.5, 50 s");
  auto* case_file = command->add_option("--case", options->case_file, "Take the material from this case's [material] table");
  preset->excludes(case_file);
  command->add_option("--set", options->overrides, "Override a case key (with --case), e.g. --set material.bulk_modulus_pa=1e6")
      ->type_name("KEY=VALUE")
      ->needs(case_file);
  command->add_option("--history", options->history,
                      "uniaxial: stretch 1 -> --to, instantaneous elastic response; shear: simple shear amount "
                      "0 -> --to; relaxation: stretch ramped linearly to --to in --ramp s, held --hold s; "
                      "constant-rate: stretch changed at engineering strain rate --rate until --to")
      ->check(CLI::IsMember({"uniaxial", "shear", "relaxation", "constant-rate"}))
      ->capture_default_str();
  command->add_option("--to", options->target,
                      "Final stretch (axial histories; < 1 compresses) or shear amount "
                      "(defaults: uniaxial 1.5, shear 1.0, relaxation 1.1, constant-rate 0.7)");
  command->add_option("--steps", options->program.steps, "Steps of the loading part")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--ramp", options->program.ramp_s, "relaxation: ramp duration, s")->capture_default_str();
  command->add_option("--hold", options->program.hold_s, "relaxation: hold duration, s")->capture_default_str();
  command->add_option("--rate", options->program.rate_per_s, "constant-rate: engineering strain rate, 1/s")
      ->capture_default_str();
  command->add_flag("--long-term", options->program.long_term,
                    "uniaxial/shear: fully relaxed (long-term) response instead of the instantaneous one");
  command->callback([options] { run(*options); });
}

}  // namespace needlefem::app
