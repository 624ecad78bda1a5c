// Work budgets: bounds on how much work one run may do (moves the program expands to:
// InterpreterLimits::max_commands; path samples the planner makes and columns the removal engine
// visits: EstimateOptions). A program that passes one is not wrong: a control would run it, for
// days perhaps. The run stops where the budget ran out, writes nothing, and says which budget,
// where, and how to raise it; the command line ends with its own exit status (5), not the one of
// a program the control rejects (2).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "ncjoule/diagnostic.hpp"

namespace ncjoule {

// The defaults: over 100 times the moves and path samples the largest corpus programs need, 3x
// their removal work (README, "Limits"); each stops a runaway within seconds of one core.
inline constexpr std::size_t kDefaultMaxMoves = 20'000'000;
inline constexpr std::size_t kDefaultMaxPathSamples = 100'000'000;
inline constexpr double kDefaultMaxColumnVisits = 2e10;

// Thrown in the estimate's stream to end the run (estimate/work_budget.hpp); the estimate catches
// it and reports `diagnostic`.
struct BudgetExceeded : std::runtime_error {
  explicit BudgetExceeded(Diagnostic d) : std::runtime_error(d.message), diagnostic(std::move(d)) {}
  Diagnostic diagnostic;
};

// "stopped here: the program makes more than LIMIT WHAT (its budget of WHAT). ... raise the
// budget with --OPTION N, or KEY = N in the user config".
std::string budget_message(const std::string& what, double limit, const std::string& option,
                           const std::string& key);

} // namespace ncjoule
