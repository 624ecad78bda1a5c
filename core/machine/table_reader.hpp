// Reads one TOML table of a profile strictly: every value read is checked for presence, type,
// unit and range, and keys nobody read are reported (a misspelt key or an unknown unit would
// otherwise be silently ignored and a default used instead).
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <toml++/toml.h>

#include "ncjoule/machine.hpp"
#include "units.hpp"

namespace ncjoule::profile_detail {

enum class Range {
  Positive,    // > 0 (rates, accelerations)
  NonNegative, // >= 0 (times, powers, "0 = none" values)
  Any,
};

class TableReader {
public:
  // `values`, when given, receives every value read: its dotted key, its file and its text.
  TableReader(const toml::table& table, std::string file, std::string prefix,
              std::map<std::string, ProfileValue>* values = nullptr);

  // <stem>_<unit> for one unit of the dimension, converted to internal units.
  double quantity(std::string_view stem, Dimension dimension, Range range);
  std::optional<double> optional_quantity(std::string_view stem, Dimension dimension, Range range);
  // A number whose unit is implied by the model it belongs to (Zhou's c3, c4, d1..d4), within
  // [lowest, highest] where given (what the thing it stands for can physically be).
  double number(std::string_view key, Range range, double lowest = -1e12, double highest = 1e12);
  std::optional<double> optional_number(std::string_view key, Range range, double lowest = -1e12,
                                        double highest = 1e12);
  std::string string(std::string_view key);
  std::optional<std::string> optional_string(std::string_view key);
  bool boolean(std::string_view key);
  std::optional<bool> optional_boolean(std::string_view key);
  // One of the given words (case-sensitive); the error lists them.
  std::string choice(std::string_view key, std::initializer_list<std::string_view> words);

  // The value itself (marked as read), for shapes the readers above do not cover; null when
  // missing.
  const toml::node* raw(std::string_view key) { return find(key); }
  TableReader table(std::string_view key);
  std::optional<TableReader> optional_table(std::string_view key);

  // Throws for the first key that was never read.
  void finish() const;

  [[noreturn]] void fail(std::string_view key, const std::string& reason) const;
  std::string path_of(std::string_view key) const;

private:
  const toml::node* find(std::string_view key);
  std::string file_of(const toml::node* node) const;
  double checked(std::string_view key, const toml::node& node, double factor, Range range);
  // Fails unless `value` (in internal units, from a key written in units of `factor`) is in
  // the dimension's physical range.
  void check_plausible(std::string_view key, double value, double factor, Dimension dimension,
                       Range range) const;
  void check_between(std::string_view key, double value, double lowest, double highest) const;

  const toml::table& table_;
  std::string file_;
  std::string prefix_;
  std::set<std::string, std::less<>> read_;
  std::map<std::string, Dimension, std::less<>> stems_; // for hints on unknown keys
  std::map<std::string, ProfileValue>* values_ = nullptr;
};

} // namespace ncjoule::profile_detail
