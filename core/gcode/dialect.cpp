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
  siemens.paren_argument_lists = true; // CYCLE81(...), MSG("...")
  siemens.sinumerik_words = true;
  siemens.g70_g71_units = true; // G70/G700 inch, G71/G710 mm
  all.push_back(siemens);

  Dialect heidenhain;
  heidenhain.name = "heidenhain";    // TNC controls programmed in DIN/ISO
  heidenhain.paren_comments = false; // ';' starts a comment
  heidenhain.star_block_end = true;
  heidenhain.arc_centre_absolute = true;
  heidenhain.g70_g71_units = true;
  heidenhain.dwell_x_word = false;
  heidenhain.comment_open = ";";
  heidenhain.comment_close = "";
  all.push_back(heidenhain);

  // Marlin, RepRapFirmware and Smoothieware (FreeCAD's marlin, rrf, smoothie posts): G4 P is
  // in milliseconds, G4 S in seconds.
  Dialect reprap;
  reprap.name = "reprap";
  reprap.dwell_p_in_ms = true;
  reprap.dwell_s_word = true;
  all.push_back(reprap);
  return all;
}

const std::vector<Dialect>& dialects() {
  static const std::vector<Dialect> all = make_dialects();
  return all;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

} // namespace

std::optional<Dialect> find_dialect(std::string_view name) {
  const std::string n = lower(name);
  for (const Dialect& d : dialects())
    if (d.name == n) return d;
  if (n == "mach4") return find_dialect("mach3");
  if (n == "sinumerik") return find_dialect("siemens");
  if (n == "marlin" || n == "rrf" || n == "reprapfirmware" || n == "smoothie")
    return find_dialect("reprap");
  if (n == "tnc") return find_dialect("heidenhain");
  return std::nullopt;
}

std::vector<std::string> dialect_names() {
  std::vector<std::string> names;
  for (const Dialect& d : dialects())
    names.push_back(d.name);
  return names;
}

Dialect detect_dialect(const SourceFile& source) {
  // Look at the first few hundred lines only: posts put the tell-tale lines up front. Names in
  // the header comments (FreeCAD writes "Post Processor: ...grbl_post", other CAM systems the
  // machine or control) count as much as syntax.
  int fanuc_votes = 0, haas_votes = 0, grbl_votes = 0, linuxcnc_votes = 0, mach_votes = 0;
  int siemens_votes = 0, heidenhain_votes = 0, reprap_votes = 0;
  const std::size_t limit = std::min<std::size_t>(source.lines.size(), 400);
  auto has = [](const std::string& l, const char* what) {
    return l.find(what) != std::string::npos;
  };
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
      while (k < l.size() && std::isdigit(static_cast<unsigned char>(l[k])))
        ++k;
      while (k < l.size() && (l[k] == ' ' || l[k] == '\t'))
        ++k;
      if (k == l.size() || l[k] == '(' || l[k] == ';')
        ++fanuc_votes;
      else
        ++linuxcnc_votes;
    }
    if (l.rfind("o<", 0) == 0 || has(l, "#<")) ++linuxcnc_votes;
    if (has(l, "m98") || has(l, "g65") || has(l, "fanuc")) ++fanuc_votes;
    if (has(l, "g187") || has(l, "m97") || has(l, "haas")) ++haas_votes;
    if (has(l, "mach3") || has(l, "mach4") || has(l, "uccnc")) ++mach_votes;
    if (has(l, "grbl") || has(l, "jtech")) ++grbl_votes; // J Tech lasers run grbl
    if (has(l, "linuxcnc") || has(l, "emc2") || has(l, "pathpilot") || has(l, "tormach"))
      ++linuxcnc_votes;
    if (has(l, "mcall") || has(l, "cycle8") || has(l, "sinumerik") || has(l, "siemens") ||
        l.rfind("trans ", 0) == 0 || has(l, "g291") || has(l, "g290"))
      ++siemens_votes;
    // Heidenhain ISO: "%NAME G71 *" headers, blocks ending in '*'.
    if ((l[0] == '%' && (has(l, "g70") || has(l, "g71"))) || has(l, "heidenhain") ||
        (l.size() > 1 && l.back() == '*' && l[0] == 'n'))
      ++heidenhain_votes;
    if (has(l, "marlin") || has(l, "rrf_post") || has(l, "reprap") || has(l, "smoothie"))
      ++reprap_votes;
  }
  const char* name = "linuxcnc";
  if (linuxcnc_votes > 0)
    name = "linuxcnc";
  else if (siemens_votes > 0)
    name = "siemens";
  else if (heidenhain_votes > 0)
    name = "heidenhain";
  else if (haas_votes > 0)
    name = "haas";
  else if (grbl_votes > 0)
    name = "grbl";
  else if (reprap_votes > 0)
    name = "reprap";
  else if (mach_votes > 0)
    name = "mach3";
  else if (fanuc_votes > 0)
    name = "fanuc";
  return *find_dialect(name);
}

} // namespace ncjoule
