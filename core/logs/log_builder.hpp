// Internal: turning one logged value into an observation, the same way for both forms.
#pragma once

#include <string_view>
#include <vector>

#include "item_resolver.hpp"

namespace ncjoule::logs_detail {

struct ValueProblems {
  std::size_t not_numbers = 0; // a numeric item's value that is not a number (skipped)
  int first_line = 0;
  std::string first_item;
};

// Adds the observation of `value` for a resolved item (nothing when it maps to no signal).
void add_observation(ControllerLog& log, const ItemResolver& resolver, const ResolvedItem& item,
                     std::uint16_t file, std::uint16_t device, double t_s, std::string_view value,
                     std::uint32_t line, std::string_view key, ValueProblems& problems);

// The diagnostic for a file's values that were not numbers, when there were any.
void report_value_problems(const ValueProblems& problems, const std::string& path,
                           std::vector<Diagnostic>& diagnostics);

} // namespace ncjoule::logs_detail
