// A validated, fully resolved case: every key of the schema (case/schema.cpp) with its value
// from the case file, a --set override, or the schema default. Values are in the units their
// key names carry (radius_mm, bevel_deg, ...); convert to SI where the physics starts.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "case/case_error.hpp"

namespace needlefem {

// The text of an input file the user named (`what`: "case file", "sweep file"). Refuses with a
// CaseError "FILE: REASON" a path that cannot be opened, a directory, or a file holding nothing
// but white space ("empty case file"): none of them is a case, and running the defaults instead
// would be silent.
std::string read_input_file(const std::filesystem::path& file, const std::string& what);

// The keys that state how long the needle moves: motion.duration_s, motion.insertion_travel_mm,
// motion.rotation_deg. Case::parse resolves motion.duration_s from those given and refuses them
// if they disagree. A layer of overrides (--set, a sweep's set and axis values) that gives one of
// them restates the motion's length: the lower layers' statements of it are dropped, not
// contradicted, so `--set motion.duration_s=0.01` shortens a case that states its travel.
const std::vector<std::string>& motion_length_keys();
bool states_motion_length(const std::string& key);

// The environment variable whose "KEY=VALUE" words (separated by white space) override every case
// the process (and the runs it starts) loads, after --set: a whole workflow on other settings
// without editing its commands, e.g. NEEDLEFEM_SET="tissue.core_element_mm=1.5 motion.duration_s=0.001"
// (how tests/readme runs the README's commands on small settings). The resolved case echoes them.
inline constexpr const char* kEnvironmentOverrides = "NEEDLEFEM_SET";

class Case {
 public:
  // Reads and validates a TOML case file, then applies "key=value" overrides (from --set), then
  // those of NEEDLEFEM_SET. Throws CaseError naming the file (or "--set", "NEEDLEFEM_SET"), the key
  // and the reason.
  static Case load(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
  // Validates a TOML document given as text; `origin` names it in error messages.
  static Case parse(const std::string& toml_text, const std::string& origin,
                    const std::vector<std::string>& overrides = {});

  const std::string& origin() const { return origin_; }

  // Typed access by dotted key ("needle.radius_mm"). Asking for a key the schema does not
  // know, or with the wrong type, is a programming error (std::logic_error).
  double real(const std::string& key) const;
  long integer(const std::string& key) const;
  bool flag(const std::string& key) const;
  std::string text(const std::string& key) const;
  std::vector<double> reals(const std::string& key) const;
  std::vector<std::string> texts(const std::string& key) const;
  // Keys without a default (optional) may be absent.
  bool has(const std::string& key) const;
  std::optional<double> maybe_real(const std::string& key) const;
  std::optional<long> maybe_integer(const std::string& key) const;
  std::optional<std::vector<double>> maybe_reals(const std::string& key) const;
  // A text key naming a file, resolved relative to the case file's folder ("" stays "").
  std::filesystem::path path(const std::string& key) const;
  // True when the key was given in the file or by --set rather than taken from the default.
  bool given(const std::string& key) const;

  // The fully resolved case, echoed into every output.
  std::string to_toml() const;
  nlohmann::json to_json() const;
  // A case echoed by an earlier version (a summary.json's "case") with each choice it names by a
  // former name (KeySpec::aliases) under its current one: a result made before a choice was
  // renamed still matches its case.
  static nlohmann::json with_current_choice_names(nlohmann::json echoed);

  // A CaseError message "ORIGIN: key 'KEY': REASON" for cross-key rules checked elsewhere.
  CaseError error(const std::string& key, const std::string& reason) const;

 // Opaque storage of the resolved values (defined in case.cpp).
  struct Values;

 private:
  Case(std::string origin, std::filesystem::path base_dir, std::shared_ptr<const Values> values);
  std::string origin_;
  std::filesystem::path base_dir_;
  std::shared_ptr<const Values> values_;
};

}  // namespace needlefem
