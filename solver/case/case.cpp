// Case loading: TOML (toml++) -> flattened dotted keys -> checked against the schema ->
// defaults filled in. Every failure is a CaseError "ORIGIN: key 'KEY': REASON".
#include "case/case.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <variant>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "case/schema.hpp"

namespace needlefem {

using Value = std::variant<double, long, bool, std::string, std::vector<double>, std::vector<std::string>>;

struct Case::Values {
  std::map<std::string, Value> values;
  std::set<std::string> given;
};

namespace {

std::string node_type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a real number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date/time";
  }
}

class Checker {
 public:
  explicit Checker(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    throw case_error(origin_, key, reason);
  }

  const KeySpec& spec_of(const std::string& key) const {
    if (const KeySpec* spec = find_key(key)) return *spec;
    std::string hint = closest_key(key);
    fail(key, hint.empty() ? std::string("unknown key (see `needlefem keys`)")
                           : fmt::format("unknown key (did you mean '{}'?)", hint));
  }

  double number(const std::string& key, const toml::node& node, const KeySpec& spec) const {
    double v;
    if (auto i = node.as_integer()) v = static_cast<double>(i->get());
    else if (auto f = node.as_floating_point()) v = f->get();
    else fail(key, fmt::format("expected a real number, got {}", node_type_name(node)));
    if (!std::isfinite(v)) fail(key, "must be finite");
    check_range(key, v, spec);
    return v;
  }

  void check_range(const std::string& key, double v, const KeySpec& spec) const {
    const bool below = spec.min_exclusive ? v <= spec.min : v < spec.min;
    if (below || v > spec.max)
      fail(key, fmt::format("{} is out of range {}", v, range_text(spec)));
  }

  Value convert(const std::string& key, const toml::node& node) const {
    const KeySpec& spec = spec_of(key);
    switch (spec.type) {
      case KeyType::Real: return number(key, node, spec);
      case KeyType::Integer: {
        auto i = node.as_integer();
        if (!i) fail(key, fmt::format("expected an integer, got {}", node_type_name(node)));
        check_range(key, static_cast<double>(i->get()), spec);
        return static_cast<long>(i->get());
      }
      case KeyType::Flag: {
        auto b = node.as_boolean();
        if (!b) fail(key, fmt::format("expected true or false, got {}", node_type_name(node)));
        return b->get();
      }
      case KeyType::Text: {
        auto s = node.as_string();
        if (!s) fail(key, fmt::format("expected a string, got {}", node_type_name(node)));
        return s->get();
      }
      case KeyType::Choice: {
        auto s = node.as_string();
        if (!s) fail(key, fmt::format("expected a string, got {}", node_type_name(node)));
        const std::string choice = current_choice(spec, s->get());
        if (std::find(spec.choices.begin(), spec.choices.end(), choice) == spec.choices.end())
          fail(key, fmt::format("'{}' is not one of: {}", s->get(), fmt::join(spec.choices, ", ")));
        return choice;
      }
      case KeyType::RealList: {
        auto a = node.as_array();
        if (!a) fail(key, fmt::format("expected a list of real numbers, got {}", node_type_name(node)));
        if (a->empty() || (spec.list_length && a->size() != spec.list_length))
          fail(key, spec.list_length ? fmt::format("expected {} numbers, got {}", spec.list_length, a->size())
                                     : std::string("expected a non-empty list"));
        std::vector<double> out;
        for (const auto& element : *a) out.push_back(number(key, element, spec));
        return out;
      }
      case KeyType::TextList: {
        auto a = node.as_array();
        if (!a) fail(key, fmt::format("expected a list of strings, got {}", node_type_name(node)));
        std::vector<std::string> out;
        for (const auto& element : *a) {
          auto s = element.as_string();
          if (!s) fail(key, fmt::format("expected a list of strings, got {} in it", node_type_name(element)));
          out.push_back(s->get());
        }
        return out;
      }
    }
    fail(key, "unsupported key type");
  }

  void flatten(const toml::table& table, const std::string& prefix, Case::Values& into) const {
    for (const auto& [name, node] : table) {
      const std::string key = prefix.empty() ? std::string(name.str()) : prefix + "." + std::string(name.str());
      if (const toml::table* sub = node.as_table()) {
        if (find_key(key)) fail(key, "expected a value, got a table");
        flatten(*sub, key, into);
        continue;
      }
      into.values[key] = convert(key, node);
      into.given.insert(key);
    }
  }

 private:
  std::string origin_;
};

// "key=value": the value is read as TOML, or taken as a bare string for text/choice keys.
// The assignments of NEEDLEFEM_SET, separated by white space.
std::vector<std::string> environment_overrides() {
  std::vector<std::string> assignments;
  const char* text = std::getenv(kEnvironmentOverrides);
  std::istringstream words(text ? text : "");
  for (std::string word; words >> word;) assignments.push_back(word);
  return assignments;
}

void apply_override(const std::string& assignment, Case::Values& into, const std::string& source) {
  const Checker checker(source + " " + assignment);
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) checker.fail(assignment, "expected KEY=VALUE");
  const std::string key = assignment.substr(0, eq), raw = assignment.substr(eq + 1);
  const KeySpec& spec = checker.spec_of(key);
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + raw);
  } catch (const toml::parse_error&) {
    if (spec.type != KeyType::Text && spec.type != KeyType::Choice)
      checker.fail(key, fmt::format("cannot read '{}' as a value", raw));
    parsed.insert_or_assign("value", raw);
  }
  into.values[key] = checker.convert(key, *parsed.get("value"));
  into.given.insert(key);
}

// motion.duration_s from the motion's length as the case states it: the duration itself, the
// insertion travel over the insertion speed, or the rotation angle over the rotation speed, each
// plus half the start ramp (the travel the smoothstep start loses: geometry/needle_motion.hpp).
// Speeds are never derived, so every statement given must yield the same duration.
double motion_duration(const Checker& checker, const Case::Values& v) {
  const auto number = [&](const std::string& key) { return std::get<double>(v.values.at(key)); };
  const double half_ramp = 0.5 * number("motion.ramp_s");
  const std::string ramp_note = half_ramp > 0.0 ? " with the start ramp" : "";
  struct Statement {
    std::string key, text;
    double duration;
  };
  std::vector<Statement> stated;
  if (v.given.count("motion.duration_s")) {
    const double d = number("motion.duration_s");
    stated.push_back({"motion.duration_s", fmt::format("motion.duration_s = {:.6g} s", d), d});
  }
  // A length at a speed: the duration it takes, if the speed moves the needle that way.
  const auto length = [&](const std::string& key, const std::string& speed_key, const char* unit) {
    if (!v.given.count(key)) return;
    const double amount = number(key), speed = number(speed_key);
    if (amount == 0.0 && speed == 0.0) return;  // no turn at no speed: says nothing about the duration
    if (speed == 0.0) checker.fail(key, fmt::format("{:.6g} {} needs a nonzero {}", amount, unit, speed_key));
    if (!(amount / speed > 0.0))
      checker.fail(key, fmt::format("{:.6g} {} is not reached moving at {} = {:.6g} {}/s (the signs differ or the "
                                    "length is 0)", amount, unit, speed_key, speed, unit));
    const double d = amount / speed + half_ramp;
    stated.push_back({key, fmt::format("{} = {:.6g} {} at {} = {:.6g} {}/s takes {:.6g} s{}", key, amount, unit,
                                       speed_key, speed, unit, d, ramp_note), d});
  };
  length("motion.insertion_travel_mm", "motion.insertion_speed_mm_per_s", "mm");
  length("motion.rotation_deg", "motion.rotation_speed_deg_per_s", "deg");
  if (stated.empty()) return number("motion.duration_s");
  for (const auto& other : stated)
    if (std::abs(other.duration - stated.front().duration) > 1e-6 * stated.front().duration)
      checker.fail(other.key, fmt::format("{}, but {}", other.text, stated.front().text));
  return stated.front().duration;
}

Value default_value(const KeySpec& spec) {
  return std::visit(
      [](const auto& v) -> Value {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) return 0.0;  // never used: optional keys are skipped
        else return v;
      },
      spec.fallback);
}

}  // namespace

Case::Case(std::string origin, std::filesystem::path base_dir, std::shared_ptr<const Values> values)
    : origin_(std::move(origin)), base_dir_(std::move(base_dir)), values_(std::move(values)) {}

Case Case::parse(const std::string& toml_text, const std::string& origin, const std::vector<std::string>& overrides) {
  auto values = std::make_shared<Values>();
  const Checker checker(origin);
  toml::table table;
  try {
    table = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& e) {
    throw CaseError(fmt::format("{}:{}:{}: TOML syntax error: {}", origin, e.source().begin.line,
                                e.source().begin.column, e.description()));
  }
  checker.flatten(table, "", *values);
  // A layer of overrides replaces the values below it; one that states the motion's length drops
  // the lower layers' statements of it (motion_length_keys).
  const auto apply_layer = [&](const std::vector<std::string>& assignments, const std::string& source) {
    Values set;
    for (const auto& assignment : assignments) apply_override(assignment, set, source);
    if (std::any_of(set.given.begin(), set.given.end(), states_motion_length))
      for (const auto& key : motion_length_keys()) {
        values->values.erase(key);
        values->given.erase(key);
      }
    for (auto& [key, value] : set.values) values->values[key] = std::move(value);
    values->given.insert(set.given.begin(), set.given.end());
  };
  apply_layer(overrides, "--set");
  apply_layer(environment_overrides(), kEnvironmentOverrides);
  for (const auto& spec : case_schema())
    if (!values->values.count(spec.key) && !std::holds_alternative<std::monostate>(spec.fallback))
      values->values[spec.key] = default_value(spec);
  values->values["motion.duration_s"] = motion_duration(Checker(origin), *values);
  const auto base = std::filesystem::path(origin).parent_path();
  return Case(origin, base, std::move(values));
}

std::string read_input_file(const std::filesystem::path& file, const std::string& what) {
  std::error_code error;
  if (std::filesystem::is_directory(file, error))
    throw CaseError(fmt::format("{}: is a directory, not a {}", file.string(), what));
  std::ifstream in(file);
  if (!in) throw CaseError(fmt::format("{}: cannot open {} ({})", file.string(), what, std::strerror(errno)));
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw CaseError(fmt::format("{}: cannot read {}", file.string(), what));
  std::string content = text.str();
  if (content.find_first_not_of(" \t\r\n") == std::string::npos)
    throw CaseError(fmt::format("{}: empty {}", file.string(), what));
  return content;
}

Case Case::load(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return parse(read_input_file(file, "case file"), file.string(), overrides);
}

namespace {
template <class T>
const T& typed(const std::map<std::string, Value>& values, const std::string& key) {
  auto it = values.find(key);
  if (it == values.end()) throw std::logic_error("case key '" + key + "' is not in the schema or has no value");
  const T* v = std::get_if<T>(&it->second);
  if (!v) throw std::logic_error("case key '" + key + "' read with the wrong type");
  return *v;
}
}  // namespace

double Case::real(const std::string& key) const { return typed<double>(values_->values, key); }
long Case::integer(const std::string& key) const { return typed<long>(values_->values, key); }
bool Case::flag(const std::string& key) const { return typed<bool>(values_->values, key); }
std::string Case::text(const std::string& key) const { return typed<std::string>(values_->values, key); }
std::vector<double> Case::reals(const std::string& key) const {
  return typed<std::vector<double>>(values_->values, key);
}
std::vector<std::string> Case::texts(const std::string& key) const {
  return typed<std::vector<std::string>>(values_->values, key);
}
bool Case::has(const std::string& key) const { return values_->values.count(key) > 0; }
std::optional<double> Case::maybe_real(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return real(key);
}
std::optional<long> Case::maybe_integer(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return integer(key);
}
std::optional<std::vector<double>> Case::maybe_reals(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return reals(key);
}
bool Case::given(const std::string& key) const { return values_->given.count(key) > 0; }

std::filesystem::path Case::path(const std::string& key) const {
  const std::string value = text(key);
  if (value.empty()) return {};
  std::filesystem::path p(value);
  return p.is_absolute() ? p : base_dir_ / p;
}

const std::vector<std::string>& motion_length_keys() {
  static const std::vector<std::string> keys{"motion.duration_s", "motion.insertion_travel_mm", "motion.rotation_deg"};
  return keys;
}

bool states_motion_length(const std::string& key) {
  const auto& keys = motion_length_keys();
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

CaseError case_error(const std::string& origin, const std::string& key, const std::string& reason) {
  return CaseError(fmt::format("{}: key '{}': {}", origin, key, reason));
}

CaseError Case::error(const std::string& key, const std::string& reason) const {
  return case_error(origin_, key, reason);
}

std::string Case::to_toml() const {
  toml::table root;
  for (const auto& [key, value] : values_->values) {
    toml::table* table = &root;
    std::size_t start = 0, dot;
    while ((dot = key.find('.', start)) != std::string::npos) {
      auto name = key.substr(start, dot - start);
      if (!table->contains(name)) table->insert(name, toml::table{});
      table = table->get_as<toml::table>(name);
      start = dot + 1;
    }
    const std::string leaf = key.substr(start);
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, std::vector<std::string>>) {
            toml::array array;
            for (const auto& x : v) array.push_back(x);
            table->insert(leaf, std::move(array));
          } else if constexpr (std::is_same_v<T, long>) {
            table->insert(leaf, static_cast<int64_t>(v));
          } else {
            table->insert(leaf, v);
          }
        },
        value);
  }
  std::ostringstream out;
  out << "# resolved case from " << origin_ << "\n" << root << "\n";
  return out.str();
}

namespace {
// Where a dotted key ("needle.radius_mm") sits in the echoed case: "/needle/radius_mm".
nlohmann::json::json_pointer pointer_to(const std::string& key) {
  std::string pointer = "/" + key;
  std::replace(pointer.begin(), pointer.end(), '.', '/');
  return nlohmann::json::json_pointer(pointer);
}
}  // namespace

nlohmann::json Case::to_json() const {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [key, value] : values_->values)
    std::visit([&](const auto& v) { out[pointer_to(key)] = v; }, value);
  return out;
}

nlohmann::json Case::with_current_choice_names(nlohmann::json echoed) {
  if (!echoed.is_object()) return echoed;
  for (const KeySpec& spec : case_schema()) {
    if (spec.aliases.empty()) continue;
    const nlohmann::json::json_pointer at = pointer_to(spec.key);
    if (echoed.contains(at) && echoed[at].is_string()) echoed[at] = current_choice(spec, echoed[at].get<std::string>());
  }
  return echoed;
}

}  // namespace needlefem
