#pragma once
// Strict reading of TOML tables: every key a table may hold is asked for by
// name; whatever is left over is an unknown key, reported with a "did you
// mean" when it is close to an allowed one. Errors name the file, line,
// column and key, and say what is allowed.
#include <cmath>
#include <initializer_list>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "darcydem/core/time_series.hpp"

namespace darcydem {

/// Predicates for TableReader::check.
inline bool is_positive(double v) { return v > 0.0 && std::isfinite(v); }
inline bool is_non_negative(double v) { return v >= 0.0 && std::isfinite(v); }

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Closest candidate within a small edit distance, or "".
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

class TableReader {
 public:
  /// `where` names the table for messages, e.g. "[[material]] #2".
  TableReader(const toml::table& table, std::string where, std::string file);

  [[nodiscard]] bool has(std::string_view key) const;
  /// Marks keys as allowed without reading them (alternatives).
  void allow(std::initializer_list<std::string_view> keys);

  double number(std::string_view key);  ///< required
  std::optional<double> optional_number(std::string_view key);
  double number_or(std::string_view key, double fallback);
  std::int64_t integer(std::string_view key);
  std::optional<std::int64_t> optional_integer(std::string_view key);
  bool boolean_or(std::string_view key, bool fallback);
  std::string string(std::string_view key);
  std::optional<std::string> optional_string(std::string_view key);
  /// A string that must be one of `allowed`.
  std::string choice(std::string_view key, const std::vector<std::string>& allowed);
  std::optional<std::string> optional_choice(std::string_view key, const std::vector<std::string>& allowed);
  /// An array of exactly n numbers.
  std::vector<double> numbers(std::string_view key, std::size_t n);
  std::optional<std::vector<double>> optional_numbers(std::string_view key, std::size_t n);
  /// An array of numbers of any length >= 1.
  std::vector<double> number_list(std::string_view key);
  std::vector<std::string> string_list(std::string_view key);
  const toml::table* optional_table(std::string_view key);
  /// The raw node (marked as used), or nullptr.
  const toml::node* raw(std::string_view key) { return get(key); }
  /// "file:line:column" of the table itself.
  [[nodiscard]] std::string here() const { return location(table_.source()); }
  const toml::array* optional_array(std::string_view key);

  /// Throws on any key that was not asked for.
  void finish() const;

  /// Error at a key (its line if present, else the table's).
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  /// A required key is absent (reports a near-miss key as a typo instead).
  [[noreturn]] void missing(std::string_view key, const std::string& what) const;
  /// Error about the table itself.
  [[noreturn]] void fail_table(const std::string& message) const;

  /// Checks a value with a predicate and a description of what is allowed.
  template <class Pred>
  double check(std::string_view key, double value, Pred&& ok, const std::string& allowed) const {
    if (!ok(value)) {
      fail(key, "must be " + allowed + ", got " + format_number(value));
    }
    return value;
  }

  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] const toml::table& table() const { return table_; }
  [[nodiscard]] const std::string& where() const { return where_; }
  [[nodiscard]] std::string location(const toml::source_region& s) const;
  static std::string format_number(double v);

 private:
  const toml::node* get(std::string_view key);
  const toml::table& table_;
  std::string where_;
  std::string file_;
  std::set<std::string, std::less<>> used_;
};

/// Parses a TOML file, turning syntax errors into SceneErrors.
toml::table parse_toml_file(const std::string& path, std::string& text_out);

/// A number, or a table { times = [...], values = [...] } (s from the start
/// of the stage, piecewise linear), at `key`; `unit` says what it is in the
/// messages.
TimeSeries read_time_series(TableReader& r, std::string_view key, const std::string& unit);

}  // namespace darcydem
