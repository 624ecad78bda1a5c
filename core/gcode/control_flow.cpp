// Control flow: LinuxCNC's O-words (sub/call/return, if/elseif/else, while, do-while, repeat,
// break/continue) and the subprogram calls of the Fanuc family (M98/M99, Haas M97, G65).
#include "interpreter_impl.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "codes.hpp"
#include "expression.hpp"

namespace ncjoule::detail {

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

// What a warning about a program not found adds when folders of the control's programs were
// searched too.
std::string Interpreter::not_in_folders() const {
  return options_.control_programs ? " nor in the macro folders" : "";
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
  if (kw.empty()) return; // a Fanuc O-number program header: nothing to do
  if (!dialect_.o_word_subroutines) {
    warning(b.o_column, "O-word '" + kw + "' is LinuxCNC syntax, not of the " + dialect_.name +
                            " dialect; interpreted as LinuxCNC would");
  }
  if (kw == "sub")
    o_sub(b);
  else if (kw == "endsub" || kw == "return")
    o_return(b);
  else if (kw == "call")
    o_call(b);
  else if (kw == "if" || kw == "elseif" || kw == "else" || kw == "endif")
    o_if(b);
  else if (kw == "do" || kw == "while" || kw == "endwhile")
    o_while(b);
  else if (kw == "repeat" || kw == "endrepeat")
    o_repeat(b);
  else if (kw == "break" || kw == "continue")
    o_break_or_continue(b);
  else
    error(b.o_column, "unknown O-word keyword '" + kw + "'");
}

void Interpreter::o_sub(const Block& b) {
  // A definition met in the flow of the program: skip its body.
  auto end = find_next(b.o_label, pc_, {"endsub"});
  if (!end) {
    error(b.o_column, "o" + b.o_label + " sub has no matching endsub");
    stop();
    return;
  }
  next_pc_ = *end + 1;
}

void Interpreter::o_return(const Block& b) {
  if (frames_.empty()) {
    if (b.o_keyword == "return")
      warning(b.o_column, "o" + b.o_label + " return outside a subroutine: ignored");
    return;
  }
  std::optional<double> value;
  if (!b.o_args.empty()) {
    double v;
    if (eval_condition(b.o_args, b.o_column, v)) value = v;
  }
  return_from_subroutine(value);
}

void Interpreter::o_call(const Block& b) {
  const std::string& label = b.o_label;
  const int col = b.o_column;
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
  std::optional<std::size_t> sub = labels_.last(label, "sub");
  if (!sub && label.size() > 2 && label.front() == '<' &&
      load_control_program(label.substr(1, label.size() - 2)))
    sub = labels_.last(label, "sub");
  if (!sub) {
    // LinuxCNC finds o<name> in a file on the config's SUBROUTINE_PATH: the program runs.
    warning(col, "subroutine o" + label + " is not defined in this file" + not_in_folders() +
                     ": the control reads it from its subroutine "
                     "path; its time is not counted (call skipped)");
    return;
  }
  call_subroutine(*sub, std::move(args), false, 1);
}

void Interpreter::o_if(const Block& b) {
  const std::string& kw = b.o_keyword;
  const std::string& label = b.o_label;
  if (kw == "endif") return; // flow goes on
  if (kw == "elseif" || kw == "else") {
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
    if (!eval_condition(args, b.o_column, v)) return;
    if (v != 0) {
      next_pc_ = at + 1;
      return;
    }
    auto branch = find_next(label, at, {"elseif", "else", "endif"});
    if (!branch) {
      error(b.o_column, "o" + label + " if has no matching endif");
      stop();
      return;
    }
    lex_line(line_text(*branch), dialect_, other);
    if (other.o_keyword == "elseif") {
      at = *branch;
      args = other.o_args;
      continue;
    }
    next_pc_ = *branch + 1;
    return;
  }
}

void Interpreter::o_while(const Block& b) {
  const std::string& kw = b.o_keyword;
  const std::string& label = b.o_label;
  const int col = b.o_column;
  if (kw == "do") return; // flow goes on into the body
  if (kw == "endwhile") {
    auto head = find_prev(label, pc_, {"while"});
    if (!head) {
      error(col, "o" + label + " endwhile has no matching while");
      return;
    }
    next_pc_ = *head;
    return;
  }
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
}

void Interpreter::o_repeat(const Block& b) {
  const std::string& label = b.o_label;
  const int col = b.o_column;
  auto& counters = frames_.empty() ? top_repeat_counters_ : frames_.back().repeat_counters;
  if (b.o_keyword == "endrepeat") {
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
    return;
  }
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
}

void Interpreter::o_break_or_continue(const Block& b) {
  auto end = find_next(b.o_label, pc_, {"endwhile", "endrepeat", "while"});
  if (!end) return;
  if (b.o_keyword == "continue") {
    next_pc_ = *end;
    return;
  }
  auto& counters = frames_.empty() ? top_repeat_counters_ : frames_.back().repeat_counters;
  if (auto head = find_prev(b.o_label, pc_, {"repeat"})) counters.erase(*head);
  next_pc_ = *end + 1;
}

// ------------------------------------------------------------------------------------------
// Fanuc family: M98 P<program> L<repeats>, Haas M97 P<N-number>, M99, G65 macro calls
// ------------------------------------------------------------------------------------------

void Interpreter::macro_call(const BlockValues& v) {
  // G65 P<program> L<repeats>: every other letter is an argument (A=#1, B=#2, C=#3, I=#4, J=#5,
  // K=#6, D=#7, ...), not an axis, feed or speed.
  if (!v.has('p')) {
    error(v.g_column(650), "G65 needs a P word (macro program number)");
    return;
  }
  auto it = program_numbers_.find(std::lround(*v['p']));
  if (it == program_numbers_.end() && load_control_program(std::to_string(std::lround(*v['p']))))
    it = program_numbers_.find(std::lround(*v['p']));
  if (it == program_numbers_.end()) {
    // Probing and shop macros (O9000-O9999, Renishaw's O9810...) live in the control's memory:
    // the program runs; only this call's time is unknown.
    warning(v.column['p' - 'a'], "macro program O" + std::to_string(std::lround(*v['p'])) +
                                     " is not in this file" + not_in_folders() +
                                     ": the control holds it; its time is "
                                     "not counted (call skipped)");
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

std::optional<std::size_t> Interpreter::n_number_line(long n_number) {
  if (!n_numbers_) {
    n_numbers_.emplace();
    for (std::size_t i = 0; i < line_count_; ++i) {
      std::string_view l = line_text(i);
      std::size_t k = l.find_first_not_of(" \t/");
      if (k == std::string_view::npos || (l[k] != 'n' && l[k] != 'N')) continue;
      const std::size_t first = ++k;
      while (k < l.size() && std::isdigit(static_cast<unsigned char>(l[k])))
        ++k;
      // A number too long for a long is no call target (nothing can call it).
      long num = 0;
      const auto [end, ec] = std::from_chars(l.data() + first, l.data() + k, num);
      if (k > first && ec == std::errc() && end == l.data() + k) (*n_numbers_)[num].push_back(i);
    }
    for (const auto& [number, line] : program_numbers_)
      program_starts_.push_back(line);
    std::sort(program_starts_.begin(), program_starts_.end());
  }
  auto it = n_numbers_->find(n_number);
  if (it == n_numbers_->end()) return std::nullopt;
  // The control searches the program it runs: prefer the N block between the O-number headers
  // around the current line (a file's subprograms reuse N numbers).
  const auto next = std::upper_bound(program_starts_.begin(), program_starts_.end(), pc_);
  const std::size_t from = next == program_starts_.begin() ? 0 : *(next - 1);
  const std::size_t to = next == program_starts_.end() ? line_count_ : *next;
  for (std::size_t line : it->second)
    if (line >= from && line < to) return line;
  return it->second.front();
}

void Interpreter::fanuc_call(const BlockValues& v, int m) {
  if (!v.has('p')) {
    error(v.column['m' - 'a'], "M" + std::to_string(m) + " needs a P word");
    return;
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
    if (it == program_numbers_.end() && load_control_program(std::to_string(p)))
      it = program_numbers_.find(p);
    if (it != program_numbers_.end()) target = it->second;
  } else {
    target = n_number_line(p);
    if (target) --*target; // the N line itself is the body's first line
  }
  if (!target && m == 98) {
    // A subprogram in the control's memory (O8000-O9999 and the shop's own): the program runs.
    warning(v.column['p' - 'a'], "subprogram O" + std::to_string(p) + " is not in this file" +
                                     not_in_folders() +
                                     ": the control holds it; its time is "
                                     "not counted (call skipped)");
    return;
  }
  if (!target) { // M97's N block must be in this program: the control stops with an alarm
    error(v.column['p' - 'a'],
          "local subprogram N" + std::to_string(p) + " is not in this file: call skipped");
    return;
  }
  if (repeats > 0) call_subroutine(*target, {}, true, repeats);
}

void Interpreter::fanuc_return(const BlockValues& v) {
  if (!frames_.empty()) {
    return_from_subroutine(std::nullopt);
    return;
  }
  note(v.column['m' - 'a'], "M99 in the main program: it would restart the program; "
                            "counted once and ended here");
  emit_simple(CanonKind::ProgramEnd);
  finished_ = true;
  result_.completed = true;
}

} // namespace ncjoule::detail
