#include "table_reader.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "ncjoule/profile.hpp"

namespace ncjoule::profile_detail {
namespace {

std::string unit_list(std::string_view stem, Dimension dimension) {
  std::string list;
  for (const UnitSuffix& u : units_of(dimension)) {
    if (!list.empty()) list += ", ";
    list += std::string(stem) + "_" + std::string(u.suffix);
  }
  return list;
}

const char* type_name(const toml::node& node) {
  switch (node.type()) {
  case toml::node_type::string:
    return "a string";
  case toml::node_type::integer:
    return "an integer";
  case toml::node_type::floating_point:
    return "a number";
  case toml::node_type::boolean:
    return "a boolean";
  case toml::node_type::table:
    return "a table";
  case toml::node_type::array:
    return "an array";
  default:
    return "a date or time";
  }
}

} // namespace

TableReader::TableReader(const toml::table& table, std::string file, std::string prefix,
                         std::map<std::string, ProfileValue>* values)
    : table_(table), file_(std::move(file)), prefix_(std::move(prefix)), values_(values) {}

// The file a node was read from: a value a base profile gives is that profile's, not the file
// the reader was opened on.
std::string TableReader::file_of(const toml::node* node) const {
  if (node && node->source().path && !node->source().path->empty()) return *node->source().path;
  return file_;
}

std::string TableReader::path_of(std::string_view key) const {
  return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
}

void TableReader::fail(std::string_view key, const std::string& reason) const {
  // Where: the key's value, else the table that lacks it.
  const toml::node* node = table_.get(key);
  const toml::source_position where = node ? node->source().begin : table_.source().begin;
  throw ProfileError(file_of(node ? node : &table_), path_of(key), reason, int(where.line),
                     int(where.column));
}

const toml::node* TableReader::find(std::string_view key) {
  const toml::node* node = table_.get(key);
  if (!node) return nullptr;
  read_.insert(std::string(key));
  if (values_ && !node->is_table()) {
    std::ostringstream text;
    node->visit([&](const auto& value) { text << value; });
    (*values_)[path_of(key)] = {file_of(node), text.str(), int(node->source().begin.line)};
  }
  return node;
}

double TableReader::checked(std::string_view key, const toml::node& node, double factor,
                            Range range) {
  std::optional<double> value;
  if (const auto* i = node.as_integer()) value = static_cast<double>(i->get());
  if (const auto* f = node.as_floating_point()) value = f->get();
  if (!value) fail(key, std::string("expected a number, found ") + type_name(node));
  if (!std::isfinite(*value)) fail(key, "must be a finite number");
  // No quantity of a machine comes near this; 1e308 s of tool change is a slip, not a machine.
  if (std::abs(*value) > 1e12) fail(key, "is out of any plausible range (above 1e12)");
  if (range == Range::Positive && !(*value > 0)) fail(key, "must be greater than zero");
  if (range == Range::NonNegative && *value < 0) fail(key, "must not be negative");
  return *value * factor;
}

namespace {

// A limit as the user reads it: %g, without an exponent below a million.
std::string limit_text(double value) {
  char text[64];
  std::snprintf(text, sizeof text,
                std::abs(value) >= 1e-4 && std::abs(value) < 1e7 ? "%.10g" : "%g", value);
  return text;
}

} // namespace

void TableReader::check_plausible(std::string_view key, double value, double factor,
                                  Dimension dimension, Range range) const {
  if (value == 0) return;
  const Plausible p = plausible(dimension);
  const double magnitude = std::abs(value);
  const bool negative_allowed = range == Range::Any && p.most_negative > 0;
  if (magnitude >= p.smallest && ((value > 0 && value <= p.largest) ||
                                  (value < 0 && negative_allowed && magnitude <= p.most_negative)))
    return;
  std::string allowed =
      "from " + limit_text(p.smallest / factor) + " to " + limit_text(p.largest / factor);
  if (negative_allowed)
    allowed = "from " + limit_text(-p.most_negative / factor) + " to " +
              limit_text(p.largest / factor) + " (or 0)";
  else if (range != Range::Positive)
    allowed += " (or 0)";
  fail(key, limit_text(value / factor) + " is no machine's " + p.what + ": give one " + allowed +
                " in the key's unit (a slip of units or of typing?)");
}

void TableReader::check_between(std::string_view key, double value, double lowest,
                                double highest) const {
  if (value >= lowest && value <= highest) return;
  fail(key, limit_text(value) + " is outside what it can physically be: give one from " +
                limit_text(lowest) + " to " + limit_text(highest));
}

std::optional<double> TableReader::optional_quantity(std::string_view stem, Dimension dimension,
                                                     Range range) {
  stems_.emplace(std::string(stem), dimension);
  std::optional<double> result;
  std::string found_key;
  for (const UnitSuffix& u : units_of(dimension)) {
    const std::string key = std::string(stem) + "_" + std::string(u.suffix);
    const toml::node* node = find(key);
    if (!node) continue;
    if (result) fail(key, "given twice, also as '" + path_of(found_key) + "'");
    result = checked(key, *node, u.to_internal, range);
    check_plausible(key, *result, u.to_internal, dimension, range);
    found_key = key;
  }
  return result;
}

double TableReader::quantity(std::string_view stem, Dimension dimension, Range range) {
  std::optional<double> value = optional_quantity(stem, dimension, range);
  if (!value) {
    // Written with a unit ncjoule does not know? Name that key rather than a missing one.
    for (const auto& [key, node] : table_)
      if (key.str().starts_with(std::string(stem) + "_"))
        fail(key.str(), "unknown unit for '" + std::string(stem) + "': write it as one of " +
                            unit_list(stem, dimension));
    const std::string first =
        std::string(stem) + "_" + std::string(units_of(dimension).front().suffix);
    fail(first, "missing (write it as one of " + unit_list(stem, dimension) + ")");
  }
  return *value;
}

double TableReader::number(std::string_view key, Range range, double lowest, double highest) {
  const toml::node* node = find(key);
  if (!node) fail(key, "missing");
  const double value = checked(key, *node, 1.0, range);
  if (!(range != Range::Positive && value == 0)) check_between(key, value, lowest, highest);
  return value;
}

std::optional<double> TableReader::optional_number(std::string_view key, Range range, double lowest,
                                                   double highest) {
  const toml::node* node = find(key);
  if (!node) return std::nullopt;
  const double value = checked(key, *node, 1.0, range);
  if (!(range != Range::Positive && value == 0)) check_between(key, value, lowest, highest);
  return value;
}

std::optional<std::string> TableReader::optional_string(std::string_view key) {
  if (!find(key)) return std::nullopt;
  return string(key);
}

std::string TableReader::string(std::string_view key) {
  const toml::node* node = find(key);
  if (!node) fail(key, "missing");
  const auto* s = node->as_string();
  if (!s) fail(key, std::string("expected a string, found ") + type_name(*node));
  return s->get();
}

bool TableReader::boolean(std::string_view key) {
  const toml::node* node = find(key);
  if (!node) fail(key, "missing");
  const auto* b = node->as_boolean();
  if (!b) fail(key, std::string("expected true or false, found ") + type_name(*node));
  return b->get();
}

std::optional<bool> TableReader::optional_boolean(std::string_view key) {
  if (!find(key)) return std::nullopt;
  return boolean(key);
}

std::string TableReader::choice(std::string_view key,
                                std::initializer_list<std::string_view> words) {
  std::string value = string(key);
  std::string list;
  for (std::string_view w : words) {
    if (w == value) return value;
    if (!list.empty()) list += ", ";
    list += "\"" + std::string(w) + "\"";
  }
  fail(key, "\"" + value + "\" is not one of " + list);
}

TableReader TableReader::table(std::string_view key) {
  std::optional<TableReader> t = optional_table(key);
  if (!t) fail(key, "missing table [" + path_of(key) + "]");
  return *t;
}

std::optional<TableReader> TableReader::optional_table(std::string_view key) {
  const toml::node* node = find(key);
  if (!node) return std::nullopt;
  const auto* t = node->as_table();
  if (!t) fail(key, std::string("expected a table, found ") + type_name(*node));
  return TableReader(*t, file_, path_of(key), values_);
}

void TableReader::finish() const {
  for (const auto& [key, node] : table_) {
    if (read_.count(key.str())) continue;
    std::string reason = "unknown key";
    for (const auto& [stem, dimension] : stems_) {
      if (key.str().starts_with(stem + "_")) {
        reason =
            "unknown unit for '" + stem + "': write it as one of " + unit_list(stem, dimension);
        break;
      }
    }
    throw ProfileError(file_of(&node), path_of(key.str()), reason, int(node.source().begin.line),
                       int(node.source().begin.column));
  }
}

} // namespace ncjoule::profile_detail
