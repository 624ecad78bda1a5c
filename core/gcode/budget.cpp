// The one wording of every work budget's stop (budget.hpp).
#include "ncjoule/budget.hpp"

#include <cstdio>

namespace ncjoule {

std::string budget_message(const std::string& what, double limit, const std::string& option,
                           const std::string& key) {
  char count[64];
  std::snprintf(count, sizeof count, "%.0f", limit);
  return "stopped here: the program makes more than " + std::string(count) + " " + what +
         " (its budget of " + what + "). It may be a valid program a control would run: raise " +
         "the budget with --" + option + " N, or " + key + " = N in the user config";
}

} // namespace ncjoule
