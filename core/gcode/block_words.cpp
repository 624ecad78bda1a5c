// A block's words: their values (expressions evaluated, parameters assigned as rs274ngc does)
// and the check of its G codes' modal groups, as the dialect's control has them.
#include "interpreter_impl.hpp"

#include <algorithm>
#include <cmath>

#include "codes.hpp"
#include "expression.hpp"
#include "value_limits.hpp"

namespace ncjoule::detail {

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
    const char up = w.letter >= 'a' && w.letter <= 'z' ? char(w.letter - 'a' + 'A') : w.letter;
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
  // Values beyond what any control takes (value_limits.hpp), in the units the block itself
  // may set.
  bool inch = state_.inch;
  if (has_g(v, 200) || (dialect_.g70_g71_units && (has_g(v, 700) || has_g(v, 7000))))
    inch = true;
  else if (has_g(v, 210) || (dialect_.g70_g71_units && (has_g(v, 710) || has_g(v, 7100))))
    inch = false;
  for (int s = 0; s < int(v.letter.size()); ++s) {
    if (!v.letter[s]) continue;
    const char letter = s == slot('@') ? '@' : s == slot('^') ? '^' : char('a' + s);
    if (auto why = word_out_of_range(letter, *v.letter[s], inch)) {
      error(v.column[s], std::move(*why));
      ok = false;
    }
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
    if (!(a.bare_expression ? evaluate_bare : evaluate)(a.value, params_, w.value, err, off)) {
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

bool Interpreter::check_modal_groups(BlockValues& v) {
  // G80 beside another motion code: the other code counts (rs274 runs "G0 G80 G90 ..." so, and
  // posts write it in their safety line).
  const auto motion_codes =
      std::count_if(v.g.begin(), v.g.end(), [](int code) { return g_group(code) == 1; });
  if (motion_codes > 1 && has_g(v, 800)) std::erase(v.g, 800);
  // G28/G30 already move in machine coordinates: a G53 beside them ("G91 G28 G53 Z0") adds
  // nothing. LinuxCNC refuses the pair (two codes of group 0); the evident reading is kept.
  if (has_g(v, 530) && (has_g(v, 280) || has_g(v, 300))) {
    warning(v.g_column(530), "G53 with G28/G30 on one line: G53 is ignored (the return to home "
                             "is in machine coordinates already; LinuxCNC refuses the pair)");
    std::erase(v.g, 530);
  }
  int seen[16] = {};
  bool ok = true;
  std::vector<int> overridden;
  for (int code : v.g) {
    const int group = g_group(code);
    if (group < 0) continue;
    if (seen[group]) {
      const std::string pair = g_name(seen[group] - 1) + " and " + g_name(code);
      if (dialect_.last_code_of_group_wins || !strict_) {
        // Fanuc: the last code of a group in a block is the one that counts.
        warning(v.g_column(code),
                "two G codes of the same modal group on one line: " + pair +
                    "; the last one counts" +
                    (dialect_.last_code_of_group_wins ? "" : " (LinuxCNC would refuse the block)"));
        overridden.push_back(seen[group] - 1);
      } else {
        error(v.g_column(code), "two G codes of the same modal group on one line: " + pair);
        ok = false;
      }
    }
    seen[group] = code + 1;
  }
  for (int code : overridden)
    v.g.erase(std::find(v.g.begin(), v.g.end(), code));
  return ok;
}

} // namespace ncjoule::detail
