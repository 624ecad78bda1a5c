// The calibrated profile: the base profile's text with each fitted key written in place of the
// base's own (in whatever unit the base wrote it), with its uncertainty and data in a comment;
// every other line, comment and key as the base has it; a header naming the machine, the date
// and the data.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <toml++/toml.h>

#include "ncjoule/calibrate_timing.hpp"
#include "ncjoule/profile.hpp"

namespace ncjoule {
namespace {

std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      if (start < text.size()) lines.emplace_back(text.substr(start));
      break;
    }
    lines.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

std::string trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return std::string(s);
}

// "[kinematics.x]  # comment" -> "kinematics.x"; empty for other lines (and [[arrays]]).
std::string header_of(const std::string& line) {
  const std::string t = trimmed(line);
  if (t.size() < 3 || t[0] != '[' || t[1] == '[') return {};
  const std::size_t close = t.find(']');
  if (close == std::string::npos) return {};
  std::string name;
  for (char c : t.substr(1, close - 1))
    if (c != ' ' && c != '"' && c != '\'') name += c;
  return name;
}

// The key a line sets ("accel_m_s2 = 2.5  # ..." -> "accel_m_s2"), empty when none.
std::string key_of(const std::string& line) {
  const std::string t = trimmed(line);
  if (t.empty() || t[0] == '#' || t[0] == '[') return {};
  const std::size_t eq = t.find('=');
  return eq == std::string::npos ? std::string() : trimmed(t.substr(0, eq));
}

std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// The names a quantity may be written under in a profile (docs/machine-profiles.md, Units).
std::vector<std::string> names_of(const TimingKeyInfo& info) {
  const std::string stem(info.stem);
  if (info.unit.empty()) return {stem};
  if (info.unit == "s_per_1000rpm")
    return {stem + "_s_per_1000rpm", stem + "_ms_per_1000rpm", stem + "_min_per_1000rpm"};
  std::vector<std::string_view> units;
  if (info.unit == "m_s2")
    units = {"mm_s2", "m_s2", "in_s2"};
  else if (info.unit == "mm_min")
    units = {"mm_min", "mm_s", "m_min", "in_min"};
  else
    units = {"s", "ms", "min"};
  std::vector<std::string> names;
  for (std::string_view u : units)
    names.push_back(stem + "_" + std::string(u));
  return names;
}

struct Editor {
  std::vector<std::string> lines;

  // [first, last) of a table's lines (its header excluded); nullopt when it has none.
  std::optional<std::pair<std::size_t, std::size_t>> span(const std::string& table) const {
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (header_of(lines[i]) == table) {
        std::size_t j = i + 1;
        while (j < lines.size() && header_of(lines[j]).empty() &&
               trimmed(lines[j]).rfind("[[", 0) != 0)
          ++j;
        return std::make_pair(i + 1, j);
      }
    return std::nullopt;
  }

  // Writes `line` for the key in place of any line that sets one of `names` in `table`.
  void set(const std::string& table, const std::vector<std::string>& names, const std::string& line,
           std::string* was) {
    auto s = span(table);
    if (!s) {
      // A table the base does not have: at the end, after the tables it belongs under.
      if (!lines.empty() && !trimmed(lines.back()).empty()) lines.push_back("");
      lines.push_back("[" + table + "]");
      lines.push_back(line);
      return;
    }
    std::optional<std::size_t> at;
    for (std::size_t i = s->first; i < s->second; ++i) {
      const std::string key = key_of(lines[i]);
      if (std::find(names.begin(), names.end(), key) == names.end()) continue;
      if (!at) {
        at = i;
        if (was) {
          std::string old = trimmed(lines[i]);
          if (const std::size_t hash = old.find('#'); hash != std::string::npos)
            old = trimmed(old.substr(0, hash));
          *was = old;
        }
        lines[i] = line;
      } else {
        lines.erase(lines.begin() + std::ptrdiff_t(i));
        --i;
        --s->second;
      }
    }
    if (at) return;
    // After the table's last key.
    std::size_t insert = s->first;
    for (std::size_t i = s->first; i < s->second; ++i)
      if (!key_of(lines[i]).empty()) insert = i + 1;
    lines.insert(lines.begin() + std::ptrdiff_t(insert), line);
  }

  std::string text() const {
    std::string out;
    for (const std::string& l : lines)
      out += l + "\n";
    return out;
  }
};

std::string number(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, v);
  std::string s = text;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0"; // a float in TOML
  return s;
}

} // namespace

std::optional<std::string> calibrated_profile_text(std::string_view base_toml,
                                                   const std::string& base_path,
                                                   const TimingFit& fit, const SpindleRunUp& run_up,
                                                   const CalibratedProfileInfo& info,
                                                   std::vector<Diagnostic>& diagnostics) {
  toml::table root;
  try {
    root = toml::parse(base_toml, base_path);
  } catch (const toml::parse_error& e) {
    diagnostics.push_back({Severity::Error, base_path, int(e.source().begin.line),
                           int(e.source().begin.column),
                           "not valid TOML: " + std::string(e.description())});
    return std::nullopt;
  }
  Editor editor{split_lines(base_toml)};
  for (const FittedTimingKey& f : fit.keys) {
    if (!f.fitted) continue;
    const TimingKeyInfo& key = timing_key_info(f.key);
    const std::string name =
        std::string(key.stem) + (key.unit.empty() ? "" : "_" + std::string(key.unit));
    const int digits = key.unit == "mm_min" ? 5 : 4;
    std::string comment = "# " + f.why;
    if (std::isfinite(f.std_error))
      comment += ", +- " + number(f.std_error * key.to_unit, 2) + " (1 SE)";
    std::string was;
    const std::string line = name + " = " + number(f.value * key.to_unit, digits);
    editor.set(std::string(key.table), names_of(key), line, &was);
    // The comment: the data and what the base had.
    auto s = editor.span(std::string(key.table));
    for (std::size_t i = s->first; i < s->second; ++i)
      if (editor.lines[i] == line) {
        editor.lines[i] += "  " + comment + (was.empty() ? "; not in the base" : "; base: " + was);
        break;
      }
  }
  if (fit.spindle_waits && *fit.spindle_waits)
    editor.set("kinematics", {"spindle_waits"},
               "spindle_waits = true  # fitted: the logged times hold a wait for the spindle at "
               "each speed change (spindle_ramp_s_per_1000rpm)",
               nullptr);
  // A measured run-up curve would replace the fitted wait's ramp: it is written only where the
  // path does not wait for the spindle (it then times the spindle's energy).
  const bool waits = fit.machine.kinematics.spindle_waits;
  if (!run_up.points.empty() && !waits) {
    std::string value = "spindle_run_up_rpm_s = [";
    for (std::size_t i = 0; i < run_up.points.size(); ++i)
      value += (i ? ", [" : "[") + number(run_up.points[i].first, 6) + ", " +
               number(run_up.points[i].second, 3) + "]";
    value += "]  # measured: the logged spindle speed of " + std::to_string(run_up.run_ups) +
             " run-ups from rest (medians)";
    editor.set("kinematics", {"spindle_run_up_rpm_s"}, value, nullptr);
  }
  // The machine, the date and the data, where a reader of the profile looks first.
  const std::string where = " from the MTConnect logs of " +
                            (info.machine.empty() ? std::string("the machine") : info.machine) +
                            " (ncjoule calibrate --timing, " + info.date + ")";
  auto top_value = [&](const char* key) {
    const auto v = root[key].value<std::string>();
    return v ? *v : std::string();
  };
  auto set_top = [&](const char* key, const std::string& value) {
    // Top-level keys sit before the first table.
    std::size_t end = 0;
    while (end < editor.lines.size() && header_of(editor.lines[end]).empty())
      ++end;
    const std::string line = std::string(key) + " = " + quoted(value);
    for (std::size_t i = 0; i < end; ++i)
      if (key_of(editor.lines[i]) == key) {
        editor.lines[i] = line;
        return;
      }
    editor.lines.insert(editor.lines.begin() + std::ptrdiff_t(end), line);
  };
  if (!info.name.empty()) set_top("name", info.name);
  set_top("summary", (top_value("summary").empty() ? top_value("name") : top_value("summary")) +
                         "; timing calibrated" + where);
  set_top("source", top_value("source") + "; timing keys fitted" + where);
  if (auto s = editor.span("kinematics")) {
    const auto* kin = root["kinematics"].as_table();
    const std::string old = kin && (*kin)["source"].value<std::string>()
                                ? *(*kin)["source"].value<std::string>()
                                : std::string();
    editor.set("kinematics", {"source"},
               "source = " +
                   quoted(old + (old.empty() ? "" : "; ") + "timing keys marked fitted" + where),
               nullptr);
  }
  std::string header = "# " + (info.name.empty() ? std::string("Machine profile") : info.name) +
                       ": calibrated by ncjoule calibrate --timing on " + info.date + " for " +
                       (info.machine.empty() ? std::string("the machine") : info.machine) +
                       " from its MTConnect logs, on the base profile " + base_path + ".\n";
  for (const std::string& d : info.data)
    header += "#   " + d + "\n";
  header += "# The fitted keys carry their uncertainty (1 standard error) and data in a comment; "
            "the keys the logs\n# could not tell are the base profile's:\n";
  for (const FittedTimingKey& f : fit.keys)
    if (!f.fitted) header += "#   " + timing_key_name(f.key) + ": " + f.why + "\n";
  if (!run_up.points.empty() && waits) {
    char text[160];
    std::snprintf(
        text, sizeof text,
        "# The logged spindle speed rises at %.0f rpm/s from rest (%zu run-ups); the path "
        "waits longer than that,\n# so the fitted ramp, not the run-up, is written.\n",
        run_up.rpm_per_s, run_up.run_ups);
    header += text;
  }
  header += "\n";
  std::string text = header + editor.text();
  try {
    (void)parse_profile(text, info.name.empty() ? base_path : info.name + ".toml");
  } catch (const ProfileError& e) {
    Diagnostic d = e.diagnostic();
    d.message = "the calibrated profile would not load: " + d.message;
    diagnostics.push_back(d);
    return std::nullopt;
  }
  return text;
}

} // namespace ncjoule
