// The controller dialects ncjoule knows, as data, and telling one from a file's code.
#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <string_view>
#include <vector>

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
  // G15/G16 polar coordinate command (Fanuc Series 16/18 Operator's Manual, 9.2).
  fanuc.polar_g16 = true;
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
  // G16 polar mode about the point where G16 was read (Mach3's "G16 polar origin").
  mach3.polar_g16 = true;
  mach3.polar_pole_at_g16 = true;
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
  siemens.polar_g16 = true; // ISO mode's G15/G16, as Fanuc
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

// A line split as dialect detection reads it: its code, and the text of its comments ("( )" and
// ';' to the end of the line; the Fanuc family's ';' ends the block, and what follows it is no
// code either). Lower case. A Sinumerik call's argument list reads as a comment here: its name
// stays in the code, which is what the clues look at.
struct SplitLine {
  std::string code;
  std::vector<std::string> comments;
};

SplitLine split_line(const std::string& line) {
  SplitLine out;
  std::size_t i = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == ';') {
      out.comments.push_back(line.substr(i + 1));
      break;
    }
    if (c == '(') {
      const std::size_t close = line.find(')', i + 1);
      out.comments.push_back(
          line.substr(i + 1, close == std::string::npos ? std::string::npos : close - i - 1));
      if (close == std::string::npos) break;
      out.code += ' ';
      i = close + 1;
      continue;
    }
    out.code += c;
    ++i;
  }
  return out;
}

// Whether `code` (lower case) holds the word `word` ("m31", "g65") not followed by a digit or
// '.' (M310, M31.5 are other codes) nor preceded by a letter (a word inside a name).
bool has_code(const std::string& code, std::string_view word) {
  for (std::size_t at = code.find(word); at != std::string::npos; at = code.find(word, at + 1)) {
    const bool letter_before = at > 0 && std::isalpha(static_cast<unsigned char>(code[at - 1]));
    const std::size_t after = at + word.size();
    const bool digit_after =
        after < code.size() &&
        (std::isdigit(static_cast<unsigned char>(code[after])) || code[after] == '.');
    if (!letter_before && !digit_after) return true;
  }
  return false;
}

// Whether `code` holds `word` as a word of its own (not inside a longer name).
bool has_word(const std::string& code, std::string_view word) {
  for (std::size_t at = code.find(word); at != std::string::npos; at = code.find(word, at + 1)) {
    const std::size_t after = at + word.size();
    const bool before_ok = at == 0 || !std::isalnum(static_cast<unsigned char>(code[at - 1]));
    const bool after_ok =
        after >= code.size() || !std::isalnum(static_cast<unsigned char>(code[after]));
    if (before_ok && after_ok) return true;
  }
  return false;
}

// Whether a comment is a post processor's statement about itself: "(Post Processor:
// PathScripts.post.grbl_post)", "(Created with grbl post processor ...)", "; Posts processor:
// MPCNC.cps", "(Mach3 post)", "(G-code generated for UCCNC controller ...)". Only such a
// statement names the control a program was written for; a customer's, a part's or a machine's
// name in another comment ("CUSTOMER: SIEMENS AG", "HOLES FOR THE HAAS TRUNNION") does not.
bool is_post_signature(const std::string& comment) {
  for (std::string_view phrase :
       {"post processor", "postprocessor", "post-processor", "posts processor", "post processed",
        "post-processed", "post:", "post name"})
    if (comment.find(phrase) != std::string::npos) return true;
  if (comment.find("generated for") != std::string::npos &&
      comment.find("control") != std::string::npos)
    return true;
  // "(Mach3 post)": a short comment that ends with the word "post".
  std::vector<std::string_view> words;
  std::string_view rest = comment;
  while (!rest.empty()) {
    const std::size_t begin = rest.find_first_not_of(" \t");
    if (begin == std::string_view::npos) break;
    rest.remove_prefix(begin);
    const std::size_t end = std::min(rest.find_first_of(" \t"), rest.size());
    words.push_back(rest.substr(0, end));
    rest.remove_prefix(end);
  }
  return !words.empty() && words.size() <= 3 && words.back() == "post";
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
  // Look at the first few hundred lines only: posts put the tell-tale lines up front. The dialect
  // is decided by the code (words and codes only some families have, a program header's form,
  // grbl's '$' lines, Heidenhain's '*' block ends) and by the post processor's signature in the
  // header's comments, never by other free text in comments: a customer's or a machine's name
  // is no clue. The first clue for each dialect is kept to say why it was chosen.
  enum Family { LinuxCnc, Siemens, Heidenhain, Haas, Grbl, RepRap, Mach, Fanuc, kFamilies };
  static constexpr const char* kNames[kFamilies] = {"linuxcnc", "siemens", "heidenhain", "haas",
                                                    "grbl",     "reprap",  "mach3",      "fanuc"};
  std::array<std::string, kFamilies> clue;
  const std::size_t limit = std::min<std::size_t>(source.lines.size(), 400);
  // The header: the lines before the first that moves an axis, where a post describes itself.
  bool in_header = true;
  // Fusion's posts describe the machine they post for in a block of their own ("(Machine)",
  // "(  vendor: HAAS)", "(  model: ...)"): the vendor line there is the post's statement too.
  std::size_t machine_block = 0; // lines left in such a block
  for (std::size_t i = 0; i < limit; ++i) {
    const SplitLine split = split_line(to_lower(source.line_text(i)));
    std::string l = split.code;
    const std::size_t first = l.find_first_not_of(" \t");
    const std::size_t last = l.find_last_not_of(" \t\r");
    l = first == std::string::npos ? std::string() : l.substr(first, last - first + 1);
    const std::string at = " at line " + std::to_string(i + 1);
    auto vote = [&](Family f, const std::string& what) {
      if (clue[f].empty()) clue[f] = what + at;
    };
    if (in_header) {
      for (const std::string& comment : split.comments) {
        const std::string_view text = trim(comment);
        if (text == "machine") {
          machine_block = 4;
          continue;
        }
        const bool vendor = machine_block > 0 && text.rfind("vendor", 0) == 0;
        // ncjoule's own header names the dialect it was written for: it does not tell it again.
        if (comment.rfind("ncj ", 0) == 0 || (!vendor && !is_post_signature(comment))) continue;
        auto named = [&](std::initializer_list<const char*> words) {
          for (const char* w : words)
            if (comment.find(w) != std::string::npos) return true;
          return false;
        };
        const std::string signature =
            vendor ? "the post's machine block" : "the post processor's signature";
        if (named({"fanuc"})) vote(Fanuc, "'fanuc' in " + signature);
        if (named({"haas"})) vote(Haas, "'haas' in " + signature);
        if (named({"mach3", "mach4", "uccnc", "uc-cnc"})) vote(Mach, "'mach3' in " + signature);
        if (named({"grbl", "jtech"})) vote(Grbl, "'grbl' in " + signature); // J Tech lasers
        if (named({"linuxcnc", "emc2", "pathpilot", "tormach"}))
          vote(LinuxCnc, "'linuxcnc' in " + signature);
        if (named({"sinumerik", "siemens"})) vote(Siemens, "'sinumerik' in " + signature);
        if (named({"heidenhain"})) vote(Heidenhain, "'heidenhain' in " + signature);
        if (named({"marlin", "rrf_post", "reprap", "smoothie"}))
          vote(RepRap, "'marlin' in " + signature);
      }
    }
    if (machine_block > 0) --machine_block;
    if (l.empty()) continue;
    if (l[0] == '$') vote(Grbl, "'$' settings line");
    if (l[0] == 'o' && l.size() > 1 && std::isdigit(static_cast<unsigned char>(l[1]))) {
      // An O-number alone (maybe with a comment) is a Fanuc program header; followed by a
      // keyword (sub, if, repeat, ...) it is a LinuxCNC O-word.
      std::size_t k = 1;
      while (k < l.size() && std::isdigit(static_cast<unsigned char>(l[k])))
        ++k;
      while (k < l.size() && (l[k] == ' ' || l[k] == '\t'))
        ++k;
      if (k == l.size())
        vote(Fanuc, "O-number program header");
      else
        vote(LinuxCnc, "O-word with a keyword");
    }
    if (l.rfind("o<", 0) == 0) vote(LinuxCnc, "named O-word");
    if (l.find("#<") != std::string::npos) vote(LinuxCnc, "named parameter");
    if (has_code(l, "m98")) vote(Fanuc, "M98 subprogram call");
    if (has_code(l, "g65")) vote(Fanuc, "G65 macro call");
    if (has_code(l, "g187")) vote(Haas, "G187");
    if (has_code(l, "m97")) vote(Haas, "M97 local subprogram call");
    // Chip auger and through-spindle coolant: Haas's own M codes, which its posts write.
    for (const char* code : {"m31", "m33", "m88", "m89"})
      if (has_code(l, code)) vote(Haas, "Haas code " + to_upper(code));
    if (l.find("mcall") != std::string::npos) vote(Siemens, "MCALL");
    // Sinumerik's own language: declarations, subprogram definitions, inch feeds (G700/G710),
    // the machine-coordinate word SUPA.
    for (const char* word : {"extern ", "def ", "proc "})
      if (l.rfind(word, 0) == 0) vote(Siemens, to_upper(std::string(word, std::strlen(word) - 1)));
    if (has_code(l, "g700") || has_code(l, "g710")) vote(Siemens, "G700/G710");
    if (has_word(l, "supa")) vote(Siemens, "SUPA");
    if (l.find("cycle8") != std::string::npos) vote(Siemens, "CYCLE8x call");
    if (l.rfind("trans ", 0) == 0) vote(Siemens, "TRANS frame");
    if (has_code(l, "g291") || has_code(l, "g290")) vote(Siemens, "G290/G291");
    // Heidenhain ISO: "%NAME G71 *" headers, blocks ending in '*'.
    if (l[0] == '%' && (has_code(l, "g70") || has_code(l, "g71")))
      vote(Heidenhain, "'%NAME G71' header");
    if (l.size() > 1 && l.back() == '*' && l[0] == 'n') vote(Heidenhain, "block ending in '*'");
    // The header ends where the program starts moving.
    for (char axis : {'x', 'y', 'z'})
      if (l.find(axis) != std::string::npos) in_header = false;
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
