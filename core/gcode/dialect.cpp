// The controller dialects ncjoule knows, as data, and guessing one from a file.
#include <algorithm>
#include <array>
#include <cctype>

#include "ncjoule/gcode.hpp"
#include "ncjoule/text.hpp"

namespace ncjoule {
namespace {

std::vector<Dialect> make_dialects() {
  std::vector<Dialect> all;

  Dialect linuxcnc;
  linuxcnc.name = "linuxcnc";
  linuxcnc.o_word_subroutines = true;
  linuxcnc.retract_to_r_by_default = true; // rs274 starts in G99
  linuxcnc.percent_alone = true;
  all.push_back(linuxcnc);

  Dialect fanuc;
  fanuc.name = "fanuc";
  fanuc.semicolon_comments = false; // ';' is the end-of-block character on Fanuc tapes
  fanuc.dwell_p_in_ms = true;       // G4 P is in milliseconds
  fanuc.dwell_x_word = true;        // G4 X is in seconds
  fanuc.fanuc_subprograms = true;
  fanuc.g65_macro_calls = true;
  fanuc.upper_case_comments = true;
  // No figure holds for the whole family (each control's manual states its own): 128, kept
  // short (docs/annotation.md lists every dialect's limit and where it comes from).
  fanuc.max_line_length = 128;
  fanuc.canned_cycle_group = true;
  fanuc.last_code_of_group_wins = true;
  // The builders' M codes differ; a rotary table's clamp and unclamp (M10/M11) is what Fanuc-
  // controlled mills with a 4th axis share, and what CAM posts for them write around every index.
  fanuc.machine_m_codes = {10, 11};
  // G73's back-off and G83's clearance are parameters 5114 and 5115, set by the machine's
  // builder (Fanuc Operator's Manual, "High-speed peck drilling cycle (G73)", "Peck drilling
  // cycle (G83)"): no family default; rs274ngc's 0.010 in until a profile gives the machine's.
  all.push_back(fanuc);

  Dialect haas = fanuc;
  haas.name = "haas";
  haas.dwell_p_in_ms = false;
  haas.dwell_p_integer_is_ms = true; // G4 P1000 = 1 s, G4 P1.0 = 1 s
  haas.haas_local_subprograms = true;
  // Setting 22, Can Cycle Delta Z: G73's back-off and the height above the last peck G83
  // rapids back down to; 0.050 in as shipped (Haas Mill Operator's Manual, Settings).
  haas.peck_clearance_mm = 0.05 * 25.4;
  haas.chip_break_retract_mm = 0.05 * 25.4;
  // Haas mill M codes (Haas Mill Operator's Manual, M-codes chapter) that move no axis ncjoule
  // times: 4th/5th-axis brakes (M10-M13), user and relay outputs (M21-M28, M51-M59, M61-M69),
  // chip auger (M31, M33), coolant spigot (M34, M35), gear ranges (M41, M42), pallet and part
  // checks (M36, M46, M48, M50), probe-skip alarms (M78, M79), doors (M80, M81), tool unclamp
  // and clamp (M82, M86), air blast (M83, M84), through-spindle coolant (M88, M89), sleep (M95),
  // input jumps and prompts (M96, M109). Their pumps and motors are not in the power models.
  haas.machine_m_codes = {10, 11, 12, 13, 21, 22, 23, 24, 25, 26, 27, 28, 31, 33,
                          34, 35, 36, 41, 42, 46, 48, 50, 51, 52, 53, 54, 55, 56,
                          57, 58, 59, 61, 62, 63, 64, 65, 66, 67, 68, 69, 75, 76,
                          77, 78, 79, 80, 81, 82, 83, 84, 86, 88, 89, 95, 96, 109};
  all.push_back(haas);

  Dialect grbl;
  grbl.name = "grbl";
  grbl.dollar_lines = true;
  // Senders stream to grbl by counting characters into its 128-byte serial receive buffer
  // (serial.h RX_BUFFER_SIZE); grbl's own stream.py sends a line only while the bytes in flight
  // stay under 127, so a line longer than 125 bytes (126 with its newline, 127 with CR LF) is
  // never sent.
  grbl.max_line_length = 125;
  all.push_back(grbl);

  Dialect mach3;
  mach3.name = "mach3";
  mach3.fanuc_subprograms = true; // Mach3/Mach4 support M98/M99 and o-numbers
  mach3.canned_cycle_group = true;
  mach3.last_code_of_group_wins = true;
  mach3.zero_radius_circle_is_no_motion = true;
  all.push_back(mach3);

  Dialect siemens;
  siemens.name = "siemens"; // Sinumerik in ISO mode (G291)
  siemens.paren_comments = true;
  siemens.dwell_x_word = true;
  siemens.fanuc_subprograms = true;
  // Sinumerik's comments are ';' to the end of the line; "( )" is a call's argument list
  // (CYCLE81(...), COS (0), MSG("...")), never a comment to write.
  siemens.comment_open = ";";
  siemens.comment_close = "";
  siemens.upper_case_comments = true;
  siemens.paren_argument_lists = true; // CYCLE81(...), MSG("...")
  siemens.sinumerik_words = true;
  siemens.g70_g71_units = true; // G70/G700 inch, G71/G710 mm
  siemens.canned_cycle_group = true;
  siemens.last_code_of_group_wins = true;
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
  // Marlin reads "( )" as code unless built with PAREN_COMMENTS (off by default): its words
  // would be parameters (E= an extrusion). ';' comments are dropped as they are read.
  reprap.comment_open = ";";
  reprap.comment_close = "";
  // Marlin keeps a line's code in a 96-byte buffer (MAX_CMD_SIZE, with its terminating zero)
  // and skips what comes past it: lines of 95 bytes stay whole whatever reads them.
  reprap.max_line_length = 95;
  // Marlin's motors on and off (M17, M18, M84), finish moves (M400), message (M117), fan (M106,
  // M107), report position (M114), feed and flow overrides (M220, M221): no motion of their own.
  reprap.machine_m_codes = {17, 18, 84, 106, 107, 114, 117, 220, 221, 400};
  reprap.end_code_optional = true;
  reprap.lenient_words = true;
  all.push_back(reprap);
  return all;
}

const std::vector<Dialect>& dialects() {
  static const std::vector<Dialect> all = make_dialects();
  return all;
}

// ncjoule's own annotations ("(NCJ ... CK=XXXXXX)", "; NCJ ...") name the dialect they were
// written for: they must not tell it again. Expects lower case.
std::string without_annotations(std::string line) {
  for (std::size_t at; (at = line.find("(ncj ")) != std::string::npos;) {
    const std::size_t close = line.find(')', at);
    line.erase(at, close == std::string::npos ? std::string::npos : close - at + 1);
  }
  for (const char* marker : {";ncj ", "; ncj "})
    if (const std::size_t at = line.find(marker); at != std::string::npos) line.erase(at);
  return line;
}

// Whether `line` (lower case) holds the word `code` ("m31") not followed by a digit or '.'
// (M310, M31.5 are other codes) nor preceded by a letter (a word inside a name).
bool has_code(const std::string& line, const char* code) {
  const std::size_t n = std::char_traits<char>::length(code);
  for (std::size_t at = line.find(code); at != std::string::npos; at = line.find(code, at + 1)) {
    const bool letter_before = at > 0 && std::isalpha(static_cast<unsigned char>(line[at - 1]));
    const bool digit_after =
        at + n < line.size() &&
        (std::isdigit(static_cast<unsigned char>(line[at + n])) || line[at + n] == '.');
    if (!letter_before && !digit_after) return true;
  }
  return false;
}

} // namespace

std::optional<Dialect> find_dialect(std::string_view name) {
  const std::string n = to_lower(name);
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

DialectChoice choose_dialect(const SourceFile& source) {
  // Look at the first few hundred lines only: posts put the tell-tale lines up front. Names in
  // the header comments (FreeCAD writes "Post Processor: ...grbl_post", other CAM systems the
  // machine or control) count as much as syntax. The first clue for each dialect is kept to
  // say why it was chosen.
  enum Family { LinuxCnc, Siemens, Heidenhain, Haas, Grbl, RepRap, Mach, Fanuc, kFamilies };
  static constexpr const char* kNames[kFamilies] = {"linuxcnc", "siemens", "heidenhain", "haas",
                                                    "grbl",     "reprap",  "mach3",      "fanuc"};
  std::array<std::string, kFamilies> clue;
  const std::size_t limit = std::min<std::size_t>(source.lines.size(), 400);
  auto has = [](const std::string& l, const char* what) {
    return l.find(what) != std::string::npos;
  };
  for (std::size_t i = 0; i < limit; ++i) {
    std::string l = without_annotations(to_lower(source.line_text(i)));
    const std::size_t first = l.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    l.erase(0, first);
    const std::string at = " at line " + std::to_string(i + 1);
    auto vote = [&](Family f, const std::string& what) {
      if (clue[f].empty()) clue[f] = what + at;
    };
    if (l[0] == '$') vote(Grbl, "'$' settings line");
    if (l[0] == 'o' && l.size() > 1 && std::isdigit(static_cast<unsigned char>(l[1]))) {
      // An O-number alone (maybe with a comment) is a Fanuc program header; followed by a
      // keyword (sub, if, repeat, ...) it is a LinuxCNC O-word.
      std::size_t k = 1;
      while (k < l.size() && std::isdigit(static_cast<unsigned char>(l[k])))
        ++k;
      while (k < l.size() && (l[k] == ' ' || l[k] == '\t'))
        ++k;
      if (k == l.size() || l[k] == '(' || l[k] == ';')
        vote(Fanuc, "O-number program header");
      else
        vote(LinuxCnc, "O-word with a keyword");
    }
    if (l.rfind("o<", 0) == 0) vote(LinuxCnc, "named O-word");
    if (has(l, "#<")) vote(LinuxCnc, "named parameter");
    if (has(l, "m98")) vote(Fanuc, "M98 subprogram call");
    if (has(l, "g65")) vote(Fanuc, "G65 macro call");
    if (has(l, "fanuc")) vote(Fanuc, "'fanuc' in the text");
    if (has(l, "g187")) vote(Haas, "G187");
    if (has(l, "m97")) vote(Haas, "M97 local subprogram call");
    // Chip auger and through-spindle coolant: Haas's own M codes, which its posts write.
    for (const char* code : {"m31", "m33", "m88", "m89"})
      if (has_code(l, code)) vote(Haas, "Haas code " + to_upper(code));
    if (has(l, "haas")) vote(Haas, "'haas' in the text");
    if (has(l, "mach3") || has(l, "mach4")) vote(Mach, "'mach3/mach4' in the text");
    if (has(l, "uccnc")) vote(Mach, "'uccnc' in the text");
    if (has(l, "grbl") || has(l, "jtech")) vote(Grbl, "'grbl' in the text"); // J Tech lasers
    if (has(l, "linuxcnc") || has(l, "emc2")) vote(LinuxCnc, "'linuxcnc' in the text");
    if (has(l, "pathpilot") || has(l, "tormach")) vote(LinuxCnc, "'tormach' in the text");
    if (has(l, "mcall")) vote(Siemens, "MCALL");
    if (has(l, "cycle8")) vote(Siemens, "CYCLE8x call");
    if (has(l, "sinumerik") || has(l, "siemens")) vote(Siemens, "'sinumerik' in the text");
    if (l.rfind("trans ", 0) == 0) vote(Siemens, "TRANS frame");
    if (has(l, "g291") || has(l, "g290")) vote(Siemens, "G290/G291");
    // Heidenhain ISO: "%NAME G71 *" headers, blocks ending in '*'.
    if (l[0] == '%' && (has(l, "g70") || has(l, "g71"))) vote(Heidenhain, "'%NAME G71' header");
    if (has(l, "heidenhain")) vote(Heidenhain, "'heidenhain' in the text");
    if (l.size() > 1 && l.back() == '*' && l[0] == 'n') vote(Heidenhain, "block ending in '*'");
    if (has(l, "marlin") || has(l, "rrf_post") || has(l, "reprap") || has(l, "smoothie"))
      vote(RepRap, "'marlin/reprap' in the text");
  }
  // The first family in this order with a clue wins: the more specific before the more general.
  for (int f = 0; f < kFamilies; ++f)
    if (!clue[f].empty()) return {*find_dialect(kNames[f]), DialectOrigin::Detected, clue[f]};
  return {*find_dialect("linuxcnc"), DialectOrigin::Default, "nothing in the program names one"};
}

Dialect detect_dialect(const SourceFile& source) {
  return choose_dialect(source).dialect;
}

std::string describe_dialect_choice(const DialectChoice& choice) {
  switch (choice.origin) {
  case DialectOrigin::Given:
    return choice.dialect.name + " (given)";
  case DialectOrigin::Detected:
    return choice.dialect.name + " (detected: " + choice.reason + ")";
  case DialectOrigin::Default:
    break;
  }
  return choice.dialect.name + " (default: " + choice.reason + ")";
}

} // namespace ncjoule
