// `needlefem keys [PREFIX]`: prints the case schema (every key, type, unit, range, default, help).
#include <fmt/core.h>

#include "app/commands.hpp"
#include "case/schema.hpp"

namespace needlefem::app {

void add_keys_command(CLI::App& app) {
  auto* command = app.add_subcommand("keys", "List every case key with its type, range, default and help");
  auto prefix = std::make_shared<std::string>();
  command->add_option("prefix", *prefix, "Only keys starting with this, e.g. needle or material.");
  command->callback([prefix] {
    for (const auto& spec : case_schema())
      if (spec.key.rfind(*prefix, 0) == 0) fmt::print("{}\n", describe_key(spec));
  });
}

}  // namespace needlefem::app
