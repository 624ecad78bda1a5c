// The [power] section of a machine profile, written in the layout core/machine reads, with the
// source of each constant as a comment beside it; and a whole profile with a new section.
#include <cstdio>
#include <map>
#include <sstream>
#include <toml++/toml.h>

#include "ncjoule/calibrate.hpp"
#include "ncjoule/profile.hpp"

namespace ncjoule {
namespace {

using PP = PowerParameter;

std::string number(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.10g", v);
  std::string s = text;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0"; // a float must look like one
  return s;
}

// A TOML basic string: quotes and backslashes escaped, and control characters too (\u001B), which
// TOML does not allow raw (a file name holding ESC would make a profile that does not load).
std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if ((byte < 0x20 && c != '\t') || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04X", unsigned(byte));
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// Keys of the base profile's [power] tables that fitting does not produce (cutting_term,
// material, spindle_rated_w, the fitted ranges, [power.profile_material], ...), as TOML lines
// for the section they belong to: a calibrated profile keeps them.
struct KeptPowerKeys {
  std::string power;  // lines for [power]
  std::string zhou;   // lines for [power.zhou]
  std::string tables; // whole [power.*] tables other than pavanaskar and zhou
};

std::string toml_lines(const toml::table& t) {
  if (t.empty()) return "";
  std::ostringstream out;
  out << toml::toml_formatter(t) << "\n";
  return out.str();
}

KeptPowerKeys kept_power_keys(const toml::table* power) {
  KeptPowerKeys kept;
  if (!power) return kept;
  toml::table top, zhou, tables;
  for (const auto& [key, node] : *power) {
    const std::string k(key.str());
    // Quantities may carry their unit in the key (tool_change_w, c1_kw): all spellings go.
    if (k == "source" || k == "model" || k.rfind("tool_change", 0) == 0 || k == "cutting_term" ||
        k == "co2_kg_per_kwh" || k == "price_per_kwh" || k == "machine_rate_per_hour" ||
        k == "currency" || k == "pavanaskar")
      continue;
    if (k == "zhou") {
      if (const auto* z = node.as_table())
        for (const auto& [zkey, znode] : *z) {
          const std::string zk(zkey.str());
          const bool written = zk == "source" || zk.rfind("fitted_", 0) == 0 ||
                               (zk.size() >= 2 && (zk[0] == 'c' || zk[0] == 'd') && zk[1] >= '1' &&
                                zk[1] <= '4' && (zk.size() == 2 || zk[2] == '_'));
          if (!written) zhou.insert_or_assign(zkey, znode);
        }
      continue;
    }
    if (node.is_table())
      tables.insert_or_assign(key, node);
    else
      top.insert_or_assign(key, node);
  }
  kept.power = toml_lines(top);
  kept.zhou = toml_lines(zhou);
  if (!tables.empty()) {
    toml::table wrapped;
    wrapped.insert_or_assign("power", tables);
    kept.tables = "\n" + toml_lines(wrapped);
  }
  return kept;
}

std::string power_section_toml(const PowerConstants& k,
                               const std::map<PowerParameter, std::string>& notes,
                               const std::string& source, const KeptPowerKeys& kept) {
  std::ostringstream out;
  auto line = [&](PP p) {
    const std::string key(parameter_info(p).key);
    out << key.substr(key.rfind('.') + 1) << " = " << number(get_parameter(k, p)) << "  # "
        << parameter_info(p).unit;
    if (auto it = notes.find(p); it != notes.end()) out << "; " << it->second;
    out << "\n";
  };
  // The loader asks every section for its source.
  const std::string source_line =
      "source = " + quoted(source.empty() ? "not given" : source) + "\n";
  out << "[power]\n" << source_line;
  out << "model = " << quoted(model_name(k.model)) << "  # combined | pavanaskar | zhou\n";
  line(PP::ToolChange);
  // Pavanaskar's model cuts with its own per-axis lines: a cutting term kept from a combined base
  // profile would make the written profile one the loader refuses.
  if (k.model != PowerModel::Pavanaskar)
    out << "cutting_term = "
        << quoted(k.cutting_term == CuttingTerm::Material ? "material" : "fitted")
        << "  # fitted: c3, c4 of [power.zhou]; material: the workpiece's k_c\n";
  out << "co2_kg_per_kwh = " << number(k.co2_kg_per_kwh) << "\n";
  out << "price_per_kwh = " << number(k.price_per_kwh) << "\n";
  if (k.machine_rate_per_hour > 0)
    out << "machine_rate_per_hour = " << number(k.machine_rate_per_hour) << "\n";
  out << "currency = " << quoted(k.currency) << "\n";
  out << kept.power;
  out << "\n[power.pavanaskar]\n" << source_line;
  for (PP p : {PP::Tare, PP::Coolant, PP::SpindleKA, PP::SpindleKB, PP::SpindleKC})
    line(p);
  const char* axes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    out << "\n[power.pavanaskar." << axes[i] << "]\n";
    for (PP first : {PP::MoveKAX, PP::MoveKBX, PP::CutKAX, PP::CutKBX})
      line(static_cast<PP>(static_cast<int>(first) + i));
  }
  out << "\n[power.zhou]\n" << source_line;
  for (PP p : {PP::ZhouC1, PP::ZhouC2, PP::ZhouC3, PP::ZhouC4, PP::ZhouD1, PP::ZhouD2, PP::ZhouD3,
               PP::ZhouD4})
    line(p);
  const ZhouConstants& z = k.zhou;
  if (z.fitted_rpm_max > 0) {
    out << "fitted_rpm_min = " << number(z.fitted_rpm_min) << "  # rpm, the fit's data\n";
    out << "fitted_rpm_max = " << number(z.fitted_rpm_max) << "  # rpm\n";
    out << "fitted_mrr_min_mm3_s = " << number(z.fitted_mrr_min_mm3_s) << "\n";
    out << "fitted_mrr_max_mm3_s = " << number(z.fitted_mrr_max_mm3_s) << "\n";
  }
  out << kept.zhou << kept.tables;
  return out.str();
}

} // namespace

std::string power_section_toml(const PowerConstants& k,
                               const std::map<PowerParameter, std::string>& notes,
                               const std::string& source) {
  return power_section_toml(k, notes, source, KeptPowerKeys{});
}

std::optional<std::string> profile_with_power(std::string_view base_toml,
                                              const std::string& base_path, const std::string& name,
                                              const PowerConstants& constants,
                                              const std::map<PowerParameter, std::string>& notes,
                                              const std::string& power_source,
                                              std::vector<Diagnostic>& diagnostics) {
  toml::table root;
  if (!base_toml.empty()) {
    try {
      root = toml::parse(base_toml, base_path);
    } catch (const toml::parse_error& e) {
      diagnostics.push_back({Severity::Error, base_path, int(e.source().begin.line),
                             int(e.source().begin.column),
                             "not valid TOML: " + std::string(e.description())});
      return std::nullopt;
    }
  }
  const KeptPowerKeys kept = kept_power_keys(root["power"].as_table());
  root.erase("power");
  if (!name.empty()) root.insert_or_assign("name", name);
  std::ostringstream out;
  // toml++ writes the top-level keys before any table, so the [power] tables can follow.
  out << toml::toml_formatter(root) << "\n\n"
      << power_section_toml(constants, notes, power_source, kept);
  // Made from a base profile, what is handed back must load: a profile ncjoule would refuse is
  // worse than none. Without a base it is the [power] tables alone, for a profile to take in.
  if (base_toml.empty()) return out.str();
  try {
    (void)parse_profile(out.str(), name.empty() ? base_path : name + ".toml");
  } catch (const ProfileError& e) {
    Diagnostic d = e.diagnostic();
    d.message = "the fitted profile would not load: " + d.message;
    diagnostics.push_back(d);
    return std::nullopt;
  }
  return out.str();
}

} // namespace ncjoule
