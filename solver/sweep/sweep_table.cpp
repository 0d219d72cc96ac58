#include "sweep/sweep_table.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <sys/file.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <deque>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "case/case.hpp"
#include "case/schema.hpp"
#include "io_errors/io_errors.hpp"
#include "output/csv.hpp"

namespace needlefem::sweep {

namespace fs = std::filesystem;

namespace {

constexpr double kEmpty = std::numeric_limits<double>::quiet_NaN();
constexpr std::int8_t kUnknown = -1;

// Paper 001's safety limits, applied to a run's maxima when its summary has no "thresholds".
struct Limit {
  const char* name;
  const char* maximum;  // key under summary "max"
  double value;
};
constexpr Limit kPaperLimits[] = {{"log_strain", "log_strain", 0.19},
                                  {"strain_rate_per_s", "strain_rate_per_s", 10.0},
                                  {"stress_pa", "von_mises_pa", 120e3}};

constexpr const char* kMaxima[] = {"log_strain", "strain_rate_per_s", "von_mises_pa", "principal_stress_pa"};
constexpr const char* kNeedle[] = {"max_axial_force_n", "max_torque_n_m", "max_lateral_force_n"};

enum class Kind { text, number, flag };

struct Column {
  std::string name;
  Kind kind;
  std::vector<std::string> text;
  std::vector<double> number;
  std::vector<std::int8_t> flag;
};

double number_at(const nlohmann::json& json, const nlohmann::json::json_pointer& pointer) {
  if (!json.is_object() || !json.contains(pointer)) return kEmpty;
  const auto& value = json.at(pointer);
  return value.is_number() ? value.get<double>() : kEmpty;
}

// pass (1) / fail (0) of one summary "thresholds" entry, -1 when it says neither.
std::int8_t entry_pass(const nlohmann::json& entry) {
  if (entry.is_boolean()) return entry.get<bool>();
  if (!entry.is_object()) return kUnknown;
  for (const char* key : {"pass", "passed", "safe", "ok"})
    if (entry.contains(key) && entry[key].is_boolean()) return entry[key].get<bool>();
  if (entry.contains("value") && entry.contains("limit") && entry["value"].is_number() && entry["limit"].is_number())
    return entry["value"].get<double>() <= entry["limit"].get<double>();
  return kUnknown;
}

// Threshold name -> pass/fail for a completed run.
std::vector<std::pair<std::string, std::int8_t>> threshold_results(const nlohmann::json& summary) {
  std::vector<std::pair<std::string, std::int8_t>> out;
  if (summary.contains("thresholds")) {
    const auto& thresholds = summary["thresholds"];
    if (thresholds.is_object())
      for (const auto& [name, entry] : thresholds.items()) out.emplace_back(name, entry_pass(entry));
    else if (thresholds.is_array())
      for (const auto& entry : thresholds)
        if (entry.is_object() && entry.contains("name") && entry["name"].is_string())
          out.emplace_back(entry["name"].get<std::string>(), entry_pass(entry));
    return out;
  }
  for (const auto& limit : kPaperLimits) {
    const double value = number_at(summary, nlohmann::json::json_pointer(fmt::format("/max/{}/value", limit.maximum)));
    out.emplace_back(limit.name, std::isnan(value) ? kUnknown : static_cast<std::int8_t>(value <= limit.value));
  }
  return out;
}

std::string joined_rules(const DesignPoint& point, bool messages) {
  std::string out;
  for (const auto& v : point.violations)
    out += (out.empty() ? "" : "; ") + (messages ? fmt::format("rule '{}': {}", v.rule, v.message) : v.rule);
  return out;
}

// A deque: columns are filled through references that must survive later additions.
Column& add_column(std::deque<Column>& columns, std::string name, Kind kind) {
  return columns.emplace_back(Column{std::move(name), kind, {}, {}, {}});
}

// Mesh-objective metrics of each limit (run/safety_report.hpp) and their verdicts, then the run's.
void add_safety_columns(std::deque<Column>& columns, const std::vector<PointRecord>& records) {
  for (const auto& limit : kPaperLimits) {
    for (const auto& [column, key] : {std::pair{"critical_distance_{}", "critical_distance"},
                                      std::pair{"volume_above_{}_mm3", "volume_above_limit_mm3"},
                                      std::pair{"percentile_{}", "percentile"}}) {
      Column& c = add_column(columns, fmt::format(fmt::runtime(column), limit.name), Kind::number);
      const nlohmann::json::json_pointer pointer(fmt::format("/safety/{}/{}/value", limit.name, key));
      for (const auto& r : records) c.number.push_back(number_at(r.summary, pointer));
    }
  }
  const auto add_verdict = [&](const std::string& column, const std::string& pointer_text) {
    Column& c = add_column(columns, column, Kind::flag);
    const nlohmann::json::json_pointer pointer(pointer_text);
    for (const auto& r : records) {
      const bool has = r.status == "completed" && r.summary.contains(pointer) && r.summary.at(pointer).is_string();
      c.flag.push_back(!has ? kUnknown : static_cast<std::int8_t>(r.summary.at(pointer).get<std::string>() == "pass"));
    }
  };
  for (const auto& limit : kPaperLimits)
    add_verdict(fmt::format("verdict_{}", limit.name), fmt::format("/safety/{}/verdict", limit.name));
  add_verdict("verdict", "/verdict");  // the run's: fail when any limit fails
}

// Threshold columns: the union of the names the completed runs report, in first-seen order, and
// "safe" (every threshold passed).
void add_threshold_columns(std::deque<Column>& columns, const std::vector<PointRecord>& records) {
  std::vector<std::vector<std::pair<std::string, std::int8_t>>> results;
  std::vector<std::string> names;
  for (const auto& r : records) {
    results.push_back(r.status == "completed" ? threshold_results(r.summary) : decltype(results)::value_type{});
    for (const auto& [name, pass] : results.back())
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  for (const auto& name : names) {
    Column& c = add_column(columns, "pass_" + name, Kind::flag);
    for (const auto& row : results) {
      auto it = std::find_if(row.begin(), row.end(), [&](const auto& entry) { return entry.first == name; });
      c.flag.push_back(it == row.end() ? kUnknown : it->second);
    }
  }
  Column& safe = add_column(columns, "safe", Kind::flag);
  for (const auto& row : results) {
    std::int8_t all = row.empty() ? kUnknown : 1;
    for (const auto& [name, pass] : row) all = pass == 0 ? 0 : (pass == kUnknown && all == 1 ? kUnknown : all);
    safe.flag.push_back(all);
  }
}

std::deque<Column> table_columns(const SweepPlan& plan, const fs::path& out_dir) {
  std::vector<PointRecord> records;
  for (const auto& p : plan.points) records.push_back(read_point(p, out_dir));

  std::deque<Column> columns;
  auto add = [&](std::string name, Kind kind) -> Column& { return add_column(columns, std::move(name), kind); };
  Column& point = add("point", Kind::text);
  Column& grids = add("grids", Kind::text);
  for (const auto& p : plan.points) {
    point.text.push_back(p.name);
    grids.text.push_back(fmt::format("{}", fmt::join(p.grids, ",")));
  }
  for (const auto& key : plan.swept_keys) {
    const KeyType type = find_key(key)->type;
    Column& c = add(key, type == KeyType::Real || type == KeyType::Integer ? Kind::number : Kind::text);
    for (const auto& p : plan.points) {
      const auto& v = p.values[key];
      if (c.kind == Kind::number) c.number.push_back(v.is_number() ? v.get<double>() : kEmpty);
      else c.text.push_back(v.is_string() ? v.get<std::string>() : v.is_null() ? "" : v.dump());
    }
  }
  Column& status = add("status", Kind::text);
  for (const auto& r : records) status.text.push_back(r.status);
  for (const char* name : kMaxima) {
    Column& c = add(fmt::format("max_{}", name), Kind::number);
    for (const auto& r : records) c.number.push_back(number_at(r.summary, nlohmann::json::json_pointer(fmt::format("/max/{}/value", name))));
  }
  for (const char* name : kNeedle) {
    Column& c = add(fmt::format("needle_{}", name), Kind::number);
    for (const auto& r : records) c.number.push_back(number_at(r.summary, nlohmann::json::json_pointer(fmt::format("/needle/{}", name))));
  }
  add_safety_columns(columns, records);
  Column& coarse_mesh = add("coarse_mesh", Kind::text);  // empty: the converged setting (or not judged)
  for (const auto& p : plan.points) coarse_mesh.text.push_back(fmt::format("{}", fmt::join(p.coarse_mesh, "; ")));
  add_threshold_columns(columns, records);

  Column& dofs = add("dofs", Kind::number);
  Column& wall = add("wall_s", Kind::number);
  Column& reached = add("time_reached_s", Kind::number);
  for (const auto& r : records) {
    dofs.number.push_back(number_at(r.summary, nlohmann::json::json_pointer("/solver/dofs")));
    wall.number.push_back(number_at(r.summary, nlohmann::json::json_pointer("/solver/wall_s")));
    reached.number.push_back(number_at(r.summary, nlohmann::json::json_pointer("/time_reached_s")));
  }
  Column& rules = add("rules", Kind::text);
  Column& error = add("error", Kind::text);
  for (std::size_t i = 0; i < plan.points.size(); ++i) {
    rules.text.push_back(joined_rules(plan.points[i], false));
    error.text.push_back(records[i].error);
  }
  return columns;
}

std::string csv_text(const std::deque<Column>& columns, std::size_t rows) {
  std::vector<std::string> header;
  for (const auto& c : columns) header.push_back(output::csv_field(c.name));
  std::string text = fmt::format("{}\n", fmt::join(header, ","));
  for (std::size_t i = 0; i < rows; ++i) {
    std::vector<std::string> fields;
    for (const auto& c : columns) {
      if (c.kind == Kind::text) fields.push_back(output::csv_field(c.text[i]));
      else if (c.kind == Kind::number) fields.push_back(std::isnan(c.number[i]) ? "" : fmt::format("{:.9g}", c.number[i]));
      else fields.push_back(c.flag[i] == kUnknown ? "" : fmt::format("{}", c.flag[i]));
    }
    text += fmt::format("{}\n", fmt::join(fields, ","));
  }
  return text;
}

// An HDF5 identifier closed when it goes out of scope.
class H5Id {
 public:
  H5Id(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("sweep table: HDF5 cannot " + what);
  }
  H5Id(H5Id&& other) noexcept : id_(std::exchange(other.id_, -1)), close_(other.close_) {}
  H5Id& operator=(H5Id&&) = delete;
  ~H5Id() {
    if (id_ >= 0) close_(id_);
  }
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void h5_check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("sweep table: HDF5 cannot " + what);
}

H5Id utf8_text_type() {
  H5Id type(H5Tcopy(H5T_C_S1), H5Tclose, "copy the string type");
  h5_check(H5Tset_size(type, H5T_VARIABLE), "make strings variable-length");
  h5_check(H5Tset_cset(type, H5T_CSET_UTF8), "set UTF-8");
  return type;
}

std::vector<const char*> c_strings(const std::vector<std::string>& texts) {
  std::vector<const char*> out;
  for (const auto& t : texts) out.push_back(t.c_str());
  return out;
}

void write_text_attribute(hid_t object, const std::string& name, const std::vector<std::string>& texts, bool scalar) {
  H5Id type = utf8_text_type();
  const hsize_t size = texts.size();
  H5Id space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &size, nullptr), H5Sclose, "create a dataspace");
  H5Id attribute(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                 "create attribute " + name);
  const auto pointers = c_strings(texts);
  h5_check(H5Awrite(attribute, type, pointers.data()), "write attribute " + name);
}

void write_h5(const fs::path& file, const SweepPlan& plan, const std::deque<Column>& columns, std::size_t rows) {
  io::stop_hdf5_error_printing();  // each failure is reported by H5Id and h5_check
  H5Id h5(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "create " + file.string());
  write_text_attribute(h5, "format", {"needlefem-sweep-table"}, true);
  write_text_attribute(h5, "sweep_file", {plan.sweep_file.string()}, true);
  write_text_attribute(h5, "base_case", {plan.base_case.string()}, true);
  std::vector<std::string> names;
  for (const auto& c : columns) names.push_back(c.name);
  write_text_attribute(h5, "columns", names, false);

  const hsize_t size = rows;
  H5Id space(H5Screate_simple(1, &size, nullptr), H5Sclose, "create the row dataspace");
  for (const auto& c : columns) {
    const bool text = c.kind == Kind::text, number = c.kind == Kind::number;
    H5Id text_type = utf8_text_type();
    const hid_t file_type = text ? hid_t(text_type) : number ? H5T_IEEE_F64LE : H5T_STD_I8LE;
    H5Id dataset(H5Dcreate2(h5, c.name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
                 "create dataset " + c.name);
    herr_t status;
    if (text) status = H5Dwrite(dataset, text_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, c_strings(c.text).data());
    else if (number) status = H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.number.data());
    else status = H5Dwrite(dataset, H5T_NATIVE_INT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.flag.data());
    h5_check(status, "write dataset " + c.name);
  }
}

// Holds an exclusive flock on DIR/.sweep.lock while alive.
class TableLock {
 public:
  explicit TableLock(const fs::path& out_dir) : fd_(::open((out_dir / ".sweep.lock").c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0) throw std::runtime_error("cannot lock " + (out_dir / ".sweep.lock").string());
  }
  TableLock(const TableLock&) = delete;
  TableLock& operator=(const TableLock&) = delete;
  ~TableLock() { ::close(fd_); }

 private:
  int fd_;
};

fs::path partial_name(const fs::path& file) { return fmt::format("{}.partial.{}", file.string(), ::getpid()); }

}  // namespace

fs::path point_directory(const fs::path& out_dir, const DesignPoint& point) { return out_dir / point.name; }

PointRecord read_point(const DesignPoint& point, const fs::path& out_dir) {
  if (!point.valid()) return {"impossible", nullptr, joined_rules(point, true)};
  std::ifstream in(point_directory(out_dir, point) / "summary.json");
  if (!in) return {"pending", nullptr, ""};
  const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
  if (summary.is_discarded() || !summary.is_object() ||
      Case::with_current_choice_names(summary.value("case", nlohmann::json())) != point.resolved)
    return {"pending", nullptr, ""};
  const std::string status = summary.value("status", "");
  if (status == "completed") return {status, summary, ""};
  if (status == "running") return {"pending", nullptr, ""};  // its run was killed: run it again
  return {"failed", summary, summary.value("error", "no error message")};
}

void write_file_atomically(const fs::path& file, const std::string& text) {
  const fs::path partial = partial_name(file);
  {
    std::ofstream out(partial);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + partial.string());
  }
  fs::rename(partial, file);
}

void write_tables(const SweepPlan& plan, const fs::path& out_dir) {
  const TableLock lock(out_dir);
  const auto columns = table_columns(plan, out_dir);
  write_file_atomically(out_dir / "sweep.csv", csv_text(columns, plan.points.size()));
  const fs::path h5 = out_dir / "sweep.h5";
  write_h5(partial_name(h5), plan, columns, plan.points.size());
  fs::rename(partial_name(h5), h5);
}

}  // namespace needlefem::sweep
