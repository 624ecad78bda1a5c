// Reading machine profiles (samples/machines/*.toml) into a MachineProfile.
//
// A profile that cannot be trusted is refused, never half-read: a missing key, a value of the
// wrong type, a key whose unit suffix is not one ncjoule knows, or an impossible value (negative
// acceleration, zero rapid rate) throws ProfileError naming the file, the key and the reason.
// Keys carry their unit in their name (rapid_mm_min, accel_mm_s2, tool_change_s); values are
// converted to internal units (mm, s, mm/s, mm/s^2, W) on load. docs/machine-profiles.md lists
// the keys.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/machine.hpp"

namespace ncjoule {

class ProfileError : public std::runtime_error {
public:
  ProfileError(std::string file, std::string key, std::string reason, int line = 0, int column = 0);
  const std::string& file() const { return file_; }
  // Dotted path of the offending key ("kinematics.x.accel_mm_s2"); empty for errors of the
  // whole file (unreadable, not TOML).
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }
  int line() const { return line_; }     // 1-based, 0 when the whole file is meant
  int column() const { return column_; } // 1-based, 0 when not known
  // The refusal as every reader reports a problem: file, line, column, severity, message.
  Diagnostic diagnostic() const;

private:
  std::string file_, key_, reason_;
  int line_ = 0, column_ = 0;
};

// Parses profile text; `path` is used in error messages and stored as source_path.
//
// A profile may start from another: `base = "haas-vf2"` (or "mill.toml") takes every value of
// that profile, found beside this one or else in `base_dirs` (the shipped profiles' folders),
// and this file's values replace its own key by key (a table's keys one by one, an array as a
// whole). A base may have its own base; a cycle is refused at the `base` line. Errors name the
// file that wrote the value; MachineProfile::values says which file gives each.
MachineProfile parse_profile(std::string_view text, const std::string& path,
                             const std::vector<std::string>& base_dirs = {});

// Reads and parses a profile file.
MachineProfile load_profile(const std::string& path,
                            const std::vector<std::string>& base_dirs = {});

} // namespace ncjoule
