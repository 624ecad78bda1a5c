// Words of several letters. Sinumerik programs are full of them (MCALL, CYCLE81(...), TRANS,
// ROT, SOFT, G642 ...); other controls have a few (Fanuc macro B's GOTO, IF, WHILE). Those with a
// meaning for time are honoured; the rest give a warning and the block runs without them.
//
// Sinumerik references (SINUMERIK 840D sl / 828D Programming Manual, Fundamentals, and
// Job Planning):
// - Programmable frames, "TRANS, ATRANS: translation" and "ROT, AROT: rotation": TRANS X.. Y..
//   Z.. replaces the programmable frame with a shift, ATRANS adds a shift to it, ROT Z<angle>
//   or ROT RPL=<angle> replaces it with a rotation in the working plane, AROT adds one; TRANS or
//   ROT alone clears the whole programmable frame. Blocks with these words do not move.
// - "MCALL: modal subroutine call": MCALL CYCLE81(...) runs the cycle after every following
//   block that moves an axis, until a block with MCALL alone.
// - Continuous-path modes G64, G641, G642, G645, jerk limitation SOFT/BRISK, the compressors
//   COMPON/COMPCURV/COMPCAD/COMPOF, feed forward FFWON/FFWOF and the high-speed setting cycle
//   CYCLE832 change only how blocks are blended: planner hints.
#include <cmath>
#include <numbers>

#include "interpreter_impl.hpp"

#include "ncjoule/text.hpp"

namespace ncjoule::detail {
namespace {

bool is_any(std::string_view name, std::initializer_list<std::string_view> names) {
  for (std::string_view n : names)
    if (name == n) return true;
  return false;
}

// The Sinumerik drilling cycles that expand into moves.
bool is_drilling_cycle(std::string_view name) {
  return is_any(name, {"cycle81", "cycle82", "cycle83", "cycle84", "cycle840", "cycle85", "cycle86",
                       "cycle87", "cycle88", "cycle89"});
}

// Words that only switch something with no time of its own on a milling machine.
bool is_silent(std::string_view name) {
  return is_any(name, {"diamof", "diamon", "supa", "g500", "trafoof", "cfc", "cftcp", "cfin", "ret",
                       "spos", "ori", "oriwks", "oriaxes", "oricurve"});
}

// Words that only change how blocks are blended or how hard the axes accelerate.
bool is_planner_word(std::string_view name) {
  return is_any(name,
                {"soft", "brisk", "drive", "compon", "compcurv", "compcad", "compof", "ffwon",
                 "ffwof", "cycle832", "upath", "spath", "g641", "g642", "g643", "g644", "g645"});
}

} // namespace

std::optional<Interpreter::SinumerikCycle> Interpreter::parse_cycle(const Keyword& k) {
  SinumerikCycle c;
  c.name = std::string(k.name);
  c.line = current_line_;
  c.column = k.column;
  std::string_view args = k.args;
  std::size_t start = 0;
  int depth = 0;
  for (std::size_t i = 0; i <= args.size(); ++i) {
    if (i < args.size() && (args[i] == '(' || args[i] == '[')) ++depth;
    if (i < args.size() && (args[i] == ')' || args[i] == ']')) --depth;
    if (i < args.size() && (args[i] != ',' || depth > 0)) continue;
    std::string_view a = args.substr(start, i - start);
    start = i + 1;
    if (a.empty()) {
      c.args.push_back(std::nullopt);
      continue;
    }
    double value;
    std::string err;
    std::size_t off = 0;
    if (!evaluate(a, params_, value, err, off)) {
      warning(k.column, "argument " + std::to_string(c.args.size() + 1) + " of " +
                            to_upper(k.name) + " ('" + std::string(a) +
                            "') is not a number this interpreter can evaluate: taken as empty");
      c.args.push_back(std::nullopt);
      continue;
    }
    c.args.push_back(value);
  }
  return c;
}

void Interpreter::rotate_arc_offsets(BlockValues& v) const {
  // Under ROT the arc centre offsets I/J are given in the rotated frame.
  if (frame_rotation_deg_ == 0 || state_.plane != Plane::XY || !arc_incremental_) return;
  const double t = frame_rotation_deg_ * std::numbers::pi / 180.0;
  const double i = v['i'].value_or(0), j = v['j'].value_or(0);
  if (!v.has('i') && !v.has('j')) return;
  v.letter[slot('i')] = i * std::cos(t) - j * std::sin(t);
  v.letter[slot('j')] = i * std::sin(t) + j * std::cos(t);
}

void Interpreter::keywords(const Block& b, BlockValues& v,
                           std::optional<SinumerikCycle>& call_now) {
  const bool sinumerik = dialect_.sinumerik_words;
  bool mcall = false;
  for (std::size_t n = 0; n < b.keywords.size(); ++n) {
    const Keyword& k = b.keywords[n];
    const std::string name = to_upper(k.name);
    if (sinumerik && k.name == "mcall") {
      mcall = true;
      // MCALL alone ends the modal call; MCALL followed by a cycle starts one.
      if (n + 1 == b.keywords.size()) modal_cycle_.reset();
      continue;
    }
    if (sinumerik && is_drilling_cycle(k.name)) {
      auto cycle = parse_cycle(k);
      if (!cycle) continue;
      if (mcall)
        modal_cycle_ = std::move(cycle);
      else
        call_now = std::move(cycle);
      continue;
    }
    if (sinumerik && is_any(k.name, {"trans", "atrans"})) {
      const bool add = k.name == "atrans";
      const double u = unit();
      if (!add) {
        frame_shift_ = Pose{};
        if (!v.has('x') && !v.has('y') && !v.has('z')) frame_rotation_deg_ = 0;
      }
      // ATRANS shifts along the axes of the frame as it stands (after its rotation).
      const double t = add ? frame_rotation_deg_ * std::numbers::pi / 180.0 : 0.0;
      const double dx = v['x'].value_or(0) * u, dy = v['y'].value_or(0) * u;
      frame_shift_.x += dx * std::cos(t) - dy * std::sin(t);
      frame_shift_.y += dx * std::sin(t) + dy * std::cos(t);
      frame_shift_.z += v['z'].value_or(0) * u;
      for (char a : {'x', 'y', 'z'})
        v.letter[slot(a)].reset();
      continue;
    }
    if (sinumerik && is_any(k.name, {"rot", "arot"})) {
      const bool add = k.name == "arot";
      if (!add) frame_rotation_deg_ = 0;
      double angle = 0;
      if (v.has('z')) angle = *v['z'];
      for (const Keyword& r : b.keywords)
        if (r.name == "rpl") {
          double value;
          std::string err;
          std::size_t off = 0;
          if (evaluate(r.args, params_, value, err, off)) angle = value;
        }
      if (v.has('x') || v.has('y'))
        warning(k.column, name + " about X or Y (a tilted plane) is not modelled: ignored");
      if (!add) frame_shift_ = Pose{}; // ROT replaces the whole programmable frame
      frame_rotation_deg_ += angle;
      for (char a : {'x', 'y', 'z'})
        v.letter[slot(a)].reset();
      continue;
    }
    if (sinumerik && k.name == "rpl") continue; // read with ROT/AROT
    if (sinumerik && k.name == "msg") {
      std::string text(k.args);
      if (text.size() >= 2 && text.front() == '"' && text.back() == '"')
        text = text.substr(1, text.size() - 2);
      emit_simple(CanonKind::Message, 0, text);
      continue;
    }
    if (sinumerik && is_silent(k.name)) continue;
    if (sinumerik && (k.name == "m17" || k.name == "ret")) continue;
    if (sinumerik && is_planner_word(k.name)) {
      std::string text = name;
      if (k.has_parens) text += "(" + to_upper(k.args) + ")";
      emit_simple(CanonKind::PlannerHint, 0, text);
      continue;
    }
    warning(k.column, "unknown or unsupported word '" + name +
                          "': ignored (the block's motion is still counted)");
  }
  (void)b;
}

} // namespace ncjoule::detail
