// The interpreter's main loop: control flow (O-words, M98/M99) and the execution of one block
// in LinuxCNC's order of execution.
#include "interpreter_impl.hpp"

#include <algorithm>
#include <cmath>

namespace ncjoule::detail {
namespace {

// Modal groups of G codes (x10). Two codes of one group in one block are an error.
int g_group(int code) {
  switch (code) {
  case 0:
  case 10:
  case 20:
  case 30:
  case 330:
  case 331:
  case 382:
  case 383:
  case 384:
  case 385:
  case 730:
  case 740:
  case 760:
  case 800:
  case 810:
  case 820:
  case 830:
  case 840:
  case 850:
  case 860:
  case 870:
  case 880:
  case 890:
    return 1;
  case 170:
  case 180:
  case 190:
    return 2;
  case 900:
  case 910:
    return 3;
  case 901:
  case 911:
    return 4;
  case 930:
  case 940:
  case 950:
    return 5;
  case 200:
  case 210:
    return 6;
  case 400:
  case 410:
  case 411:
  case 420:
  case 421:
    return 7;
  case 430:
  case 431:
  case 432:
  case 490:
    return 8;
  case 980:
  case 990:
    return 10;
  case 540:
  case 550:
  case 560:
  case 570:
  case 580:
  case 590:
  case 591:
  case 592:
  case 593:
    return 12;
  case 610:
  case 611:
  case 640:
    return 13;
  case 40:
  case 100:
  case 280:
  case 281:
  case 300:
  case 301:
  case 530:
  case 920:
  case 921:
  case 922:
  case 923:
    return 0;
  default:
    return -1;
  }
}

std::string g_name(int code) {
  std::string s = "G" + std::to_string(code / 10);
  if (code % 10) s += "." + std::to_string(code % 10);
  return s;
}

bool has_g(const BlockValues& v, int code) {
  return std::find(v.g.begin(), v.g.end(), code) != v.g.end();
}
bool has_m(const BlockValues& v, int code) {
  return std::find(v.m.begin(), v.m.end(), code) != v.m.end();
}

// Codes that change only how a controller blends or smooths the path: kept as planner hints.
// - Haas G187 P1/P2/P3 E<tol> (Haas Mill Operator's Manual, "G187 Accuracy Control"): rough,
//   medium or finish smoothing, E the corner rounding tolerance.
// - Haas G103 P<n> ("G103 Limit Block Lookahead"): at most n blocks of look-ahead, P0 none.
// - Fanuc G05.1 Q1/Q0 (AI contour control on/off), G08 P1/P0 (advanced preview control), G05
//   P10000 (high-speed machining mode). G5/G5.1 are splines in LinuxCNC, hence the dialect test.
// - Sinumerik G641/G642/G643/G644/G645: continuous path with rounding.
bool is_planner_hint_g(int code, const Dialect& dialect) {
  if (code == 1870 || code == 1030 || code == 80 || code == 81) return true;
  if (dialect.sinumerik_words && code >= 6410 && code <= 6450) return true;
  const bool linuxcnc = dialect.o_word_subroutines;
  return !linuxcnc && (code == 51 || code == 50);
}

std::string number_text(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

} // namespace

int BlockValues::g_column(int code) const {
  for (auto& [c, col] : g_columns)
    if (c == code) return col;
  return column['g' - 'a'];
}

Interpreter::Interpreter(const SourceFile& source, const InterpreterOptions& options,
                         const CanonSink& sink)
    : source_(source), options_(options), sink_(sink),
      dialect_(options.dialect ? *options.dialect : detect_dialect(source)), tools_(options.tools) {
  result_.dialect = dialect_;
  retract_to_r_ = dialect_.retract_to_r_by_default;
  arc_incremental_ = !dialect_.arc_centre_absolute;
  params_.set_system_lookup(
      [this](std::string_view name, double& value) { return system_parameter(name, value); });
}

bool Interpreter::system_parameter(std::string_view name, double& value) const {
  const double u = unit();
  if (name == "_x") return value = pos_.x / u, true;
  if (name == "_y") return value = pos_.y / u, true;
  if (name == "_z") return value = pos_.z / u, true;
  if (name == "_a") return value = pos_.a, true;
  if (name == "_b") return value = pos_.b, true;
  if (name == "_c") return value = pos_.c, true;
  if (name == "_metric") return value = state_.inch ? 0 : 1, true;
  if (name == "_imperial") return value = state_.inch ? 1 : 0, true;
  if (name == "_absolute") return value = incremental_ ? 0 : 1, true;
  if (name == "_incremental") return value = incremental_ ? 1 : 0, true;
  if (name == "_feed") return value = state_.feed / u, true;
  if (name == "_rpm") return value = state_.spindle_rpm, true;
  if (name == "_current_tool") return value = state_.tool, true;
  if (name == "_selected_tool") return value = selected_tool_, true;
  if (name == "_motion_mode") return value = int(motion_), true;
  if (name == "_plane")
    return value = state_.plane == Plane::XY ? 170 : state_.plane == Plane::XZ ? 180 : 190, true;
  if (name == "_coord_system")
    return value = g5x_index_ <= 6 ? 530 + 10 * g5x_index_ : 590 + (g5x_index_ - 6), true;
  if (name == "_line") return value = current_line_ + 1, true;
  if (name == "_task") return value = 0, true; // not running under a GUI preview
  if (name == "_value_returned") return value = 0, true;
  if (name == "_call_level") return value = double(frames_.size()), true;
  return false;
}

// A loop repeats its blocks' diagnostics: each (line, column, message) is reported once, and
// at most kMaxDiagnostics in all.
constexpr std::size_t kMaxDiagnostics = 1000;

void Interpreter::report(Severity severity, int column, std::string message) {
  if (!reported_.emplace(current_line_, column, message).second) return;
  if (result_.diagnostics.size() == kMaxDiagnostics) {
    result_.diagnostics.push_back({Severity::Note, source_.path, current_line_ + 1, 0,
                                   "too many diagnostics: the rest are not shown"});
  }
  if (result_.diagnostics.size() > kMaxDiagnostics && severity != Severity::Error) return;
  result_.diagnostics.push_back(
      {severity, source_.path, current_line_ + 1, column, std::move(message)});
}
void Interpreter::error(int column, std::string message) {
  report(Severity::Error, column, std::move(message));
}
void Interpreter::warning(int column, std::string message) {
  report(Severity::Warning, column, std::move(message));
}
void Interpreter::note(int column, std::string message) {
  report(Severity::Note, column, std::move(message));
}

CanonCommand Interpreter::make(CanonKind kind) const {
  CanonCommand c;
  c.kind = kind;
  c.line = current_line_;
  c.call_line = current_call_line_;
  c.state = state_;
  c.plane = state_.plane;
  c.start = pos_;
  c.end = pos_;
  return c;
}

void Interpreter::emit(CanonCommand c) {
  ++command_count_;
  if (options_.max_commands && command_count_ > options_.max_commands) {
    if (!finished_)
      error(0, "more than " + std::to_string(options_.max_commands) +
                   " canonical commands: stopped (runaway loop?)");
    stop();
    return;
  }
  sink_(c);
}

void Interpreter::emit_simple(CanonKind kind, double value, std::string text) {
  CanonCommand c = make(kind);
  c.value = value;
  c.text = std::move(text);
  emit(std::move(c));
}

Pose Interpreter::offset_total() const {
  const Pose& w = g5x_[g5x_index_];
  return {w.x + g92_.x, w.y + g92_.y, w.z + g92_.z, w.a + g92_.a, w.b + g92_.b, w.c + g92_.c};
}

// ------------------------------------------------------------------------------------------
// Labels and the main loop
// ------------------------------------------------------------------------------------------

void Interpreter::scan_labels() {
  // Only lines that begin (after blanks, '/', an N number) with 'o' can hold O-words.
  Block b;
  for (std::size_t i = 0; i < source_.lines.size(); ++i) {
    std::string_view l = source_.line_text(i);
    std::size_t k = 0;
    while (k < l.size() && (l[k] == ' ' || l[k] == '\t' || l[k] == '/'))
      ++k;
    if (k < l.size() && (l[k] == 'n' || l[k] == 'N')) {
      ++k;
      while (k < l.size() &&
             (std::isdigit(static_cast<unsigned char>(l[k])) || l[k] == ' ' || l[k] == '.'))
        ++k;
    }
    if (k >= l.size() || (l[k] != 'o' && l[k] != 'O')) continue;
    lex_line(l, dialect_, b);
    if (!b.has_o) continue;
    if (b.o_keyword.empty()) {
      if (!b.o_label.empty() && std::isdigit(static_cast<unsigned char>(b.o_label[0])))
        program_numbers_.emplace(std::stol(b.o_label), i);
    } else {
      labels_[b.o_label].emplace_back(i, b.o_keyword);
    }
  }
}

std::optional<std::size_t> Interpreter::find_next(const std::string& label, std::size_t after,
                                                  std::initializer_list<const char*> keys) const {
  auto it = labels_.find(label);
  if (it == labels_.end()) return std::nullopt;
  for (auto& [line, kw] : it->second) {
    if (line <= after) continue;
    for (const char* k : keys)
      if (kw == k) return line;
  }
  return std::nullopt;
}

std::optional<std::size_t> Interpreter::find_prev(const std::string& label, std::size_t before,
                                                  std::initializer_list<const char*> keys) const {
  auto it = labels_.find(label);
  if (it == labels_.end()) return std::nullopt;
  std::optional<std::size_t> found;
  for (auto& [line, kw] : it->second) {
    if (line >= before) break;
    for (const char* k : keys)
      if (kw == k) found = line;
  }
  return found;
}

InterpretResult Interpreter::run() {
  scan_labels();
  BlockValues values;
  const std::size_t n = source_.lines.size();
  while (!finished_ && pc_ < n) {
    current_line_ = int(pc_);
    current_call_line_ = frames_.empty() ? int(pc_) : frames_.front().call_line;
    next_pc_ = pc_ + 1;
    lex_line(source_.line_text(pc_), dialect_, block_);
    for (Diagnostic d : block_.warnings)
      report(d.severity, d.column, std::move(d.message));
    if (!block_.errors.empty()) {
      for (Diagnostic d : block_.errors) {
        d.file = source_.path;
        d.line = current_line_ + 1;
        result_.diagnostics.push_back(std::move(d));
      }
      note(0, "block skipped");
    } else if (block_.percent) {
      // A '%' opens the program; the next one closes it (LinuxCNC, Fanuc tape format). A name
      // after it ("%prog1", "%PM") names the program; Heidenhain's "%NAME G71" gives its units.
      if (seen_percent_) finished_ = true, result_.completed = true;
      seen_percent_ = true;
      if (dialect_.g70_g71_units && !finished_) {
        const std::string_view rest = block_.percent_name;
        const bool inch = rest.find("g70") != std::string_view::npos;
        if ((inch || rest.find("g71") != std::string_view::npos) && inch != state_.inch) {
          state_.inch = inch;
          emit_simple(CanonKind::LengthUnits);
        }
      }
    } else if (block_.dollar || (block_.block_delete && options_.block_delete)) {
      // grbl settings lines and deleted blocks do nothing.
    } else if (block_.has_o) {
      ++result_.blocks;
      handle_o_word(block_);
    } else if (block_.has_code()) {
      ++result_.blocks;
      if (evaluate_words(block_, values)) execute(block_, values);
    } else if (!block_.comments.empty()) {
      for (const Comment& c : block_.comments) {
        std::string_view t = c.text;
        std::string lowered(t.substr(0, 4));
        for (char& ch : lowered)
          ch = char(std::tolower(static_cast<unsigned char>(ch)));
        if (lowered == "msg,") emit_simple(CanonKind::Message, 0, std::string(t.substr(4)));
      }
    }
    if (next_pc_ <= pc_ && options_.max_loop_iterations &&
        ++loop_iterations_ > options_.max_loop_iterations) {
      error(0, "loops jumped back more than " + std::to_string(options_.max_loop_iterations) +
                   " times: stopped (endless loop?)");
      break;
    }
    pc_ = next_pc_;
  }
  if (!finished_ && !result_.diagnostics.empty() &&
      std::any_of(result_.diagnostics.begin(), result_.diagnostics.end(),
                  [](const Diagnostic& d) { return d.severity == Severity::Error; })) {
    result_.completed = false;
  } else if (!finished_) {
    current_line_ = n ? int(n - 1) : 0;
    warning(0, "the program has no M2 or M30: it ends at the end of the file");
    result_.completed = true;
  }
  result_.commands = command_count_;
  return result_;
}

// ------------------------------------------------------------------------------------------
// O-word control flow
// ------------------------------------------------------------------------------------------

bool Interpreter::eval_condition(std::string_view args, int column, double& value) {
  std::size_t len = value_length(args, 0);
  if (len == 0 || len != args.size()) {
    error(column, "expected one [expression] after the O-word keyword");
    return false;
  }
  std::string err;
  std::size_t off = 0;
  if (!evaluate(args, params_, value, err, off)) {
    error(column, err);
    return false;
  }
  return true;
}

void Interpreter::call_subroutine(std::size_t target_line, std::vector<double> args, bool fanuc,
                                  int repeats) {
  if (frames_.size() >= 100) {
    error(0, "subroutines nested more than 100 deep: stopped");
    stop();
    return;
  }
  Frame f;
  f.return_pc = pc_ + 1;
  f.start_pc = target_line + 1;
  f.fanuc = fanuc;
  f.repeats_left = repeats;
  f.call_line = frames_.empty() ? int(pc_) : frames_.front().call_line;
  params_.push_scope();
  if (!fanuc || !args.empty()) {
    for (int i = 1; i <= 30; ++i)
      params_.at(i) = 0;
    for (std::size_t i = 0; i < args.size() && i < 30; ++i)
      params_.at(int(i) + 1) = args[i];
  }
  frames_.push_back(std::move(f));
  next_pc_ = target_line + 1;
}

void Interpreter::return_from_subroutine(std::optional<double> value) {
  if (frames_.empty()) return;
  Frame& f = frames_.back();
  if (f.fanuc && f.repeats_left > 1) {
    --f.repeats_left;
    next_pc_ = f.start_pc;
    return;
  }
  next_pc_ = f.return_pc;
  frames_.pop_back();
  params_.pop_scope();
  if (value) params_.write("_value", *value);
  params_.write("_value_returned", value ? 1.0 : 0.0);
}

void Interpreter::handle_o_word(const Block& b) {
  const std::string& kw = b.o_keyword;
  const std::string& label = b.o_label;
  const int col = b.o_column;
  if (kw.empty()) return; // a Fanuc O-number program header: nothing to do
  if (!dialect_.o_word_subroutines) {
    warning(col, "O-word '" + kw + "' is LinuxCNC syntax, not of the " + dialect_.name +
                     " dialect; interpreted as LinuxCNC would");
  }
  if (kw == "sub") {
    // A definition met in the flow of the program: skip its body.
    auto end = find_next(label, pc_, {"endsub"});
    if (!end) {
      error(col, "o" + label + " sub has no matching endsub");
      stop();
      return;
    }
    next_pc_ = *end + 1;
  } else if (kw == "endsub" || kw == "return") {
    if (frames_.empty()) {
      if (kw == "return") warning(col, "o" + label + " return outside a subroutine: ignored");
      return;
    }
    std::optional<double> value;
    if (!b.o_args.empty()) {
      double v;
      if (eval_condition(b.o_args, col, v)) value = v;
    }
    return_from_subroutine(value);
  } else if (kw == "call") {
    std::vector<double> args;
    std::string_view rest = b.o_args;
    std::size_t p = 0;
    while (p < rest.size()) {
      std::size_t len = value_length(rest, p);
      if (!len) {
        error(col, "subroutine arguments must be [expressions] or numbers");
        return;
      }
      double v;
      std::string err;
      std::size_t off;
      if (!evaluate(rest.substr(p, len), params_, v, err, off)) {
        error(col, err);
        return;
      }
      args.push_back(v);
      p += len;
    }
    auto it = labels_.find(label);
    std::optional<std::size_t> sub;
    if (it != labels_.end())
      for (auto& [line, k] : it->second)
        if (k == "sub") sub = line;
    if (!sub) {
      error(col, "subroutine o" + label +
                     " is not defined in this file (subroutine files on a search path are not "
                     "read): call skipped");
      return;
    }
    call_subroutine(*sub, std::move(args), false, 1);
  } else if (kw == "if" || kw == "elseif") {
    if (kw == "elseif") {
      // Reached by falling out of a branch that ran: the if is done.
      auto end = find_next(label, pc_, {"endif"});
      next_pc_ = end ? *end + 1 : pc_ + 1;
      return;
    }
    std::size_t at = pc_;
    std::string_view args = b.o_args;
    Block other;
    for (;;) {
      double v;
      if (!eval_condition(args, col, v)) return;
      if (v != 0) {
        next_pc_ = at + 1;
        return;
      }
      auto branch = find_next(label, at, {"elseif", "else", "endif"});
      if (!branch) {
        error(col, "o" + label + " if has no matching endif");
        stop();
        return;
      }
      lex_line(source_.line_text(*branch), dialect_, other);
      if (other.o_keyword == "elseif") {
        at = *branch;
        args = other.o_args;
        continue;
      }
      next_pc_ = *branch + 1;
      return;
    }
  } else if (kw == "else") {
    auto end = find_next(label, pc_, {"endif"});
    next_pc_ = end ? *end + 1 : pc_ + 1;
  } else if (kw == "endif" || kw == "do") {
    // nothing: flow goes on
  } else if (kw == "while") {
    // The tail of a do-while loop when a 'do' with this label comes before it, after any
    // earlier while/endwhile of the same label.
    auto do_line = find_prev(label, pc_, {"do"});
    auto prev_loop = find_prev(label, pc_, {"endwhile"});
    double v;
    if (!eval_condition(b.o_args, col, v)) return;
    if (do_line && (!prev_loop || *prev_loop < *do_line)) {
      if (v != 0) next_pc_ = *do_line + 1;
      return;
    }
    if (v == 0) {
      auto end = find_next(label, pc_, {"endwhile"});
      if (!end) {
        error(col, "o" + label + " while has no matching endwhile");
        stop();
        return;
      }
      next_pc_ = *end + 1;
    }
  } else if (kw == "endwhile") {
    auto head = find_prev(label, pc_, {"while"});
    if (!head) {
      error(col, "o" + label + " endwhile has no matching while");
      return;
    }
    next_pc_ = *head;
  } else if (kw == "repeat") {
    auto& counters = frames_.empty() ? top_repeat_counters_ : frames_.back().repeat_counters;
    double v;
    if (!eval_condition(b.o_args, col, v)) return;
    long count = saturate<long>(std::floor(v + 1e-9));
    auto end = find_next(label, pc_, {"endrepeat"});
    if (!end) {
      error(col, "o" + label + " repeat has no matching endrepeat");
      stop();
      return;
    }
    if (count <= 0) {
      next_pc_ = *end + 1;
      return;
    }
    counters[pc_] = count;
  } else if (kw == "endrepeat") {
    auto& counters = frames_.empty() ? top_repeat_counters_ : frames_.back().repeat_counters;
    auto head = find_prev(label, pc_, {"repeat"});
    if (!head) {
      error(col, "o" + label + " endrepeat has no matching repeat");
      return;
    }
    auto it = counters.find(*head);
    if (it != counters.end() && --it->second > 0) {
      next_pc_ = *head + 1;
    } else if (it != counters.end()) {
      counters.erase(it);
    }
  } else if (kw == "break") {
    auto end = find_next(label, pc_, {"endwhile", "endrepeat", "while"});
    if (end) {
      auto& counters = frames_.empty() ? top_repeat_counters_ : frames_.back().repeat_counters;
      if (auto head = find_prev(label, pc_, {"repeat"})) counters.erase(*head);
      next_pc_ = *end + 1;
    }
  } else if (kw == "continue") {
    auto end = find_next(label, pc_, {"endwhile", "endrepeat", "while"});
    if (end) next_pc_ = *end;
  } else {
    error(col, "unknown O-word keyword '" + kw + "'");
  }
}

// ------------------------------------------------------------------------------------------
// Words and modal groups
// ------------------------------------------------------------------------------------------

bool Interpreter::evaluate_words(const Block& b, BlockValues& v) {
  v.letter.fill(std::nullopt);
  v.g.clear();
  v.m.clear();
  v.g_columns.clear();
  bool ok = true;
  for (const Word& w : b.words) {
    double value;
    std::string err;
    std::size_t off = 0;
    if (!evaluate(w.value, params_, value, err, off)) {
      error(w.column, err);
      ok = false;
      continue;
    }
    const char up = char(std::toupper(w.letter));
    if (w.letter == 'g' || w.letter == 'm') {
      const double scaled = value * 10.0;
      const double r = std::round(scaled);
      if (std::abs(scaled - r) > 1e-6 || value < 0 || value > 100000) {
        error(w.column, std::string(1, up) + " code must be a number from 0 to 100000 with at "
                                             "most one decimal");
        ok = false;
        continue;
      }
      if (w.letter == 'g') {
        v.g.push_back(int(r));
        v.g_columns.emplace_back(int(r), w.column);
      } else {
        if (int(r) % 10) {
          error(w.column, "M codes have no decimals");
          ok = false;
          continue;
        }
        v.m.push_back(int(r) / 10);
      }
      v.column[w.letter - 'a'] = w.column;
      continue;
    }
    if (w.letter == 'n') continue; // N words past the first are labels too
    if (v.letter[slot(w.letter)]) {
      error(w.column, std::string("more than one ") + up + " word on the line");
      ok = false;
      continue;
    }
    v.letter[slot(w.letter)] = value;
    v.column[slot(w.letter)] = w.column;
  }
  // Parameter assignments take effect after every word of the line has been read, and all of
  // them read the values from before the line: "#1=5 #2=[#1+1]" sets #2 from the old #1.
  struct Pending {
    std::string_view name; // named parameter, or empty
    int index = 0;
    double value = 0;
    int column = 0;
  };
  std::vector<Pending> pending;
  for (const Assignment& a : b.assignments) {
    Pending w{{}, 0, 0, a.column};
    std::string err;
    std::size_t off = 0;
    if (!evaluate(a.value, params_, w.value, err, off)) {
      error(a.column, err);
      ok = false;
      continue;
    }
    if (!a.target.empty() && a.target.front() == '<') {
      w.name = a.target.substr(1, a.target.size() - 2);
    } else {
      double index;
      if (!evaluate(a.target, params_, index, err, off)) {
        error(a.column, err);
        ok = false;
        continue;
      }
      w.index = saturate<int>(std::round(index));
    }
    pending.push_back(w);
  }
  for (const Pending& w : pending) {
    std::string err;
    if (!w.name.empty())
      params_.write(w.name, w.value);
    else if (!params_.write(w.index, w.value, err))
      error(w.column, err), ok = false;
  }
  return ok;
}

bool Interpreter::check_modal_groups(const BlockValues& v) {
  int seen[16] = {};
  bool ok = true;
  for (int code : v.g) {
    const int group = g_group(code);
    if (group < 0) continue;
    if (seen[group]) {
      error(v.g_column(code), "two G codes of the same modal group on one line: " +
                                  g_name(seen[group] - 1) + " and " + g_name(code));
      ok = false;
    }
    seen[group] = code + 1;
  }
  return ok;
}

void Interpreter::execute(const Block& b, BlockValues& v) {
  if (dialect_.g65_macro_calls && has_g(v, 650)) {
    macro_call(v);
    return;
  }
  // Which of two codes of one group the programmer meant cannot be known: the block is skipped
  // whole, as rs274 refuses it, and the program goes on.
  if (!check_modal_groups(v)) {
    note(0, "block skipped");
    return;
  }
  // Words of several letters (Sinumerik frames and cycles, ...), before any motion.
  std::optional<SinumerikCycle> cycle_now;
  if (!b.keywords.empty()) keywords(b, v, cycle_now);
  const bool positioning = v.has_axis();
  // 1. Comments and messages.
  for (const Comment& c : b.comments) {
    std::string lowered(c.text.substr(0, 4));
    for (char& ch : lowered)
      ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (lowered == "msg,") emit_simple(CanonKind::Message, 0, std::string(c.text.substr(4)));
  }
  // Unknown codes: warned about, never fatal.
  for (int code : v.g) {
    if (g_group(code) >= 0) continue;
    if (is_planner_hint_g(code, dialect_)) {
      std::string text = g_name(code);
      for (char letter : {'p', 'q', 'e', 'r', 'l'})
        if (v.has(letter))
          text += std::string(" ") + char(std::toupper(letter)) + number_text(*v[letter]);
      emit_simple(CanonKind::PlannerHint, code / 10.0, text);
      continue;
    }
    if (dialect_.g70_g71_units && (code == 700 || code == 710 || code == 7000 || code == 7100)) {
      // Heidenhain ISO and Sinumerik: G70 (G700) inch, G71 (G710) millimetres.
      const bool inch = code == 700 || code == 7000;
      if (inch != state_.inch) state_.inch = inch, emit_simple(CanonKind::LengthUnits);
      continue;
    }
    switch (code) {
    case 70:
    case 80:
    case 150:
    case 160:
    case 960:
    case 970:
    case 911:
    case 901:
      break; // lathe diameter mode, spindle modes: no effect on milling motion
    case 2900:
    case 2910:
      break; // Sinumerik G290/G291: Siemens or ISO mode; both are read here
    case 50:
    case 51:
      if (dialect_.o_word_subroutines) break; // LinuxCNC splines: see the motion step
      [[fallthrough]];
    case 410:
    case 420:
      break;
    default:
      warning(v.g_column(code), "unknown or unsupported code " + g_name(code) +
                                    ": ignored (the block's motion is still counted)");
    }
  }
  for (char axis : {'u', 'v', 'w'}) {
    if (v.has(axis))
      warning(v.column[slot(axis)], std::string("the ") + char(std::toupper(axis)) +
                                        " axis is not modelled: its word is ignored");
  }
  // 3. Feed mode, 4. feed rate.
  for (int code : v.g) {
    if (code == 930 || code == 940 || code == 950) {
      FeedMode m = code == 930   ? FeedMode::InverseTime
                   : code == 940 ? FeedMode::UnitsPerMinute
                                 : FeedMode::UnitsPerRevolution;
      if (m != state_.feed_mode) {
        state_.feed_mode = m;
        emit_simple(CanonKind::SetFeedMode, double(code));
      }
      if (m == FeedMode::InverseTime) state_.feed = 0; // G93 needs F on every feed block
    }
  }
  if (v.has('f')) {
    const double f = *v['f'];
    if (f < 0) error(v.column['f' - 'a'], "negative feed rate");
    state_.feed = state_.feed_mode == FeedMode::InverseTime ? f : f * unit();
    // Under G93 the feed rate is set per move, from its length (see inverse_time_feed).
    if (state_.feed_mode != FeedMode::InverseTime) emit_simple(CanonKind::SetFeedRate, f);
  }
  // 5. Spindle speed.
  if (v.has('s') && !(dialect_.dwell_s_word && has_g(v, 40))) {
    const double s = *v['s'];
    if (s < 0) error(v.column['s' - 'a'], "negative spindle speed");
    state_.spindle_rpm = std::abs(s);
    emit_simple(CanonKind::SpindleSpeed, state_.spindle_rpm);
  }
  // 6. Select tool.
  if (v.has('t')) {
    const double t = *v['t'];
    if (t < 0 || std::abs(t - std::round(t)) > 1e-6) {
      error(v.column['t' - 'a'], "T word must be a non-negative integer");
    } else {
      selected_tool_ = int(std::lround(t));
      emit_simple(CanonKind::SelectTool, selected_tool_);
    }
  }
  // 7. Tool change.
  for (int m : v.m) {
    if (m == 6) {
      // The spindle stops for the change; the program restarts it.
      if (state_.spindle != SpindleDir::Off) {
        state_.spindle = SpindleDir::Off;
        emit_simple(CanonKind::SpindleStop);
      }
      state_.tool = selected_tool_;
      params_.at(param::kToolNumber) = state_.tool;
      emit_simple(CanonKind::ChangeTool, state_.tool);
    } else if (m == 61) {
      if (v.has('q')) state_.tool = selected_tool_ = int(std::lround(*v['q']));
    }
  }
  // 8. Spindle.
  for (int m : v.m) {
    if (m == 3) state_.spindle = SpindleDir::Clockwise, emit_simple(CanonKind::SpindleClockwise);
    if (m == 4)
      state_.spindle = SpindleDir::CounterClockwise,
      emit_simple(CanonKind::SpindleCounterClockwise);
    if (m == 5) state_.spindle = SpindleDir::Off, emit_simple(CanonKind::SpindleStop);
  }
  // 9. Coolant.
  for (int m : v.m) {
    if (m == 7) state_.mist = true, emit_simple(CanonKind::MistOn);
    if (m == 8) state_.flood = true, emit_simple(CanonKind::FloodOn);
    if (m == 9) {
      if (state_.mist) emit_simple(CanonKind::MistOff);
      if (state_.flood) emit_simple(CanonKind::FloodOff);
      state_.mist = state_.flood = false;
    }
  }
  for (int m : v.m) {
    switch (m) {
    case 0:
    case 1:
    case 2:
    case 30:
    case 60:
    case 3:
    case 4:
    case 5:
    case 6:
    case 7:
    case 8:
    case 9:
    case 61:
    case 98:
    case 99:
    case 97:
      break;
    case 48:
    case 49:
    case 50:
    case 51:
    case 52:
    case 53:
    case 62:
    case 63:
    case 64:
    case 65:
    case 66:
    case 67:
    case 68:
    case 70:
    case 71:
    case 72:
    case 73:
    case 19:
    case 29:
      break; // overrides, I/O, state save, spindle orient: no motion, no time of their own
    default:
      if (m >= 100 && m <= 199)
        note(v.column['m' - 'a'], "user M code M" + std::to_string(m) + ": no time counted");
      else
        warning(v.column['m' - 'a'],
                "unknown or unsupported code M" + std::to_string(m) + ": ignored");
    }
  }
  // 10. Dwell.
  if (has_g(v, 40)) {
    double seconds = 0;
    if (dialect_.dwell_s_word && v.has('s') && !v.has('p')) {
      seconds = *v['s']; // Marlin, RepRapFirmware: G4 S in seconds
    } else if (v.has('p')) {
      const double p = *v['p'];
      const bool integer_p = std::abs(p - std::round(p)) < 1e-9;
      if (dialect_.dwell_p_in_ms ||
          (dialect_.dwell_p_integer_is_ms && integer_p && b.code.find('.', 0) == std::string::npos))
        seconds = p / 1000.0;
      else
        seconds = p;
    } else if (dialect_.dwell_x_word && v.has('x')) {
      seconds = *v['x'];
    } else {
      error(v.g_column(40), "G4 needs a P word (dwell time)");
    }
    if (seconds < 0) error(v.g_column(40), "negative dwell time"), seconds = 0;
    CanonCommand c = make(CanonKind::Dwell);
    c.value = seconds;
    emit(std::move(c));
  }
  // 11. Plane, 12. units.
  for (int code : v.g) {
    Plane p = state_.plane;
    if (code == 170) p = Plane::XY;
    if (code == 180) p = Plane::XZ;
    if (code == 190) p = Plane::YZ;
    if (p != state_.plane) state_.plane = p, emit_simple(CanonKind::PlaneSelect);
    if (code == 200 || code == 210) {
      const bool inch = code == 200;
      if (inch != state_.inch) {
        state_.inch = inch;
        emit_simple(CanonKind::LengthUnits);
      }
    }
  }
  // 13. Cutter compensation.
  for (int code : v.g) {
    if (code == 400) cutter_comp_ = 40;
    if (code == 410 || code == 420 || code == 411 || code == 421) {
      cutter_comp_ = code / 10;
      warning(v.g_column(code), g_name(code) + " cutter radius compensation is not modelled: "
                                               "moves are taken as programmed (tool centre on "
                                               "the programmed path)");
    }
  }
  // 14. Tool length offset.
  for (int code : v.g) {
    double offset = tool_offset_z_;
    if (code == 430) {
      const int h = v.has('h') ? int(std::lround(*v['h'])) : state_.tool;
      auto it = tools_.find(h);
      offset = it != tools_.end() ? it->second.z_offset : 0.0;
      if (it == tools_.end() && h != 0 && !tools_.empty())
        warning(v.g_column(code), "tool " + std::to_string(h) + " is not in the tool table");
    } else if (code == 431) {
      offset = v.has('z') ? *v['z'] * unit() : 0.0;
      v.letter['z' - 'a'].reset();
    } else if (code == 490) {
      offset = 0;
    } else {
      continue;
    }
    // The program's Z stays where it was (as rs274 reports it); the offset shows on G53 moves.
    tool_offset_z_ = offset;
    CanonCommand c = make(CanonKind::ToolLengthOffset);
    c.value = offset;
    emit(std::move(c));
  }
  // 15. Coordinate system.
  for (int code : v.g) {
    int index = 0;
    if (code >= 540 && code <= 590 && code % 10 == 0) index = (code - 530) / 10;
    if (code >= 591 && code <= 593) index = 6 + (code - 590);
    if (!index) continue;
    const Pose old = g5x_[g5x_index_], neu = g5x_[index];
    pos_.x += old.x - neu.x, pos_.y += old.y - neu.y, pos_.z += old.z - neu.z;
    pos_.a += old.a - neu.a, pos_.b += old.b - neu.b, pos_.c += old.c - neu.c;
    g5x_index_ = index;
    params_.at(param::kCoordSystem) = index;
    CanonCommand c = make(CanonKind::WorkOffset);
    c.value = index;
    c.end = neu;
    emit(std::move(c));
  }
  // 16. Path control.
  for (int code : v.g) {
    if (code == 610 || code == 611) {
      state_.path_mode = code == 610 ? PathMode::ExactPath : PathMode::ExactStop;
      state_.path_tolerance = 0;
      emit_simple(CanonKind::PathControl);
    } else if (code == 640) {
      state_.path_mode = PathMode::Continuous;
      state_.path_tolerance = v.has('p') ? *v['p'] * unit() : 0;
      // value: LinuxCNC's naive-CAM tolerance, Q, else P, else none (SET_NAIVECAM_TOLERANCE).
      naivecam_tolerance_ = v.has('q') ? *v['q'] * unit() : state_.path_tolerance;
      emit_simple(CanonKind::PathControl, naivecam_tolerance_);
    }
  }
  // 17. Distance modes, 18. retract mode.
  for (int code : v.g) {
    if (code == 900) incremental_ = false;
    if (code == 910) incremental_ = true;
    if (code == 901) arc_incremental_ = false;
    if (code == 911) arc_incremental_ = true;
    if (code == 980) retract_to_r_ = false;
    if (code == 990) retract_to_r_ = true;
  }
  // 19. Home, coordinate data, axis offsets (non-modal group 0).
  bool axes_used = false;
  for (int code : v.g) {
    switch (code) {
    case 280:
      go_home(v, param::kG28), axes_used = true;
      break;
    case 300:
      go_home(v, param::kG30), axes_used = true;
      break;
    case 281:
    case 301: {
      const int base = code == 281 ? param::kG28 : param::kG30;
      const Pose off = offset_total();
      params_.at(base) = pos_.x + off.x;
      params_.at(base + 1) = pos_.y + off.y;
      params_.at(base + 2) = pos_.z + off.z + tool_offset_z_;
      params_.at(base + 3) = pos_.a + off.a;
      params_.at(base + 4) = pos_.b + off.b;
      params_.at(base + 5) = pos_.c + off.c;
      break;
    }
    case 100:
      axes_used = true;
      if (v.has('l') && (std::lround(*v['l']) == 2 || std::lround(*v['l']) == 20))
        set_coordinate_data(v);
      else
        set_tool_data(v);
      break;
    case 920:
    case 921:
    case 922:
    case 923:
      if (code == 920) axes_used = true;
      set_axis_offsets(v);
      break;
    default:
      break;
    }
  }
  // 20. Motion.
  for (int code : v.g) {
    if (g_group(code) != 1) continue;
    // A series of cycles ends with any motion code that is not a cycle (G80 included); one
    // cycle code after another (G81 then G82) goes on with the same series.
    const bool cycle = code == 730 || code == 740 || (code >= 810 && code <= 890);
    if (!cycle) have_cycle_initial_height_ = false;
    motion_ = Motion(code);
  }
  const bool g53 = has_g(v, 530);
  const bool motion_word_given =
      std::any_of(v.g.begin(), v.g.end(), [](int c) { return g_group(c) == 1; });
  if (dialect_.o_word_subroutines && (has_g(v, 50) || has_g(v, 51))) {
    spline(v, has_g(v, 51));
    axes_used = true;
  }
  if (!axes_used && (v.has_axis() || (motion_word_given && motion_ != Motion::None))) {
    switch (motion_) {
    case Motion::Rapid:
      straight(CanonKind::Traverse, target_from_words(v, g53));
      break;
    case Motion::Linear:
      if (state_.feed_mode == FeedMode::InverseTime && !v.has('f') && v.has_axis())
        error(v.column['g' - 'a'], "G93 inverse time: a feed move needs an F word");
      else if (state_.feed <= 0 && v.has_axis())
        error(v.column['g' - 'a'], "feed move with no feed rate (F word missing or zero)");
      if (v.has_axis()) {
        const Pose end = target_from_words(v, g53);
        CanonCommand probe_length = make(CanonKind::Feed);
        probe_length.end = end;
        inverse_time_feed(move_length(probe_length), v);
        straight(CanonKind::Feed, end);
      }
      break;
    case Motion::ArcCW:
    case Motion::ArcCCW:
      if (v.has_axis() || v.has('i') || v.has('j') || v.has('k') || v.has('r')) {
        rotate_arc_offsets(v);
        if (state_.feed <= 0) error(v.column['g' - 'a'], "arc with no feed rate (F word missing)");
        arc(v, motion_ == Motion::ArcCW);
      }
      break;
    case Motion::Probe:
    case Motion::Probe3:
    case Motion::Probe4:
    case Motion::Probe5:
      if (v.has_axis()) probe(target_from_words(v, false));
      break;
    case Motion::SpindleSynced:
    case Motion::RigidTap:
      if (v.has_axis()) spindle_synced(v);
      break;
    case Motion::None:
      if (v.has_axis())
        error(v.column['x' - 'a'] ? v.column['x' - 'a'] : 0,
              "axis words with no motion mode (after G80): ignored");
      break;
    case Motion::Threading:
      if (v.has_axis() || motion_word_given)
        warning(v.g_column(760), "G76 threading cycle is not supported: skipped");
      break;
    default:
      if (v.has_axis())
        canned_cycle(motion_, v);
      else if (motion_word_given) {
        // A cycle code alone sets the mode (and its sticky values) without drilling.
        if (v.has('r')) cycle_r_ = *v['r'], have_cycle_r_ = true;
        if (v.has('z')) cycle_z_ = *v['z'], have_cycle_z_ = true;
      }
      break;
    }
  }
  // 20b. Sinumerik cycles: one called in this block, or the MCALL cycle after a positioning.
  if (cycle_now)
    sinumerik_cycle(*cycle_now);
  else if (modal_cycle_ && positioning && v.has_axis())
    sinumerik_cycle(*modal_cycle_);
  // 21. Stops and subprogram calls (Fanuc, Haas).
  for (int m : v.m) {
    if (m == 29) rigid_tapping_ = true; // Fanuc/Haas rigid tapping mode for G84/G74
    if (m == 0) emit_simple(CanonKind::ProgramStop);
    if (m == 1) emit_simple(CanonKind::OptionalStop);
    if (m == 60) emit_simple(CanonKind::ProgramStop);
    if (m == 2 || m == 30) {
      emit_simple(CanonKind::ProgramEnd);
      finished_ = true;
      result_.completed = true;
    }
    if (m == 98 || m == 97) {
      if (!v.has('p')) {
        error(v.column['m' - 'a'], "M" + std::to_string(m) + " needs a P word");
        continue;
      }
      long p = std::lround(*v['p']);
      int repeats = v.has('l') ? int(std::lround(*v['l'])) : 1;
      std::optional<std::size_t> target;
      if (m == 98) {
        if (!v.has('l') && p > 9999 && !program_numbers_.count(p)) {
          repeats = int(p / 10000); // Fanuc P<repeats:3><program:4>
          p %= 10000;
        }
        auto it = program_numbers_.find(p);
        if (it != program_numbers_.end()) target = it->second;
      } else {
        if (!n_numbers_) {
          n_numbers_.emplace();
          for (std::size_t i = 0; i < source_.lines.size(); ++i) {
            std::string_view l = source_.line_text(i);
            std::size_t k = l.find_first_not_of(" \t/");
            if (k == std::string_view::npos || (l[k] != 'n' && l[k] != 'N')) continue;
            long num = 0;
            bool any = false;
            for (++k; k < l.size() && std::isdigit(static_cast<unsigned char>(l[k])); ++k)
              num = num * 10 + (l[k] - '0'), any = true;
            if (any) n_numbers_->emplace(num, i);
          }
        }
        auto it = n_numbers_->find(p);
        if (it != n_numbers_->end()) target = it->second - 1; // N line itself is the body start
      }
      if (!target) {
        error(v.column['p' - 'a'], (m == 98 ? "subprogram O" : "local subprogram N") +
                                       std::to_string(p) + " is not in this file: call skipped");
        continue;
      }
      if (repeats > 0) call_subroutine(*target, {}, true, repeats);
    }
    if (m == 99) {
      if (frames_.empty()) {
        note(v.column['m' - 'a'], "M99 in the main program: it would restart the program; "
                                  "counted once and ended here");
        emit_simple(CanonKind::ProgramEnd);
        finished_ = true;
        result_.completed = true;
      } else {
        return_from_subroutine(std::nullopt);
      }
    }
  }
}

void Interpreter::macro_call(const BlockValues& v) {
  // G65 P<program> L<repeats>: every other letter is an argument (A=#1, B=#2, C=#3, I=#4, J=#5,
  // K=#6, D=#7, ...), not an axis, feed or speed.
  if (!v.has('p')) {
    error(v.g_column(650), "G65 needs a P word (macro program number)");
    return;
  }
  auto it = program_numbers_.find(std::lround(*v['p']));
  if (it == program_numbers_.end()) {
    error(v.column['p' - 'a'], "macro program O" + std::to_string(std::lround(*v['p'])) +
                                   " is not in this file: call skipped");
    return;
  }
  static constexpr std::pair<char, int> map[] = {
      {'a', 1},  {'b', 2},  {'c', 3},  {'i', 4},  {'j', 5},  {'k', 6},  {'d', 7},
      {'e', 8},  {'f', 9},  {'h', 11}, {'m', 13}, {'q', 17}, {'r', 18}, {'s', 19},
      {'t', 20}, {'u', 21}, {'v', 22}, {'w', 23}, {'x', 24}, {'y', 25}, {'z', 26}};
  std::vector<double> args(26, 0.0);
  for (auto [letter, index] : map)
    if (v.has(letter)) args[index - 1] = *v[letter];
  const int repeats = v.has('l') ? int(std::lround(*v['l'])) : 1;
  call_subroutine(it->second, std::move(args), true, repeats);
}

// ------------------------------------------------------------------------------------------

} // namespace ncjoule::detail

namespace ncjoule {

InterpretResult interpret(const SourceFile& source, const InterpreterOptions& options,
                          const CanonSink& sink) {
  detail::Interpreter interpreter(source, options, sink);
  return interpreter.run();
}

Toolpath interpret(const SourceFile& source, const InterpreterOptions& options) {
  Toolpath path;
  const CanonSink sink = [&path](const CanonCommand& c) { path.commands.push_back(c); };
  path.result = interpret(source, options, sink);
  return path;
}

} // namespace ncjoule
