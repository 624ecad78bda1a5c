// The interpreter's main loop: reads a block at a time and hands it to control flow
// (control_flow.cpp) or to the block's execution in LinuxCNC's order (convert*.cpp); reports and
// emits for them.
#include "interpreter_impl.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "codes.hpp"
#include "ncjoule/budget.hpp"
#include "value_limits.hpp"

namespace ncjoule::detail {

int BlockValues::g_column(int code) const {
  for (auto& [c, col] : g_columns)
    if (c == code) return col;
  return column['g' - 'a'];
}

Interpreter::Interpreter(const SourceFile& source, const InterpreterOptions& options,
                         const CanonSink& sink)
    : source_(source), options_(options), sink_(sink), tools_(options.tools) {
  line_count_ = source.lines.size();
  DialectChoice choice = options.same_choice_as_before ? *options.same_choice_as_before
                         : options.dialect
                             ? DialectChoice{*options.dialect, DialectOrigin::Given, "given"}
                             : choose_dialect(source);
  if (choice.origin == DialectOrigin::Default && options.fallback_dialect &&
      !options.same_choice_as_before)
    choice = {*options.fallback_dialect, DialectOrigin::Given,
              "the machine's control; nothing in the program names another"};
  dialect_ = choice.dialect;
  // With no dialect named or recognised, what only LinuxCNC refuses is a warning: the program
  // may well be written for another control.
  strict_ = choice.origin != DialectOrigin::Default;
  result_.dialect = dialect_;
  result_.dialect_origin = choice.origin;
  result_.dialect_reason = choice.reason;
  // Nor is a letter alone or text after a number: Marlin reads "G28 Z" and "M0 Turn ON
  // spindle" (an MPCNC post's prompts). The letter O inside a number stays an error.
  if (!strict_) dialect_.lenient_words = true;
  retract_to_r_ = dialect_.retract_to_r_by_default;
  arc_incremental_ = !dialect_.arc_centre_absolute;
  params_.set_system_lookup(
      [this](std::string_view name, double& value) { return system_parameter(name, value); });
  for (const auto& [index, origin] : options.work_offsets) {
    if (index < 1 || index > 9 + kAdditionalWorkOffsets) continue;
    g5x_[std::size_t(index)] = origin;
    const double values[6] = {origin.x, origin.y, origin.z, origin.a, origin.b, origin.c};
    // Parameters hold G54..G59.3 only (LinuxCNC's 5602; Fanuc's #7001.. for G54.1 are beyond).
    const int first = index <= 9 ? param::kG54 + 20 * (index - 1) : 0;
    for (int i = 0; first && i < 6; ++i)
      params_.at(first + i) = values[i];
  }
  state_.inch = options.start_inch;
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
    return value = g5x_index_ <= 6   ? 530 + 10 * g5x_index_
                   : g5x_index_ <= 9 ? 590 + (g5x_index_ - 6)
                                     : 541,
           true;
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
  if (severity == Severity::Error) error_reported_ = true;
  if (!options_.keep_diagnostics) return;
  // Past the cap only one more error is kept, so that the run still fails as it must; memory
  // and output stay bounded whatever the program repeats.
  if (result_.diagnostics.size() > kMaxDiagnostics &&
      (severity != Severity::Error || error_past_cap_))
    return;
  const ReportedView key(current_line_, column, message);
  const auto at = reported_.lower_bound(key);
  if (at != reported_.end() && !ReportedOrder{}(key, *at)) return; // given before
  reported_.emplace_hint(at, current_line_, column, message);
  if (result_.diagnostics.size() == kMaxDiagnostics) {
    result_.diagnostics.push_back({Severity::Warning, source_.path, current_line_ + 1, 0,
                                   "too many diagnostics: the rest are not shown"});
    if (auto [file, local] = locate(std::size_t(current_line_)); file != &source_)
      result_.diagnostics.back().file = file->path,
      result_.diagnostics.back().line = int(local) + 1;
  }
  if (result_.diagnostics.size() > kMaxDiagnostics && severity == Severity::Error)
    error_past_cap_ = true;
  const auto [file, local] = locate(std::size_t(current_line_));
  result_.diagnostics.push_back({severity, file->path, int(local) + 1, column, std::move(message)});
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
  // A program of the control's memory has no lines in the file: its commands are the call's.
  c.line = std::size_t(current_line_) < source_.lines.size() ? current_line_ : current_call_line_;
  c.call_line = current_call_line_;
  c.state = state_;
  c.plane = state_.plane;
  c.start = pos_;
  c.end = pos_;
  return c;
}

void Interpreter::emit(CanonCommand c) {
  ++command_count_;
  // The budget of moves (budget.hpp): counted per command, checked here once for every way a
  // program has to make them (loops, canned cycles' L, splines, arcs' turns, calls). A stopped
  // run's InterpretResult::commands is over max_commands: how its callers tell the stop.
  if (options_.max_commands && command_count_ > options_.max_commands) {
    if (!finished_)
      error(0, budget_message("moves", double(options_.max_commands), "max-moves", "max_moves"));
    stop();
    return;
  }
  // The last check before the planner: what words in range still made out of range (a G91
  // sum, a cycle's arguments, a frame) is refused here, the machine staying where it was.
  if (auto why = command_out_of_range(c)) {
    error(block_.columns.empty() ? 0 : block_.columns.front(), std::move(*why));
    if (is_move(c.kind)) pos_ = c.start;
    return;
  }
  if (is_move(c.kind)) {
    c.start_known = known_axes_ == 7;
    known_axes_ |= axes_being_set_;
  }
  // Cutter radius compensation holds a move until the next one shows its corner, and with it
  // whatever comes after it (cutter_comp_moves.cpp).
  if (comp_next_) {
    CompQueue::Held held = std::move(*comp_next_);
    comp_next_.reset();
    held.command = std::move(c);
    comp_.queue.hold(std::move(held));
    return;
  }
  if (!comp_.queue.empty()) {
    comp_.queue.hold({std::move(c), {}, 0});
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

std::string_view Interpreter::line_text(std::size_t line) const {
  const auto [file, local] = locate(line);
  return file->line_text(local);
}

std::pair<const SourceFile*, std::size_t> Interpreter::locate(std::size_t line) const {
  if (line < source_.lines.size() || control_starts_.empty()) return {&source_, line};
  const auto next = std::upper_bound(control_starts_.begin(), control_starts_.end(), line);
  const std::size_t k = std::size_t(next - control_starts_.begin()) - 1;
  return {&control_sources_[k], line - control_starts_[k]};
}

bool Interpreter::load_control_program(const std::string& name) {
  if (!options_.control_programs || !control_names_tried_.insert(name).second) return false;
  std::optional<SourceFile> program = options_.control_programs(name);
  if (!program || program->lines.empty()) return false;
  const std::size_t start = line_count_;
  control_starts_.push_back(start);
  control_sources_.push_back(std::move(*program));
  line_count_ += control_sources_.back().lines.size();
  scan_labels(start);
  // A file of the control's memory may hold the program without its O-number line: it starts at
  // the file's first line.
  long number = 0;
  const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), number);
  if (ec == std::errc() && end == name.data() + name.size() && start > 0)
    program_numbers_.emplace(number, start - 1);
  n_numbers_.reset(); // GOTO and M97 targets: indexed again with the new lines
  program_starts_.clear();
  return true;
}

void Interpreter::scan_labels(std::size_t from) {
  // Only lines that begin (after blanks, '/', an N number) with 'o' can hold O-words.
  Block b;
  for (std::size_t i = from; i < line_count_; ++i) {
    std::string_view l = line_text(i);
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
      // A program number; one too long for a long (O1111...1) can be no M98 P target.
      long number = 0;
      const char* first = b.o_label.data();
      const char* last = first + b.o_label.size();
      const auto [end, ec] = std::from_chars(first, last, number);
      if (ec == std::errc() && end != first) program_numbers_.emplace(number, i);
    } else {
      labels_.add(b.o_label, b.o_keyword, i);
    }
  }
}

std::optional<std::size_t> Interpreter::find_next(const std::string& label, std::size_t after,
                                                  std::initializer_list<const char*> keys) const {
  return labels_.next(label, after, keys);
}

std::optional<std::size_t> Interpreter::find_prev(const std::string& label, std::size_t before,
                                                  std::initializer_list<const char*> keys) const {
  return labels_.previous(label, before, keys);
}

InterpretResult Interpreter::run() {
  scan_labels();
  BlockValues values;
  while (!finished_ && pc_ < line_count_) {
    current_line_ = int(pc_);
    current_call_line_ = frames_.empty() ? int(pc_) : frames_.front().call_line;
    next_pc_ = pc_ + 1;
    lex_line(line_text(pc_), dialect_, block_);
    for (Diagnostic& d : block_.warnings)
      report(d.severity, d.column, std::move(d.message));
    if (!block_.errors.empty()) {
      error_reported_ = true;
      const auto [file, local] = locate(pc_);
      for (Diagnostic& d : block_.errors) {
        if (!options_.keep_diagnostics) break;
        d.file = file->path;
        d.line = int(local) + 1;
        result_.diagnostics.push_back(std::move(d));
      }
      note(0, "block skipped");
    } else if (block_.percent && dialect_.percent_alone && !block_.percent_bare) {
      // "% vfd enable", "%(start)", "N10 %": LinuxCNC refuses the line. Taken as the program's
      // end, it would cut the rest of the program silently; read as a comment, it is said.
      if (strict_)
        error(block_.percent_column, "bad character '%': a '%' line holds nothing else");
      else
        warning(block_.percent_column,
                "a '%' line with more on it: LinuxCNC refuses it, other controls start or end "
                "the program there; read as a comment, the program goes on");
    } else if (block_.percent) {
      // A '%' opens the program; the next one closes it (LinuxCNC, Fanuc tape format). A name
      // after it ("%prog1", "%PM") names the program; Heidenhain's "%NAME G71" gives its units.
      if (seen_percent_) finished_ = true, result_.completed = true;
      seen_percent_ = true;
      if (dialect_.g70_g71_units && !finished_) {
        const std::string_view rest = block_.percent_name;
        const bool inch = rest.find("g70") != std::string_view::npos;
        if (inch || rest.find("g71") != std::string_view::npos) units_given_ = true;
        if ((inch || rest.find("g71") != std::string_view::npos) && inch != state_.inch) {
          state_.inch = inch;
          emit_simple(CanonKind::LengthUnits);
        }
      }
    } else if (block_.dollar || (block_.block_delete && options_.block_delete)) {
      // grbl settings lines and deleted blocks do nothing.
    } else if (block_.has_o) {
      ++result_.blocks;
      ++result_.word_blocks;
      handle_o_word(block_);
    } else if (block_.macro.kind != MacroFlow::None) {
      ++result_.blocks;
      ++result_.word_blocks;
      if (macro_statement(block_) && evaluate_words(block_, values)) execute(block_, values);
    } else if (block_.has_code()) {
      ++result_.blocks;
      if (!block_.words.empty() || !block_.assignments.empty()) ++result_.word_blocks;
      if (evaluate_words(block_, values)) execute(block_, values);
    } else if (!block_.comments.empty()) {
      for (const Comment& c : block_.comments) {
        std::string_view t = c.text;
        std::string lowered(t.substr(0, 4));
        for (char& ch : lowered)
          ch = char(std::tolower(static_cast<unsigned char>(ch)));
        if (lowered == "msg,") emit_simple(CanonKind::Message, 0, std::string(t.substr(4)));
        commented_tool_change(c);
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
  comp_release();
  if (!finished_ && error_reported_) {
    result_.completed = false;
  } else if (!finished_) {
    const std::size_t n = source_.lines.size();
    current_line_ = n ? int(n - 1) : 0;
    if (dialect_.end_code_optional)
      note(0, "the program has no M2 or M30: it ends at the end of the file");
    else
      warning(0, "the program has no M2 or M30: it ends at the end of the file");
    result_.completed = true;
  }
  result_.program_end = finished_;
  result_.units_given = units_given_;
  result_.commands = command_count_;
  return std::move(result_); // run() is called once
}

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
