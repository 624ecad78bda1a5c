// One block's execution, in rs274ngc's order of execution (its "convert" steps), and the first
// steps of it: comments, codes of no group, feed, spindle speed, tool, spindle and coolant,
// M codes, dwell. convert_modes.cpp holds steps 11-19, convert_motion.cpp 20-21.
#include "interpreter_impl.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "codes.hpp"
#include "ncjoule/text.hpp"
#include "value_limits.hpp"

namespace ncjoule::detail {

void Interpreter::execute(const Block& b, BlockValues& v) {
  if (dialect_.g65_macro_calls && has_g(v, 650)) {
    macro_call(v);
    return;
  }
  // Which of two codes of one group the programmer meant cannot always be known: where the
  // control refuses the block, it is skipped whole, and the program goes on.
  if (!check_modal_groups(v)) {
    note(0, "block skipped");
    return;
  }
  // L is a whole number wherever it is read (a repeat count, G10's data code): LinuxCNC refuses
  // the block ("Non integer value for integer"), Fanuc alarms on a decimal point in it.
  if (v.has('l') && std::abs(*v['l'] - std::round(*v['l'])) > 1e-4) {
    error(v.column['l' - 'a'], "L" + number_text(*v['l']) +
                                   " is not a whole number: L counts repeats (or names G10's "
                                   "data), and controls refuse a fraction; block skipped");
    return;
  }
  // Words of several letters (Sinumerik frames and cycles, ...), before any motion.
  std::optional<SinumerikCycle> cycle_now;
  if (!b.keywords.empty()) keywords(b, v, cycle_now);
  const bool positioning = v.has_axis();

  check_e_word(v);
  convert_comments(b);            // 1
  convert_other_codes(v);         // 2
  convert_feed(v);                // 3, 4
  convert_spindle_speed(v);       // 5
  convert_tool(v);                // 6, 7
  convert_spindle_and_coolant(v); // 8, 9
  check_m_codes(v);
  convert_dwell(b, v);                      // 10
  convert_plane_and_units(v);               // 11, 12
  convert_cutter_compensation(v);           // 13
  convert_tool_length_offset(v);            // 14
  convert_coordinate_system(v);             // 15
  convert_path_control(v);                  // 16
  convert_distance_modes(v);                // 17, 18
  polar_words(v);                           // G16: radius and angle to X, Y
  const bool axes_used = convert_group0(v); // 19
  set_motion_mode(v);                       // 20
  convert_motion(v, axes_used);
  // 20b. Sinumerik cycles: one called in this block, or the MCALL cycle after a positioning.
  if (cycle_now)
    sinumerik_cycle(*cycle_now);
  else if (modal_cycle_ && positioning && v.has_axis())
    sinumerik_cycle(*modal_cycle_);
  convert_stops_and_calls(v); // 21
}

// E has few uses on a mill (LinuxCNC: the G70/G76 lathe cycles and M66-M68 I/O; Haas: G187's
// accuracy; RepRap: the extruder). Its usual source is a number written with an exponent, which
// G-code does not have: "R1e9" is R1 and E9. rs274 refuses an E word nothing uses, as the
// LinuxCNC dialect does when it was chosen; elsewhere it is warned about and ignored.
void Interpreter::check_e_word(const BlockValues& v) {
  if (!v.has('e') || dialect_.name == "reprap") return;
  if (has_g(v, 700) || has_g(v, 760) || has_g(v, 1870) || has_m(v, 66) || has_m(v, 67) ||
      has_m(v, 68))
    return;
  const int column = v.column['e' - 'a'];
  const char* why = " (G-code numbers have no exponent: R1e9 is R1 and E9)";
  if (dialect_.name == "linuxcnc" && strict_)
    error(column, std::string("E word with no G70, G76, M66, M67 or M68 to use it") + why);
  else
    warning(column, std::string("E word ignored: nothing on the block uses it") + why);
}

// 1. Comments and messages.
void Interpreter::convert_comments(const Block& b) {
  for (const Comment& c : b.comments) {
    std::string lowered(c.text.substr(0, 4));
    for (char& ch : lowered)
      ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (lowered == "msg,") emit_simple(CanonKind::Message, 0, std::string(c.text.substr(4)));
  }
}

// 2. Codes of no modal group: planner hints, Heidenhain/Sinumerik units, and the codes and
// axes that are not modelled (warned about, never fatal).
void Interpreter::convert_other_codes(const BlockValues& v) {
  for (int code : v.g) {
    if (g_group(code) >= 0) continue;
    if (convert_additional_work_offset(code, v)) continue;
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
      units_given_ = true;
      if (inch != state_.inch) state_.inch = inch, emit_simple(CanonKind::LengthUnits);
      continue;
    }
    if (code == 150 || code == 160) {
      polar_mode(code == 160, v.g_column(code));
      continue;
    }
    switch (code) {
    case 70:
    case 80:
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
}

// 3. Feed mode, 4. feed rate.
void Interpreter::convert_feed(const BlockValues& v) {
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
}

// 5. Spindle speed.
void Interpreter::convert_spindle_speed(const BlockValues& v) {
  if (v.has('s') && !(dialect_.dwell_s_word && has_g(v, 40))) {
    const double s = *v['s'];
    if (s < 0) error(v.column['s' - 'a'], "negative spindle speed");
    state_.spindle_rpm = std::abs(s);
    emit_simple(CanonKind::SpindleSpeed, state_.spindle_rpm);
  }
}

// 6. Select tool, 7. tool change.
void Interpreter::convert_tool(const BlockValues& v) {
  if (v.has('t')) {
    const double t = *v['t'];
    if (t < 0 || std::abs(t - std::round(t)) > 1e-6) {
      error(v.column['t' - 'a'], "T word must be a non-negative integer");
    } else {
      selected_tool_ = int(std::lround(t));
      emit_simple(CanonKind::SelectTool, selected_tool_);
    }
  }
  for (int m : v.m) {
    if (m == 6) {
      // The spindle stops for the change; the program restarts it.
      if (state_.spindle != SpindleDir::Off) {
        state_.spindle = SpindleDir::Off;
        emit_simple(CanonKind::SpindleStop);
      }
      state_.tool = selected_tool_;
      params_.at(param::kToolNumber) = state_.tool;
      tool_changed_ = true;
      emit_simple(CanonKind::ChangeTool, state_.tool);
    } else if (m == 61) {
      if (v.has('q')) state_.tool = selected_tool_ = int(std::lround(*v['q']));
    }
  }
}

// FreeCAD's grbl post writes every tool change as a comment ("( M6 T2 )"): grbl has no tool
// changer, and the operator changes the tool by hand at that point. The cuts after it are made
// with that tool, not with the one before it. Read so only while the program has run no M6 of
// its own: where it has, a commented-out change is one the programmer took out.
void Interpreter::commented_tool_change(const Comment& comment) {
  if (tool_changed_) return;
  std::optional<int> tool;
  bool change = false;
  std::size_t i = 0;
  const std::string_view t = comment.text;
  while (i < t.size()) {
    if (t[i] == ' ' || t[i] == '\t') {
      ++i;
      continue;
    }
    const char letter = char(std::tolower(static_cast<unsigned char>(t[i])));
    std::size_t j = i + 1;
    while (j < t.size() && std::isdigit(static_cast<unsigned char>(t[j])))
      ++j;
    if (j == i + 1 || (j < t.size() && t[j] != ' ' && t[j] != '\t')) return; // not a word
    const int number = std::atoi(std::string(t.substr(i + 1, j - i - 1)).c_str());
    if (letter == 'm' && number == 6)
      change = true;
    else if (letter == 't' && !tool)
      tool = number;
    else
      return; // other code: not a tool change alone
    i = j;
  }
  if (!change || !tool || *tool == state_.tool) return;
  state_.tool = selected_tool_ = *tool;
  params_.at(param::kToolNumber) = state_.tool;
  // Selected here, as the comment says: the tool controller's label above it describes it.
  emit_simple(CanonKind::SelectTool, state_.tool);
  note(comment.column, "the tool change '" + std::string(trim(comment.text)) +
                           "' is written as a comment (grbl has no tool changer; the tool is "
                           "changed by hand): the cuts that follow are taken to run with T" +
                           std::to_string(*tool) + ", with no tool-change time");
}

// 8. Spindle, 9. coolant.
void Interpreter::convert_spindle_and_coolant(const BlockValues& v) {
  for (int m : v.m) {
    if (m == 3) state_.spindle = SpindleDir::Clockwise, emit_simple(CanonKind::SpindleClockwise);
    if (m == 4)
      state_.spindle = SpindleDir::CounterClockwise,
      emit_simple(CanonKind::SpindleCounterClockwise);
    if (m == 5) state_.spindle = SpindleDir::Off, emit_simple(CanonKind::SpindleStop);
  }
  for (int m : v.m) {
    if (m == 7) state_.mist = true, emit_simple(CanonKind::MistOn);
    if (m == 8) state_.flood = true, emit_simple(CanonKind::FloodOn);
    if (m == 9) {
      if (state_.mist) emit_simple(CanonKind::MistOff);
      if (state_.flood) emit_simple(CanonKind::FloodOff);
      state_.mist = state_.flood = false;
    }
  }
}

// M codes with no time or motion of their own, and the unknown ones.
void Interpreter::check_m_codes(const BlockValues& v) {
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
      if (std::find(dialect_.machine_m_codes.begin(), dialect_.machine_m_codes.end(), m) !=
          dialect_.machine_m_codes.end())
        break; // the family's own (a chip conveyor, a brake): nothing to time or count
      if (m >= 100 && m <= 199)
        note(v.column['m' - 'a'], "user M code M" + std::to_string(m) + ": no time counted");
      else
        warning(v.column['m' - 'a'],
                "unknown or unsupported code M" + std::to_string(m) + ": ignored");
    }
  }
}

// 10. Dwell.
void Interpreter::convert_dwell(const Block& b, const BlockValues& v) {
  if (has_g(v, 40)) {
    double seconds = 0;
    int column = v.g_column(40);
    if (dialect_.dwell_s_word && v.has('s') && !v.has('p')) {
      seconds = *v['s']; // Marlin, RepRapFirmware: G4 S in seconds
      column = v.column[slot('s')];
    } else if (v.has('p')) {
      column = v.column[slot('p')];
      const double p = *v['p'];
      const bool integer_p = std::abs(p - std::round(p)) < 1e-9;
      if (dialect_.dwell_p_in_ms ||
          (dialect_.dwell_p_integer_is_ms && integer_p && b.code.find('.', 0) == std::string::npos))
        seconds = p / 1000.0;
      else
        seconds = p;
    } else if (dialect_.dwell_x_word && v.has('x')) {
      seconds = *v['x'];
      column = v.column[slot('x')];
    } else {
      error(v.g_column(40), "G4 needs a P word (dwell time)");
    }
    if (seconds < 0) error(v.g_column(40), "negative dwell time"), seconds = 0;
    if (seconds > limit::kDwellS) {
      error(column, "dwell out of range: dwells go to 99,999.999 s (P99999999 in ms), the most "
                    "an industrial control takes");
      return;
    }
    CanonCommand c = make(CanonKind::Dwell);
    c.value = seconds;
    emit(std::move(c));
  }
}

} // namespace ncjoule::detail
