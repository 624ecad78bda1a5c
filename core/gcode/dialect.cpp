// The controller dialects ncjoule knows, as data, and guessing one from a file.
#include <algorithm>
#include <cctype>

#include "ncjoule/gcode.hpp"

namespace ncjoule {
namespace {

std::vector<Dialect> make_dialects() {
  std::vector<Dialect> all;

  Dialect linuxcnc;
  linuxcnc.name = "linuxcnc";
  linuxcnc.o_word_subroutines = true;
  linuxcnc.retract_to_r_by_default = true; // rs274 starts in G99
  all.push_back(linuxcnc);

  Dialect fanuc;
  fanuc.name = "fanuc";
  fanuc.semicolon_comments = false; // ';' is the end-of-block character on Fanuc tapes
  fanuc.dwell_p_in_ms = true;       // G4 P is in milliseconds
  fanuc.dwell_x_word = true;        // G4 X is in seconds
  fanuc.fanuc_subprograms = true;
  fanuc.g65_macro_calls = true;
  fanuc.upper_case_comments = true;
  fanuc.max_line_length = 128;
  all.push_back(fanuc);

  Dialect haas = fanuc;
  haas.name = "haas";
  haas.dwell_p_in_ms = false;
  haas.dwell_p_integer_is_ms = true; // G4 P1000 = 1 s, G4 P1.0 = 1 s
  haas.haas_local_subprograms = true;
  all.push_back(haas);

  Dialect grbl;
  grbl.name = "grbl";
  grbl.dollar_lines = true;
  grbl.max_line_length = 256; // grbl's line buffer; longer lines overflow it
  all.push_back(grbl);

  Dialect mach3;
  mach3.name = "mach3";
  mach3.fanuc_subprograms = true; // Mach3/Mach4 support M98/M99 and o-numbers
  all.push_back(mach3);

  Dialect siemens;
  siemens.name = "siemens"; // Sinumerik in ISO mode (G291)
  siemens.paren_comments = true;
  siemens.dwell_x_word = true;
  siemens.fanuc_subprograms = true;
  siemens.comment_open = "(";
  siemens.upper_case_comments = true;
  all.push_back(siemens);
  return all;
}

const std::vector<Dialect>& dialects() {
  static const std::vector<Dialect> all = make_dialects();
  return all;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

} // namespace

std::optional<Dialect> find_dialect(std::string_view name) {
  const std::string n = lower(name);
  for (const Dialect& d : dialects())
    if (d.name == n) return d;
  if (n == "mach4") return find_dialect("mach3");
  if (n == "sinumerik") return find_dialect("siemens");
  return std::nullopt;
}

std::vector<std::string> dialect_names() {
  std::vector<std::string> names;
  for (const Dialect& d : dialects()) names.push_back(d.name);
  return names;
}

Dialect detect_dialect(const SourceFile& source) {
  // Look at the first few hundred lines only: posts put the tell-tale lines up front.
  int fanuc_votes = 0, haas_votes = 0, grbl_votes = 0, linuxcnc_votes = 0, mach_votes = 0;
  const std::size_t limit = std::min<std::size_t>(source.lines.size(), 400);
  for (std::size_t i = 0; i < limit; ++i) {
    std::string l = lower(source.line_text(i));
    const std::size_t first = l.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    l.erase(0, first);
    if (l[0] == '$') ++grbl_votes;
    if (l[0] == 'o' && l.size() > 1 && std::isdigit(static_cast<unsigned char>(l[1]))) {
      // An O-number alone (maybe with a comment) is a Fanuc program header; followed by a
      // keyword (sub, if, repeat, ...) it is a LinuxCNC O-word.
      std::size_t k = 1;
      while (k < l.size() && std::isdigit(static_cast<unsigned char>(l[k]))) ++k;
      while (k < l.size() && (l[k] == ' ' || l[k] == '\t')) ++k;
      if (k == l.size() || l[k] == '(' || l[k] == ';') ++fanuc_votes;
      else ++linuxcnc_votes;
    }
    if (l.rfind("o<", 0) == 0 || l.find("#<") != std::string::npos) ++linuxcnc_votes;
    if (l.find("m98") != std::string::npos || l.find("g65") != std::string::npos) ++fanuc_votes;
    if (l.find("g187") != std::string::npos || l.find("m97") != std::string::npos ||
        l.find("haas") != std::string::npos)
      ++haas_votes;
    if (l.find("mach3") != std::string::npos || l.find("mach4") != std::string::npos) ++mach_votes;
    if (l.find("grbl") != std::string::npos) ++grbl_votes;
    if (l.find("linuxcnc") != std::string::npos || l.find("emc2") != std::string::npos)
      ++linuxcnc_votes;
  }
  const char* name = "linuxcnc";
  if (linuxcnc_votes > 0) name = "linuxcnc";
  else if (haas_votes > 0) name = "haas";
  else if (grbl_votes > 0) name = "grbl";
  else if (mach_votes > 0) name = "mach3";
  else if (fanuc_votes > 0) name = "fanuc";
  return *find_dialect(name);
}

} // namespace ncjoule
