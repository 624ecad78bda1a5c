// Planner diagnostics, with repeats folded: a program with a million moves at F0 should give a
// handful of warnings and a count, not a million lines.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::kinematics_detail {

class Warnings {
public:
  // `kind` groups repeats of one problem; line is 0-based, as in CanonCommand.
  void add(const std::string& kind, int line, std::string message,
           Severity severity = Severity::Warning) {
    int& seen = seen_[kind];
    if (++seen > kKeepPerKind) return;
    list_.push_back(Diagnostic{severity, "", line + 1, 0, std::move(message)});
  }

  // For a problem of the whole program (a limit the profile lacks): said once, at its first line.
  void add_once(const std::string& kind, int line, std::string message) {
    if (once_.insert(kind).second)
      list_.push_back(Diagnostic{Severity::Warning, "", line + 1, 0, std::move(message)});
  }

  // Said once, at its first line, with how many blocks it concerns in all (added when the
  // whole program is planned).
  void add_counted(const std::string& kind, int line, std::string message,
                   Severity severity = Severity::Note) {
    Counted& c = counted_[kind];
    if (c.count++ == 0) c.diagnostic = Diagnostic{severity, "", line + 1, 0, std::move(message)};
  }

  std::vector<Diagnostic> take() {
    for (auto& [kind, c] : counted_) {
      if (c.count > 1) c.diagnostic.message += " (" + std::to_string(c.count) + " blocks in all)";
      list_.push_back(std::move(c.diagnostic));
    }
    counted_.clear();
    for (const auto& [kind, seen] : seen_)
      if (seen > kKeepPerKind)
        list_.push_back(Diagnostic{Severity::Note, "", 0, 0,
                                   std::to_string(seen - kKeepPerKind) + " more warnings like \"" +
                                       kind + "\" not shown"});
    return std::move(list_);
  }

private:
  static constexpr int kKeepPerKind = 10;
  std::map<std::string, int> seen_;
  std::set<std::string> once_;
  struct Counted {
    std::size_t count = 0;
    Diagnostic diagnostic;
  };
  std::map<std::string, Counted> counted_;
  std::vector<Diagnostic> list_;
};

} // namespace ncjoule::kinematics_detail
