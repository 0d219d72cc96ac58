// The case schema: the single place that knows every case key, its type, unit, range,
// default and help text. Validation, `needlefem keys` and the echoed case all read it.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace needlefem {

enum class KeyType { Real, Integer, Flag, Text, Choice, RealList, TextList };

// A default value; monostate marks an optional key without default.
using KeyDefault =
    std::variant<std::monostate, double, long, bool, std::string, std::vector<double>, std::vector<std::string>>;

struct KeySpec {
  std::string key;                  // dotted: "needle.radius_mm"
  KeyType type = KeyType::Real;
  KeyDefault fallback;              // value when the case does not give the key
  std::string help;
  double min = -1e300, max = 1e300;  // inclusive numeric range (per element for lists)
  bool min_exclusive = false;
  std::vector<std::string> choices;  // for KeyType::Choice
  // KeyType::Choice: former names still accepted, each with the choice it now reads as.
  std::vector<std::pair<std::string, std::string>> aliases;
  std::size_t list_length = 0;       // for KeyType::RealList; 0 = any non-empty length
  bool input_file = false;           // KeyType::Text: a file the run reads, relative to the case file
};

const std::vector<KeySpec>& case_schema();
// `value` of a choice key under its current name (KeySpec::aliases); any other value unchanged.
const std::string& current_choice(const KeySpec& spec, const std::string& value);
const KeySpec* find_key(const std::string& key);
// The closest known key (edit distance), for "did you mean" hints; empty if none is close.
std::string closest_key(const std::string& key);
// A key's numeric range as "[0, 100]", "(0, inf)": bounds in their shortest exact form, and an
// unbounded side as inf (the schema stores it as +-1e300, which the user never typed).
std::string range_text(const KeySpec& spec);
// Human-readable description of one key (type, range, default) for --help and `keys`.
std::string describe_key(const KeySpec& spec);

}  // namespace needlefem
