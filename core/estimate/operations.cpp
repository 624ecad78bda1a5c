#include "operations.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "ncjoule/text.hpp"

namespace ncjoule::estimate_detail {
namespace {

// How far from a tool change its name is looked for, so that a file without comments costs no
// more than a few lines per tool change.
constexpr int kNameSearchLines = 40;

bool starts_with(const std::string& s, std::string_view prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

// A comment that describes a tool: a tool list entry ("T1 D=6. CR=0. - ...", "T3 : 3.0",
// "T1 = .5 ENDMILL", "T1 | 1/2 FLAT ENDMILL | ..."), Mastercam's "TOOL - 1 DIA. ...", FreeCAD's
// tool controller "TC: 6mm Endmill".
bool describes_tool(const std::string& l) {
  if (l.size() > 1 && l[0] == 't' && std::isdigit(static_cast<unsigned char>(l[1]))) {
    std::size_t i = 1;
    while (i < l.size() && std::isdigit(static_cast<unsigned char>(l[i])))
      ++i;
    while (i < l.size() && l[i] == ' ')
      ++i;
    if (i == l.size() || l[i] == ':' || l[i] == '=' || l[i] == '|' || l[i] == '-' ||
        l.find("d=") != std::string::npos)
      return true;
  }
  return starts_with(l, "tool") || starts_with(l, "tc:") || starts_with(l, "tc :");
}

// Commented-out code: every word a letter and a number ("G00 Z3", "M08", "X10. Y20.").
bool is_code(std::string_view text) {
  bool any = false;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && text[i] == ' ')
      ++i;
    if (i >= text.size()) break;
    if (!std::isalpha(static_cast<unsigned char>(text[i]))) return false;
    ++i;
    const std::size_t digits = i;
    if (i < text.size() && (text[i] == '-' || text[i] == '+')) ++i;
    while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.'))
      ++i;
    if (i == digits || (i < text.size() && text[i] != ' ')) return false;
    any = true;
  }
  return any;
}

// A commented-out O-word (LinuxCNC "o<probe> call", "o100 sub", Fanuc-style "O100 IF"): a call
// or a control word taken out of the program, no operation's name.
bool is_o_word(std::string_view text) {
  const std::string l = to_lower(trim(text));
  if (l.size() < 2 || l[0] != 'o') return false;
  std::size_t i = 1;
  if (l[i] == '<') {
    i = l.find('>', i);
    if (i == std::string::npos) return false;
    ++i;
  } else {
    while (i < l.size() && std::isdigit(static_cast<unsigned char>(l[i])))
      ++i;
    if (i == 1) return false;
  }
  const std::string_view rest = trim(std::string_view(l).substr(i));
  for (const char* word : {"call", "sub", "endsub", "return", "if", "elseif", "else", "endif",
                           "while", "endwhile", "do", "repeat", "endrepeat", "break", "continue"})
    if (rest.substr(0, rest.find(' ')) == word) return true;
  return false;
}

// Notes posts write between operations, which name none.
bool is_note(const std::string& l) {
  static const char* const kNotes[] = {
      "finish operation", "end operation", "end of operation", "machine units", "coolant",
      "begin preamble", "begin postamble", "preamble", "postamble", "output time", "exported by",
      "post processor", "tool change", "program end", "end of program", "end program", "retract",
      "rapid", "spindle", "return to", "safe", "home", "stop", "pause", "units", "wcs",
      "work offset", "date", "time:", "material", "machine:", "stock", "cam file", "project file",
      "file:",
      // Fanuc posts between operations, machine resets.
      "end of previous operation", "intermediate cleanup", "reset offsets", "cancel",
      // Fusion's personal-use notice, line by line.
      "when using fusion", "moves is reduced", "which can increase", "are available with",
      "rapid moves is reduced", "moves, which can", "moves are available", "using high feed",
      // Licences, debug output and custom-code markers.
      "without warranties", "licensed under", "copyright", "movement_", "pycam_",
      "start custom gcode", "end custom gcode", "curr:", "part zero",
      "command_", // a Fusion post's command constants, printed by its debug mode
      "x min", "x max", "y min", "y max", "z min", "z max", // extents
      "map:",                                               // a generator's dump of its settings
      // FreeCAD's block mode and toolchange markers, section markers.
      "block-expand", "block-enable", "path:", "begin toolchange", "post_amble", "pre_amble",
      "section end",
      // NX posts' comments on each move and event of a path (the events of Post Builder).
      "linear move", "circular move", "helical move", "engage move", "approach move",
      "departure move", "return move", "initial move", "first move", "gohome move", "from move",
      "start of path", "end of path", "cutcom"};
  for (const char* note : kNotes)
    if (starts_with(l, note)) return true;
  return false;
}

// Marks posts draw lines and frames with.
bool is_rule_mark(char c) {
  return c == '-' || c == '=' || c == '*' || c == '_' || c == '#' || c == '~' || c == '+' ||
         c == ' ';
}

// "OP 2", "OPERATION 3", "SEQ 10": a number, not what the operation does.
bool is_bare_number(const std::string& l) {
  for (std::string_view word : {"operation", "op.", "op", "sequence", "seq"}) {
    if (!starts_with(l, word)) continue;
    std::size_t i = word.size();
    while (i < l.size() && (l[i] == ' ' || l[i] == '#' || l[i] == '.' || l[i] == ':'))
      ++i;
    const std::size_t digits = i;
    while (i < l.size() && std::isdigit(static_cast<unsigned char>(l[i])))
      ++i;
    if (i > digits && i == l.size()) return true;
  }
  return false;
}

// Generators' own markers and debug output: a setting ("path_direction = x", "Map: Allow Rapid
// Z = true"), a condition ("xy != p_xy && z > 0: ..."), a section's bounds ("SECTION begin",
// "CHANGE TOOL begin"), a section header ("[Process]") or a list's heading.
bool is_marker(std::string_view text, const std::string& lower) {
  if (lower.find("!=") != std::string::npos || lower.find("&&") != std::string::npos ||
      lower.find("==") != std::string::npos)
    return true;
  auto ends_with = [&](std::string_view end) {
    return lower.size() > end.size() &&
           lower.compare(lower.size() - end.size(), end.size(), end) == 0;
  };
  const std::size_t eq = text.find(" = ");
  if (eq != std::string::npos && eq > 0 &&
      text.substr(0, eq).find_first_of(" \t") == std::string_view::npos)
    return true;
  if (eq != std::string::npos && (ends_with("= true") || ends_with("= false"))) return true;
  // "Feed: Max Toolpath Speed = 1000": a setting and its number.
  if (const std::size_t last = text.rfind(" = ");
      last != std::string_view::npos && text.size() > last + 3 &&
      text.substr(last + 3).find_first_not_of("0123456789.-+") == std::string_view::npos)
    return true;
  if (text.size() > 2 && text.front() == '[' && text.back() == ']') return true;
  if (text.back() == ':') return true; // the heading of a list ("G1->G0 Mapping Properties:")
  // A label and coordinates only ("start: 2.064,7.620").
  if (const std::size_t colon = text.find(": ");
      colon != std::string_view::npos &&
      text.substr(colon + 2).find_first_not_of("0123456789.,-+ ") == std::string_view::npos)
    return true;
  for (std::string_view bound : {" begin", " end"}) {
    if (!ends_with(bound)) continue;
    // The words before it in capitals, as generators write their section names.
    const std::string_view words = text.substr(0, text.size() - bound.size());
    if (words.find_first_of("abcdefghijklmnopqrstuvwxyz") == std::string_view::npos) return true;
  }
  return false;
}

} // namespace

std::optional<std::string_view> comment_of_line(std::string_view line, const Dialect& dialect) {
  const LineComments c = line_comments(line, dialect);
  if (c.comments.empty()) return std::nullopt;
  if (c.has_code) {
    // A block number is no code here: "N10 (Face1)" is how many posts name an operation.
    if (c.comments.size() != 1) return std::nullopt;
    const std::size_t open = std::size_t(std::max(0, c.comments.front().column - 1));
    const std::string_view before = trim(line.substr(0, open));
    const bool block_number =
        before.size() > 1 && (before[0] == 'N' || before[0] == 'n') &&
        before.substr(1).find_first_not_of("0123456789") == std::string_view::npos;
    const std::size_t close = line[open] == '(' ? line.find(')', open) : line.size();
    if (!block_number || close == std::string_view::npos ||
        !trim(line.substr(std::min(close + 1, line.size()))).empty())
      return std::nullopt;
  }
  return c.comments.front().text;
}

std::string operation_name_in(std::string_view comment) {
  std::string_view text = trim(comment);
  // Rules and frames around a name ("--- FACE TOP ---", "*** DRILL ***"), and comments that are
  // nothing else ("----------------------").
  while (!text.empty() && is_rule_mark(text.front()))
    text.remove_prefix(1);
  while (!text.empty() && is_rule_mark(text.back()))
    text.remove_suffix(1);
  if (text.empty() || text.size() > 80) return {};
  std::string l = to_lower(text);
  // LinuxCNC's comment commands: a message to the operator names what comes ("MSG, Change tool
  // bit to drill size 0.4mm"); debug, print and log output ("DEBUG, slot width is #<w>") and
  // the log and probe file commands name nothing.
  if (starts_with(l, "msg,")) {
    text = trim(text.substr(4));
    l = to_lower(text);
  }
  for (const char* command : {"debug,", "print,", "log,", "logopen,", "logappend,", "logclose",
                              "probeopen", "probeclose", "abort,"})
    if (starts_with(l, command)) return {};
  for (const char* prefix : {"begin operation:", "begin operation",
                             "start operation:", "operation:", "op:", "block-name:"}) {
    if (starts_with(l, prefix)) {
      text = trim(text.substr(std::string_view(prefix).size()));
      l = to_lower(text);
      break;
    }
  }
  const bool digits_only =
      l.find_first_not_of("0123456789. ") == std::string::npos; // "14": a counter, no name
  if (text.empty() || digits_only || describes_tool(l) || is_code(text) || is_o_word(text) ||
      is_note(l) || is_bare_number(l) || is_marker(text, l))
    return {};
  return std::string(text);
}

OperationTracker::OperationTracker(const SourceFile& source, const Dialect& dialect)
    : source_(source), dialect_(dialect) {
  Op lead;
  lead.summary.line = -1;
  ops_.push_back(lead);
}

void OperationTracker::find_comments_before(int line) {
  const std::size_t end = std::min(std::size_t(std::max(line, 0)), source_.lines.size());
  for (; comments_read_ < end; ++comments_read_) {
    const auto text = comment_of_line(source_.line_text(comments_read_), dialect_);
    if (text && !operation_name_in(*text).empty()) comment_lines_.push_back(int(comments_read_));
  }
}

std::size_t OperationTracker::start(int line, int comment_line, const CanonCommand& command,
                                    double start_s) {
  const int key = comment_line >= 0 ? comment_line : line;
  const auto [it, inserted] = by_line_.try_emplace(key, ops_.size());
  if (inserted) {
    Op op;
    op.summary.line = line;
    op.summary.start_s = start_s;
    op.summary.tool = command.kind == CanonKind::ChangeTool ? int(std::lround(command.value))
                                                            : command.state.tool;
    op.comment_line = comment_line;
    ops_.push_back(op);
  }
  return it->second;
}

void OperationTracker::rename(int comment_line) {
  Op& now = ops_[current_];
  if (now.comment_line == comment_line) return;
  by_line_.erase(now.comment_line);
  const auto [it, inserted] = by_line_.try_emplace(comment_line, current_);
  if (inserted)
    now.comment_line = comment_line;
  else
    current_ = it->second; // a loop runs the named operation again
}

std::size_t OperationTracker::take(const CanonCommand& command, const TimedCommand& timed) {
  const int line = command.line;
  // Operation comments are looked for in the main program, between the block that ran last
  // and this one, a subprogram's blocks standing at their call: after Estlcam's stops (O-word
  // subprograms), between their call and this block, never in a subprogram's body (the comments
  // above a subprogram describe it, not an operation of the program).
  const int at = command.call_line;
  std::optional<int> comment; // the first one there
  auto first_between = [&](int after, int before) -> std::optional<int> {
    find_comments_before(before);
    const auto it = std::upper_bound(comment_lines_.begin(), comment_lines_.end(), after);
    if (it != comment_lines_.end() && *it < before) return *it;
    return std::nullopt;
  };
  if (at > last_call_line_) comment = first_between(last_call_line_, at);
  Op& now = ops_[current_];
  // An operation started by its comment that has not moved yet: a later comment names it.
  // Not once a tool change has followed its comment: "(Profiles)" / "T2 M6" / "(Profile:
  // Layer 6)" is the operation Profiles.
  const bool unnamed =
      current_ != 0 && now.comment_line >= 0 && !now.cut && !now.moved && !now.changed_tool;
  if (command.kind == CanonKind::ChangeTool) {
    if (now.comment_line >= 0 && !now.cut && current_ != 0) {
      // The post's comment came first ("(FACE1)", "M9", "G28 G91 Z0", "T1 M6"): one operation.
      if (comment && unnamed) rename(*comment);
      ops_[current_].summary.tool = int(std::lround(command.value));
      ops_[current_].summary.line = line;
      ops_[current_].changed_tool = true;
    } else {
      current_ = start(line, -1, command, timed.start_s);
    }
  } else if (comment) {
    if (now.cut || (current_ == 0 && last_line_ >= 0) || (now.comment_line >= 0 && now.moved)) {
      // The next operation starts once this one has cut; the first one (FreeCAD's, Estlcam's
      // "No. 1") once the program's preamble has run, and not at the header's comments above
      // it; one after an operation of moves and stops only (Estlcam's "Stop After ...").
      current_ = start(line, *comment, command, timed.start_s);
    } else if (unnamed) {
      rename(*comment);
    }
  }
  // Until it cuts, an operation takes the tool in the spindle: one changed by hand where the
  // post wrote the change as a comment (FreeCAD's grbl post) is the one it cuts with.
  if (Op& op = ops_[current_];
      !op.cut && command.kind != CanonKind::ChangeTool && (current_ != 0 || op.summary.tool == 0))
    op.summary.tool = command.state.tool;
  last_line_ = line;
  last_call_line_ = at;
  return current_;
}

void OperationTracker::add(std::size_t op, CanonKind kind, double duration_s, double energy_j,
                           const ComponentValues& components_j, double removed_mm3,
                           bool removal_known) {
  Op& o = ops_[op];
  o.summary.time_s += duration_s;
  o.summary.energy_j += energy_j;
  o.summary.removed_mm3 += removed_mm3;
  for (std::size_t c = 0; c < kPowerComponentCount; ++c)
    o.summary.components_j[c] += components_j[c];
  o.summary.time.add(kind, duration_s, removed_mm3 > 0, removal_known);
  if (is_feed_move(kind)) o.cut = true;
  if (is_move(kind)) o.moved = true;
}

std::string OperationTracker::name_of(const Op& op, const std::function<bool(int)>& stops) const {
  auto comment_at = [&](int line) -> std::optional<std::string_view> {
    return comment_of_line(source_.line_text(std::size_t(line)), dialect_);
  };
  if (op.comment_line >= 0)
    if (auto text = comment_at(op.comment_line)) return operation_name_in(*text);
  const int at = op.summary.line;
  const int n = int(source_.lines.size());
  if (at < 0 || at >= n) return "T" + std::to_string(op.summary.tool);
  // Above the tool change, past lines that do not cut (M5, M9, G28, T2, blank lines), not into
  // the header's tool list.
  for (int i = at - 1; i >= std::max(0, at - kNameSearchLines); --i) {
    if (stops(i)) break;
    const auto text = comment_at(i);
    if (!text) continue;
    if (describes_tool(to_lower(trim(*text)))) break;
    if (std::string name = operation_name_in(*text); !name.empty()) return name;
  }
  // On the tool-change line.
  for (const LineComment& c : line_comments(source_.line_text(std::size_t(at)), dialect_).comments)
    if (std::string name = operation_name_in(c.text); !name.empty()) return name;
  // Below it (some Haas and Fanuc posts), before the first cut.
  for (int i = at + 1; i <= std::min(n - 1, at + kNameSearchLines); ++i) {
    if (stops(i)) break;
    if (const auto text = comment_at(i))
      if (std::string name = operation_name_in(*text); !name.empty()) return name;
  }
  return "T" + std::to_string(op.summary.tool);
}

std::vector<OperationSummary>
OperationTracker::finish(const std::function<bool(int)>& cuts_on, const EnergyResult& totals,
                         std::vector<std::uint16_t>& index_map) const {
  std::vector<int> starts;
  for (const Op& op : ops_) {
    if (op.summary.line >= 0) starts.push_back(op.summary.line);
    if (op.comment_line >= 0) starts.push_back(op.comment_line);
  }
  std::sort(starts.begin(), starts.end());
  auto stops = [&](int line) {
    return cuts_on(line) || std::binary_search(starts.begin(), starts.end(), line);
  };
  std::vector<OperationSummary> out;
  index_map.assign(ops_.size(), 0);
  const OperationSummary& lead = ops_[0].summary;
  const bool lead_empty = lead.time_s == 0 && lead.energy_j == 0 && lead.removed_mm3 == 0;
  for (std::size_t i = 0; i < ops_.size(); ++i) {
    OperationSummary op = ops_[i].summary;
    if (i == 0) {
      if (ops_.size() > 1 && lead_empty) continue;
      op.name = ops_.size() == 1 ? "program" : "before first operation";
    } else {
      op.name = name_of(ops_[i], stops);
    }
    const double share = totals.energy_j > 0 ? op.energy_j / totals.energy_j : 0.0;
    op.co2_kg = totals.co2_kg * share;
    // Electricity by the operation's energy, the machine-hour rate by its time.
    const double time_share = totals.duration_s > 0 ? op.time_s / totals.duration_s : 0.0;
    op.cost = totals.electricity_cost * share + totals.machine_cost * time_share;
    out.push_back(std::move(op));
    index_map[i] = std::uint16_t(std::min<std::size_t>(out.size(), 65535));
  }
  return out;
}

} // namespace ncjoule::estimate_detail
