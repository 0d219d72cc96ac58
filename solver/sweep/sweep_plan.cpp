#include "sweep/sweep_plan.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "case/case.hpp"
#include "case/mesh_resolution.hpp"
#include "case/schema.hpp"
#include "case/specs/mesh_spec.hpp"

namespace needlefem::sweep {

namespace {

namespace fs = std::filesystem;

// Case keys to values, the key being one dotted string ("needle.radius_mm") whatever way the
// TOML spelled it: a toml::table whose keys contain dots is a copyable map of TOML values.
using FlatTable = toml::table;

// One axis of a grid: one key (from [axes]) or several keys varying together ([linked]).
struct Axis {
  std::vector<std::string> keys;
  std::vector<toml::array> values;  // per key, the same length for all keys
  std::size_t size() const { return values.front().size(); }
};

struct Grid {
  std::string name;
  FlatTable set;
  std::vector<Axis> axes;
};

class SweepFile {
 public:
  explicit SweepFile(fs::path file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    throw CaseError(fmt::format("{}: key '{}': {}", file_.string(), key, reason));
  }

  toml::table parse() const {
    const std::string text = read_input_file(file_, "sweep file");
    try {
      return toml::parse(text, file_.string());
    } catch (const toml::parse_error& e) {
      throw CaseError(fmt::format("{}:{}:{}: TOML syntax error: {}", file_.string(), e.source().begin.line,
                                  e.source().begin.column, e.description()));
    }
  }

  const KeySpec& case_key(const std::string& where, const std::string& key) const {
    if (const KeySpec* spec = find_key(key)) return *spec;
    const std::string hint = closest_key(key);
    fail(where + key, hint.empty() ? std::string("not a case key (see `needlefem keys`)")
                                   : fmt::format("not a case key (did you mean '{}'?)", hint));
  }

  // The case keys of a table, given quoted ("needle.radius_mm" = ...) or as dotted/nested
  // keys, in the order the file gives them (a toml::table iterates sorted by key).
  std::vector<std::pair<std::string, const toml::node*>> entries(const toml::table& table,
                                                                 const std::string& where) const {
    std::vector<std::pair<std::string, const toml::node*>> out;
    collect(table, "", where, out);
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
      const auto &x = a.second->source().begin, &y = b.second->source().begin;
      return std::pair(x.line, x.column) < std::pair(y.line, y.column);
    });
    return out;
  }

  FlatTable flatten(const toml::node* node, const std::string& where) const {
    FlatTable flat;
    if (!node) return flat;
    if (!node->is_table()) fail(where, "expected a table of case keys");
    for (const auto& [key, value] : entries(*node->as_table(), where + ".")) flat.insert_or_assign(key, *value);
    return flat;
  }

  // [axes] (one axis per key) or [linked] (one axis of all keys).
  std::vector<Axis> axes(const toml::node* node, const std::string& where, bool linked) const {
    if (!node) return {};
    if (!node->is_table()) fail(where, "expected a table of case keys");
    std::vector<Axis> out;
    for (const auto& [name, value] : entries(*node->as_table(), where + ".")) {
      const toml::array* list = value->as_array();
      if (const KeyType type = find_key(name)->type; type == KeyType::RealList || type == KeyType::TextList)
        fail(where + "." + name, "is a list key; only scalar keys can be swept");
      if (!list || list->empty()) fail(where + "." + name, "expected a non-empty list of values");
      for (const auto& element : *list)
        if (element.is_array() || element.is_table())
          fail(where + "." + name, "expected a list of scalar values");
      if (linked && !out.empty()) {
        if (list->size() != out.front().size())
          fail(where + "." + name, fmt::format("has {} values but {} has {}; linked lists vary together",
                                               list->size(), out.front().keys.front(), out.front().size()));
        out.front().keys.push_back(name);
        out.front().values.push_back(*list);
      } else {
        out.push_back({{name}, {*list}});
      }
    }
    return out;
  }

  // A [[grid]] table.
  Grid grid(const toml::table& table, const std::string& where, std::string name) const {
    for (const auto& [key, value] : table)
      if (key != "set" && key != "axes" && key != "linked" && key != "name")
        fail(where + std::string(key.str()), "unknown sweep key (expected set, axes, linked, name)");
    if (const auto* named = table.get("name")) {
      if (!named->is_string()) fail(where + "name", "expected a string");
      name = named->as_string()->get();
    }
    return grid(table.get("set"), table.get("axes"), table.get("linked"), where, std::move(name));
  }

  // A grid from its set/axes/linked tables (any may be absent); `where` prefixes key names in errors.
  Grid grid(const toml::node* set, const toml::node* axes_table, const toml::node* linked_table,
            const std::string& where, std::string name) const {
    Grid g;
    g.name = std::move(name);
    g.set = flatten(set, where + "set");
    g.axes = axes(axes_table, where + "axes", false);
    auto linked = axes(linked_table, where + "linked", true);
    g.axes.insert(g.axes.end(), linked.begin(), linked.end());
    for (const auto& axis : g.axes)
      for (const auto& key : axis.keys)
        if (std::count_if(g.axes.begin(), g.axes.end(), [&](const Axis& a) {
              return std::find(a.keys.begin(), a.keys.end(), key) != a.keys.end();
            }) > 1)
          fail(where + "axes." + key, "swept twice in the same grid");
    return g;
  }

 private:
  void collect(const toml::table& table, const std::string& prefix, const std::string& where,
               std::vector<std::pair<std::string, const toml::node*>>& out) const {
    for (const auto& [name, node] : table) {
      const std::string key = prefix + std::string(name.str());
      if (node.is_table() && !find_key(key)) {
        collect(*node.as_table(), key + ".", where, out);
        continue;
      }
      case_key(where, key);
      out.emplace_back(key, &node);
    }
  }

  fs::path file_;
};

// The base case's own keys, flattened the same way (its errors are the case loader's).
FlatTable flatten_case(const toml::table& table, const std::string& prefix = "") {
  FlatTable flat;
  for (const auto& [name, node] : table) {
    const std::string key = prefix + std::string(name.str());
    if (node.is_table() && !find_key(key)) {
      for (auto&& [k, v] : flatten_case(*node.as_table(), key + ".")) flat.insert_or_assign(k, v);
      continue;
    }
    flat.insert_or_assign(key, node);
  }
  return flat;
}

// A value as TOML text; reals in the shortest form that reads back to the same double.
std::string toml_value(const toml::node& node) {
  if (const auto* real = node.as_floating_point()) {
    std::string text = fmt::format("{}", real->get());
    if (text.find_first_of(".eEn") == std::string::npos) text += ".0";  // keep it a TOML float
    return text;
  }
  if (const auto* list = node.as_array()) {
    std::vector<std::string> items;
    for (const auto& element : *list) items.push_back(toml_value(element));
    return fmt::format("[{}]", fmt::join(items, ", "));
  }
  std::ostringstream out;
  node.visit([&](const auto& value) { out << value; });
  return out.str();
}

// The flat case as a TOML document, one [section] per key prefix.
std::string case_document(const FlatTable& flat, const std::string& header) {
  std::map<std::string, std::vector<std::string>> sections;
  for (const auto& [key, value] : flat) {
    const std::string k(key.str());
    const auto dot = k.rfind('.');
    sections[k.substr(0, dot)].push_back(fmt::format("{} = {}", k.substr(dot + 1), toml_value(value)));
  }
  std::string text = header;
  for (const auto& [section, lines] : sections) text += fmt::format("\n[{}]\n{}\n", section, fmt::join(lines, "\n"));
  return text;
}

nlohmann::json json_value(const toml::node& node) {
  if (const auto* v = node.as_floating_point()) return v->get();
  if (const auto* v = node.as_integer()) return v->get();
  if (const auto* v = node.as_boolean()) return v->get();
  if (const auto* v = node.as_string()) return v->get();
  return nullptr;
}

nlohmann::json json_default(const KeySpec& spec) {
  return std::visit(
      [](const auto& v) -> nlohmann::json {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::monostate>) return nullptr;
        else return v;
      },
      spec.fallback);
}

// Directory-name text of a value: numbers in shortest form, a file by its name, other text
// reduced to safe characters; "none" for no value.
std::string name_text(const nlohmann::json& value) {
  if (value.is_null() || value == "") return "none";
  if (value.is_number_float()) return fmt::format("{}", value.get<double>());
  std::string text = value.is_string() ? fs::path(value.get<std::string>()).filename().string() : value.dump();
  for (char& ch : text)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '-' && ch != '+') ch = '-';
  return text;
}

// The words of a key's last part that say what it is, without its unit words:
// "insertion_speed_mm_per_s" -> insertion, speed.
std::vector<std::string> key_words(const std::string& key) {
  static const std::set<std::string> kUnitWords{"mm", "um", "m", "m3", "deg", "rad", "s", "per", "pa", "kpa",
                                                "n", "kg", "j", "t", "hz", "percent"};
  std::vector<std::string> words;
  std::stringstream leaf(key.substr(key.rfind('.') + 1));
  for (std::string word; std::getline(leaf, word, '_');) words.push_back(word);
  while (words.size() > 1 && kUnitWords.contains(words.back())) words.pop_back();
  return words;
}

// The labels of the swept keys in point names: their initials; keys whose initials clash get their
// words, and keys whose words still clash the whole key.
std::vector<std::string> name_labels(const std::vector<std::string>& keys) {
  using Label = std::string (*)(const std::string&);
  const Label initials = [](const std::string& key) {
    std::string out;
    for (const auto& word : key_words(key)) out += word.front();
    return out;
  };
  const Label words = [](const std::string& key) { return fmt::format("{}", fmt::join(key_words(key), "-")); };
  const Label whole = [](const std::string& key) {
    std::string out = key;
    std::replace(out.begin(), out.end(), '.', '-');
    return out;
  };
  std::vector<std::string> labels;
  for (const auto& key : keys) labels.push_back(initials(key));
  for (const Label longer : {words, whole}) {
    std::map<std::string, int> uses;
    for (const auto& label : labels) ++uses[label];
    for (std::size_t k = 0; k < keys.size(); ++k)
      if (uses[labels[k]] > 1) labels[k] = longer(keys[k]);
  }
  return labels;
}

// A point's directory name: each swept key's label followed by the point's value, joined by '_'
// ("r0.5_b20_f0.25"); a value that is not a number follows a '-' ("dc-true").
std::string point_name(const std::vector<std::string>& labels, const std::vector<std::string>& keys,
                       const nlohmann::json& values) {
  std::vector<std::string> parts;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const nlohmann::json& value = values[keys[k]];
    parts.push_back(labels[k] + (value.is_number() ? "" : "-") + name_text(value));
  }
  return fmt::format("{}", fmt::join(parts, "_"));
}

std::vector<RuleViolation> scene_violations(const MeshSpec& mesh) {
  if (!generates_brain_tip_scene(mesh)) return {};
  return brain_tip_scene_violations(mesh.tissue, needle_tip_from_spec(mesh.needle_tip));
}

// The files a run reads (scene.mesh_file, needle.cad_file, ...: KeySpec::input_file) made absolute,
// relative to the file that named them: a point's case.toml lives in the sweep's output folder.
void absolute_input_files(FlatTable& flat, const fs::path& relative_to) {
  for (const KeySpec& spec : case_schema()) {
    if (!spec.input_file) continue;
    const auto* file = flat.get_as<std::string>(spec.key);
    if (!file) continue;
    const fs::path path(file->get());
    if (!path.empty() && path.is_relative()) flat.insert_or_assign(spec.key, (relative_to / path).string());
  }
}

// The base case's keys, flattened, with the files it names made absolute.
FlatTable base_case_table(const fs::path& base_case) {
  FlatTable flat;
  try {
    flat = flatten_case(toml::parse(read_input_file(base_case, "case file"), base_case.string()));
  } catch (const toml::parse_error& e) {
    throw CaseError(fmt::format("{}:{}:{}: TOML syntax error: {}", base_case.string(), e.source().begin.line,
                                e.source().begin.column, e.description()));
  }
  absolute_input_files(flat, base_case.parent_path());
  return flat;
}

// A design point from its flat case: the case file's text, validated by the case loader and
// the geometry rules (key errors become the violation "case").
DesignPoint design_point(const FlatTable& point, std::string name, nlohmann::json values, const std::string& header,
                         const std::string& origin) {
  DesignPoint p;
  p.name = std::move(name);
  p.values = std::move(values);
  p.case_text = case_document(point, header);
  try {
    const Case c = Case::parse(p.case_text, fmt::format("{} (point {})", origin, p.name));
    p.resolved = c.to_json();
    const MeshSpec mesh = parse_mesh_spec(c);
    p.violations = scene_violations(mesh);
    p.coarse_mesh = coarser_than_converged(mesh);
  } catch (const CaseError& e) {
    p.violations = {{"case", e.what()}};
  }
  return p;
}

// A JSON scalar (or list of numbers) as the TOML value it came from.
void insert_json(FlatTable& flat, const std::string& key, const nlohmann::json& value) {
  if (value.is_boolean()) flat.insert_or_assign(key, value.get<bool>());
  else if (value.is_number_integer()) flat.insert_or_assign(key, value.get<int64_t>());
  else if (value.is_number()) flat.insert_or_assign(key, value.get<double>());
  else if (value.is_string()) flat.insert_or_assign(key, value.get<std::string>());
  else if (value.is_array()) {
    toml::array list;
    for (const auto& element : value) list.push_back(element.get<double>());
    flat.insert_or_assign(key, std::move(list));
  }
}

// The point's keys overridden by a layer (the sweep's set, a grid's set and axis values). A layer
// stating the motion's length replaces the lower layers' statement of it (case/case.hpp).
void overlay(FlatTable& point, const FlatTable& layer) {
  if (std::any_of(layer.begin(), layer.end(), [](const auto& entry) { return states_motion_length(std::string(entry.first.str())); }))
    for (const auto& key : motion_length_keys()) point.erase(key);
  for (const auto& [key, value] : layer) point.insert_or_assign(key, value);
}

void add_unique(std::vector<std::string>& list, const std::string& item) {
  if (std::find(list.begin(), list.end(), item) == list.end()) list.push_back(item);
}

// The sweep file's grids: [axes] and [linked] as the main one, then each [[grid]].
std::vector<Grid> read_grids(const SweepFile& file, const toml::table& root) {
  std::vector<Grid> grids;
  if (root.contains("axes") || root.contains("linked"))
    grids.push_back(file.grid(nullptr, root.get("axes"), root.get("linked"), "", "main"));
  if (const auto* list = root.get("grid")) {
    if (!list->is_array_of_tables()) file.fail("grid", "expected [[grid]] tables");
    std::size_t index = 0;
    for (const auto& table : *list->as_array()) {
      const std::string where = fmt::format("grid[{}].", index);
      grids.push_back(file.grid(*table.as_table(), where, fmt::format("grid{}", ++index)));
    }
  }
  if (grids.empty()) file.fail("axes", "no design points: give [axes], [linked] or [[grid]] tables");
  return grids;
}

// What every point of a sweep starts from: the base case's keys, the sweep's [set] over them,
// the sweep's folder (the files it names are relative to it) and the header of each point's case.toml.
struct PointBase {
  FlatTable base;
  FlatTable fixed;
  fs::path sweep_dir;
  std::string header;
};

// Appends grid g's design points to the plan. A point that several grids share is listed once,
// with each grid's name; two different points with one folder name are an error.
void add_grid_points(const SweepFile& file, const Grid& g, const PointBase& start,
                     std::map<std::string, std::size_t>& by_name, SweepPlan& plan) {
  std::size_t count = 1;
  for (const auto& axis : g.axes) count *= axis.size();
  for (std::size_t flat_index = 0; flat_index < count; ++flat_index) {
    FlatTable point = start.base;
    overlay(point, start.fixed);
    FlatTable assigned = g.set;
    std::size_t rest = flat_index;
    for (auto axis = g.axes.rbegin(); axis != g.axes.rend(); ++axis) {  // last axis varies fastest
      const std::size_t i = rest % axis->size();
      rest /= axis->size();
      for (std::size_t k = 0; k < axis->keys.size(); ++k) assigned.insert_or_assign(axis->keys[k], axis->values[k][i]);
    }
    absolute_input_files(assigned, start.sweep_dir);
    overlay(point, assigned);

    nlohmann::json values;
    for (const std::string& key : plan.swept_keys) {
      const toml::node* given = point.get(key);
      values[key] = given ? json_value(*given) : json_default(*find_key(key));
    }
    std::string name = point_name(plan.name_labels, plan.swept_keys, values);
    DesignPoint p = design_point(point, std::move(name), std::move(values), start.header, plan.sweep_file.string());
    p.grids = {g.name};

    const auto [it, inserted] = by_name.emplace(p.name, plan.points.size());
    if (inserted) {
      plan.points.push_back(std::move(p));
      continue;
    }
    DesignPoint& same = plan.points[it->second];
    if (same.resolved != p.resolved || (same.resolved.is_null() && same.case_text != p.case_text))
      file.fail(plan.swept_keys.front(), fmt::format("two different design points share the directory name '{}'", p.name));
    add_unique(same.grids, g.name);
  }
}

}  // namespace

SweepPlan load_sweep(const fs::path& sweep_file) {
  const SweepFile file(sweep_file);
  const toml::table root = file.parse();
  for (const auto& [key, value] : root)
    if (key != "base" && key != "set" && key != "axes" && key != "linked" && key != "grid")
      file.fail(std::string(key.str()), "unknown sweep key (expected base, set, axes, linked, grid)");

  SweepPlan plan;
  plan.sweep_file = sweep_file;
  const auto* base = root.get_as<std::string>("base");
  if (!base) file.fail("base", "required: the base case file, relative to the sweep file");
  const fs::path sweep_dir = fs::absolute(sweep_file).parent_path();
  plan.base_case = (sweep_dir / base->get()).lexically_normal();
  if (!fs::exists(plan.base_case)) file.fail("base", fmt::format("cannot open {}", plan.base_case.string()));
  if (fs::is_directory(plan.base_case))
    file.fail("base", fmt::format("{} is a directory, not a case file", plan.base_case.string()));
  const FlatTable base_flat = base_case_table(plan.base_case);

  FlatTable fixed = file.flatten(root.get("set"), "set");
  absolute_input_files(fixed, sweep_dir);

  const std::vector<Grid> grids = read_grids(file, root);

  for (const auto& g : grids) {
    for (const auto& [key, value] : g.set) add_unique(plan.swept_keys, std::string(key.str()));
    for (const auto& axis : g.axes)
      for (const auto& key : axis.keys) add_unique(plan.swept_keys, key);
  }
  plan.name_labels = name_labels(plan.swept_keys);
  const std::string header = fmt::format("# Design point of the sweep {} (base case {}).\n", sweep_file.string(),
                                         plan.base_case.string());

  const PointBase start{base_flat, fixed, sweep_dir, header};
  std::map<std::string, std::size_t> by_name;
  for (const auto& g : grids) add_grid_points(file, g, start, by_name, plan);
  return plan;
}

SweepPlan plan_axis(const fs::path& base_case, const std::vector<std::string>& set, const std::string& key,
                    const std::vector<AxisPoint>& points) {
  const Case base = Case::load(base_case, set);  // the case loader's errors for the file and the overrides
  SweepPlan plan;
  plan.base_case = fs::absolute(base_case).lexically_normal();
  plan.swept_keys = {key};
  FlatTable flat = base_case_table(plan.base_case), set_layer;
  const nlohmann::json resolved = base.to_json();
  for (const auto& assignment : set) {
    const std::string given = assignment.substr(0, assignment.find('='));
    std::string pointer = "/" + given;
    std::replace(pointer.begin(), pointer.end(), '.', '/');
    insert_json(set_layer, given, resolved.at(nlohmann::json::json_pointer(pointer)));
  }
  overlay(flat, set_layer);
  absolute_input_files(flat, plan.base_case.parent_path());  // a --set file is relative to the case, as Case::path reads it
  std::string overrides;
  for (const auto& assignment : set) overrides += fmt::format(", --set {}", assignment);
  for (const auto& axis_point : points) {
    FlatTable point = flat, axis_layer;
    insert_json(axis_layer, key, axis_point.value);
    overlay(point, axis_layer);
    const std::string header = fmt::format("# {}{}, {} = {}.\n", plan.base_case.string(), overrides, key,
                                           axis_point.value.dump());
    plan.points.push_back(design_point(point, axis_point.name, nlohmann::json{{key, axis_point.value}}, header,
                                       plan.base_case.string()));
  }
  return plan;
}

}  // namespace needlefem::sweep
