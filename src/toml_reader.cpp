#include "darcydem/scene/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace darcydem {
namespace {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const std::size_t cost = (a[i - 1] == b[j - 1]) ? 0 : 1;
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + cost});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    default:
      return "a date/time";
  }
}

}  // namespace

std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

TableReader::TableReader(const toml::table& table, std::string where, std::string file)
    : table_(table), where_(std::move(where)), file_(std::move(file)) {}

std::string TableReader::location(const toml::source_region& s) const {
  // A value given on the command line (apply_scene_overrides) carries its
  // `--set PATH=VALUE` as its source.
  if (s.path && s.path->starts_with("--set ")) return *s.path;
  return fmt::format("{}:{}:{}", file_, s.begin.line, s.begin.column);
}

std::string TableReader::format_number(double v) { return fmt::format("{}", v); }

void TableReader::fail(std::string_view key, const std::string& message) const {
  const toml::node* n = table_.get(key);
  const auto& src = n != nullptr ? n->source() : table_.source();
  throw SceneError(fmt::format("{}: error: {} key '{}': {}", location(src), where_, key, message));
}

void TableReader::fail_table(const std::string& message) const {
  throw SceneError(fmt::format("{}: error: {}: {}", location(table_.source()), where_, message));
}

bool TableReader::has(std::string_view key) const { return table_.contains(key); }

void TableReader::allow(std::initializer_list<std::string_view> keys) {
  for (auto k : keys) used_.emplace(k);
}

const toml::node* TableReader::get(std::string_view key) {
  used_.emplace(key);
  return table_.get(key);
}

std::optional<double> TableReader::optional_number(std::string_view key) {
  const toml::node* n = get(key);
  if (n == nullptr) return std::nullopt;
  if (auto v = n->value<double>(); v && (n->is_floating_point() || n->is_integer())) {
    // TOML has nan and inf; no key of a scene means either.
    if (!std::isfinite(*v)) fail(key, "must be a finite number, got " + format_number(*v));
    return *v;
  }
  fail(key, "must be a number, got " + type_name(*n));
}

void TableReader::missing(std::string_view key, const std::string& what) const {
  // A near-miss key is more likely a typo than an omission: report that.
  for (const auto& [k, v] : table_) {
    if (used_.count(k.str()) == 0 && did_you_mean(k.str(), {std::string(key)}) == key) {
      throw SceneError(
          fmt::format("{}: error: {} has unknown key '{}'. Did you mean '{}'? ('{}' is required: {})",
                      location(v.source()), where_, k.str(), key, key, what));
    }
  }
  fail_table(fmt::format("missing required key '{}' ({})", key, what));
}

double TableReader::number(std::string_view key) {
  auto v = optional_number(key);
  if (!v) missing(key, "a number");
  return *v;
}

double TableReader::number_or(std::string_view key, double fallback) {
  return optional_number(key).value_or(fallback);
}

std::optional<std::int64_t> TableReader::optional_integer(std::string_view key) {
  const toml::node* n = get(key);
  if (n == nullptr) return std::nullopt;
  if (!n->is_integer()) fail(key, "must be an integer, got " + type_name(*n));
  return n->value<std::int64_t>();
}

std::int64_t TableReader::integer(std::string_view key) {
  auto v = optional_integer(key);
  if (!v) missing(key, "an integer");
  return *v;
}

bool TableReader::boolean_or(std::string_view key, bool fallback) {
  const toml::node* n = get(key);
  if (n == nullptr) return fallback;
  if (!n->is_boolean()) fail(key, "must be true or false, got " + type_name(*n));
  return *n->value<bool>();
}

std::optional<std::string> TableReader::optional_string(std::string_view key) {
  const toml::node* n = get(key);
  if (n == nullptr) return std::nullopt;
  if (!n->is_string()) fail(key, "must be a string, got " + type_name(*n));
  return *n->value<std::string>();
}

std::string TableReader::string(std::string_view key) {
  auto v = optional_string(key);
  if (!v) missing(key, "a string");
  return *v;
}

std::optional<std::string> TableReader::optional_choice(std::string_view key,
                                                        const std::vector<std::string>& allowed) {
  auto v = optional_string(key);
  if (!v) return v;
  if (std::find(allowed.begin(), allowed.end(), *v) == allowed.end()) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
    std::string hint;
    if (auto s = did_you_mean(*v, allowed); !s.empty()) hint = fmt::format(" (did you mean \"{}\"?)", s);
    fail(key, fmt::format("\"{}\" is not allowed; one of {}{}", *v, list, hint));
  }
  return v;
}

std::string TableReader::choice(std::string_view key, const std::vector<std::string>& allowed) {
  auto v = optional_choice(key, allowed);
  if (!v) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
    missing(key, "one of " + list);
  }
  return *v;
}

std::optional<std::vector<double>> TableReader::optional_numbers(std::string_view key, std::size_t n) {
  const toml::node* node = get(key);
  if (node == nullptr) return std::nullopt;
  const toml::array* a = node->as_array();
  if (a == nullptr || a->size() != n) {
    fail(key, fmt::format("must be an array of {} numbers", n));
  }
  std::vector<double> out;
  for (const auto& e : *a) {
    auto v = e.value<double>();
    if (!v) fail(key, fmt::format("must be an array of {} numbers", n));
    if (!std::isfinite(*v)) {
      fail(key, fmt::format("must be an array of {} finite numbers, got {} at element {}", n,
                            format_number(*v), out.size() + 1));
    }
    out.push_back(*v);
  }
  return out;
}

std::vector<double> TableReader::numbers(std::string_view key, std::size_t n) {
  auto v = optional_numbers(key, n);
  if (!v) missing(key, fmt::format("an array of {} numbers", n));
  return *v;
}

std::vector<double> TableReader::number_list(std::string_view key) {
  const toml::node* node = get(key);
  if (node == nullptr) missing(key, "an array of numbers");
  const toml::array* a = node->as_array();
  if (a == nullptr || a->empty()) fail(key, "must be a non-empty array of numbers");
  std::vector<double> out;
  for (const auto& e : *a) {
    auto v = e.value<double>();
    if (!v) fail(key, "must be a non-empty array of numbers");
    if (!std::isfinite(*v)) {
      fail(key, fmt::format("must be an array of finite numbers, got {} at element {}", format_number(*v),
                            out.size() + 1));
    }
    out.push_back(*v);
  }
  return out;
}

std::vector<std::string> TableReader::string_list(std::string_view key) {
  const toml::node* node = get(key);
  if (node == nullptr) missing(key, "an array of strings");
  const toml::array* a = node->as_array();
  if (a == nullptr) fail(key, "must be an array of strings");
  std::vector<std::string> out;
  for (const auto& e : *a) {
    auto v = e.value<std::string>();
    if (!v) fail(key, "must be an array of strings");
    out.push_back(*v);
  }
  return out;
}

const toml::table* TableReader::optional_table(std::string_view key) {
  const toml::node* n = get(key);
  if (n == nullptr) return nullptr;
  if (!n->is_table()) fail(key, "must be a table, got " + type_name(*n));
  return n->as_table();
}

const toml::array* TableReader::optional_array(std::string_view key) {
  const toml::node* n = get(key);
  if (n == nullptr) return nullptr;
  if (!n->is_array()) fail(key, "must be an array, got " + type_name(*n));
  return n->as_array();
}

void TableReader::finish() const {
  std::vector<std::string> allowed(used_.begin(), used_.end());
  for (const auto& [k, v] : table_) {
    if (used_.count(k.str()) != 0) continue;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    std::string hint;
    if (auto s = did_you_mean(k.str(), allowed); !s.empty()) hint = fmt::format(" Did you mean '{}'?", s);
    throw SceneError(fmt::format("{}: error: {} has unknown key '{}'.{} Allowed keys: {}.",
                                 location(v.source()), where_, k.str(), hint, list));
  }
}

toml::table parse_toml_file(const std::string& path, std::string& text_out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(fmt::format("{}: error: cannot open the scene file", path));
  std::stringstream ss;
  ss << in.rdbuf();
  text_out = ss.str();
  try {
    return toml::parse(text_out, path);
  } catch (const toml::parse_error& e) {
    throw SceneError(fmt::format("{}:{}:{}: error: TOML syntax: {}", path, e.source().begin.line,
                                 e.source().begin.column, e.description()));
  }
}

/// A number, or a table { times = [...], values = [...] } (s from the start
/// of the stage, piecewise linear).
TimeSeries read_time_series(TableReader& r, std::string_view key, const std::string& unit) {
  const toml::node* n = r.raw(key);
  if (n == nullptr) r.fail_table(fmt::format("missing required key '{}' ({})", key, unit));
  // A number as the reader takes one (finite, or refused at the key).
  if (n->is_floating_point() || n->is_integer()) return TimeSeries::constant(r.number(key));
  const toml::table* t = n->as_table();
  if (t == nullptr) {
    r.fail(key, fmt::format("must be a number ({}) or a table {{ times = [...], values = [...] }}", unit));
  }
  TableReader tr(*t, fmt::format("{} {}", r.where(), key), r.file());
  TimeSeries s;
  s.times = tr.number_list("times");
  s.values = tr.number_list("values");
  if (s.values.size() != s.times.size()) tr.fail("values", "must have as many entries as 'times'");
  for (std::size_t i = 0; i < s.times.size(); ++i) {
    if (!(s.times[i] >= 0.0)) tr.fail("times", "must be >= 0 s (counted from the start of the stage)");
    if (i > 0 && !(s.times[i] > s.times[i - 1])) tr.fail("times", "must increase strictly");
  }
  tr.finish();
  return s;
}

}  // namespace darcydem
