// The [power] section of a machine profile, written in the layout core/machine reads, with the
// source of each constant as a comment beside it; and a whole profile with a new section.
#include <cstdio>
#include <map>
#include <sstream>
#include <toml++/toml.h>

#include "ncjoule/calibrate.hpp"

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

std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

} // namespace

std::string power_section_toml(const PowerConstants& k,
                               const std::map<PowerParameter, std::string>& notes,
                               const std::string& source) {
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
  out << "co2_kg_per_kwh = " << number(k.co2_kg_per_kwh) << "\n";
  out << "price_per_kwh = " << number(k.price_per_kwh) << "\n";
  out << "currency = " << quoted(k.currency) << "\n";
  out << "\n[power.pavanaskar]\n" << source_line;
  for (PP p : {PP::Tare, PP::Coolant, PP::SpindleKA, PP::SpindleKB})
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
  return out.str();
}

std::optional<std::string> profile_with_power(std::string_view base_toml, const std::string& name,
                                              const PowerConstants& constants,
                                              const std::map<PowerParameter, std::string>& notes,
                                              const std::string& power_source, std::string& error) {
  toml::table root;
  if (!base_toml.empty()) {
    try {
      root = toml::parse(base_toml);
    } catch (const toml::parse_error& e) {
      std::ostringstream where;
      where << e.source().begin.line << ":" << e.source().begin.column << ": " << e.description();
      error = where.str();
      return std::nullopt;
    }
  }
  root.erase("power");
  if (!name.empty()) root.insert_or_assign("name", name);
  std::ostringstream out;
  // toml++ writes the top-level keys before any table, so the [power] tables can follow.
  out << toml::toml_formatter(root) << "\n\n" << power_section_toml(constants, notes, power_source);
  return out.str();
}

} // namespace ncjoule
