// Steps 20-21 of a block's execution: the motion mode and the move the block makes, program
// stops and the Fanuc family's subprogram calls.
#include "interpreter_impl.hpp"

#include <algorithm>
#include <cmath>

#include "codes.hpp"

namespace ncjoule::detail {

// 20. Motion mode: the block's motion code, and what G80 leaves in force.
void Interpreter::set_motion_mode(const BlockValues& v) {
  for (int code : v.g) {
    if (g_group(code) != 1) continue;
    // A series of cycles ends with any motion code that is not a cycle (G80 included); one
    // cycle code after another (G81 then G82) goes on with the same series.
    const bool cycle = code == 730 || code == 740 || (code >= 810 && code <= 890);
    if (!cycle) have_cycle_initial_height_ = false, tap_peck_ = 0;
    const bool plain = motion_ == Motion::Rapid || motion_ == Motion::Linear ||
                       motion_ == Motion::ArcCW || motion_ == Motion::ArcCCW;
    if ((cycle || code == 800) && plain) motion_before_cycle_ = motion_;
    if (code == 800 && dialect_.canned_cycle_group) {
      // Fanuc's group 09: G80 ends the cycle and leaves G0/G1/G2/G3 as they were.
      if (!plain) motion_ = motion_before_cycle_;
      continue;
    }
    motion_ = Motion(code);
  }
}

// 20. Motion: the move the block's axis words make in the motion mode.
void Interpreter::convert_motion(BlockValues& v, bool axes_used) {
  const bool g53 = has_g(v, 530);
  const bool motion_word_given =
      std::any_of(v.g.begin(), v.g.end(), [](int c) { return g_group(c) == 1 && c != 800; });
  if (dialect_.o_word_subroutines && (has_g(v, 50) || has_g(v, 51))) {
    spline(v, has_g(v, 51));
    axes_used = true;
  }
  if (motion_ == Motion::None && v.has_axis() && !axes_used && !strict_) {
    // Most controls keep G0/G1 in force after G80; LinuxCNC does not. With the dialect unknown,
    // the program is more likely written for one of the many than for the one.
    motion_ = motion_before_cycle_;
    warning(0, "axis words after G80 with no motion code: moved in the " + g_name(int(motion_)) +
                   " mode in force before the cycle, as Fanuc-family controls do (LinuxCNC "
                   "would refuse the block)");
  }
  if (!axes_used && (v.has_axis() || (motion_word_given && motion_ != Motion::None))) {
    // G0/G1/G2/G3 are what cutter radius compensation offsets (not G53: LinuxCNC refuses it).
    const bool plain = motion_ == Motion::Rapid || motion_ == Motion::Linear ||
                       motion_ == Motion::ArcCW || motion_ == Motion::ArcCCW;
    comp_column_ = v.g_column(int(motion_));
    for (char axis : {'x', 'y', 'z'})
      if (!comp_column_ && v.has(axis)) comp_column_ = v.column[std::size_t(axis - 'a')];
    if (plain && g53) comp_bypass(v.g_column(530), "G53"); // LinuxCNC refuses it
    if (motion_ == Motion::Rapid || motion_ == Motion::Linear) {
      comp_.arc_not_allowed = false;
    } else if ((motion_ == Motion::ArcCW || motion_ == Motion::ArcCCW) && comp_.arc_not_allowed) {
      comp_.arc_not_allowed = false;
      if (comp_strict())
        error(v.column['g' - 'a'], "the move just after exiting cutter radius compensation "
                                   "must be straight, not an arc");
    }
    comp_motion_ = plain && !g53;
    switch (motion_) {
    case Motion::Rapid:
      straight(CanonKind::Traverse, target_from_words(v, g53), {}, g53 ? named_axes(v) : 0);
      break;
    case Motion::Linear:
      if (state_.feed_mode == FeedMode::InverseTime && !v.has('f') && v.has_axis())
        error(v.column['g' - 'a'], "G93 inverse time: a feed move needs an F word");
      else if (state_.feed <= 0 && v.has_axis())
        error(v.column['g' - 'a'], "feed move with no feed rate (F word missing or zero)");
      if (v.has_axis()) {
        const Pose end = target_from_words(v, g53);
        if (state_.feed_mode == FeedMode::InverseTime && v.has('f')) {
          // The move's length sets its feed (only here: it is a tenth of the work of a G1).
          CanonCommand probe_length = make(CanonKind::Feed);
          probe_length.end = end;
          inverse_time_feed(move_length(probe_length), v);
        }
        straight(CanonKind::Feed, end, {}, g53 ? named_axes(v) : 0);
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
    comp_motion_ = false;
  }
}

// 21. Stops and subprogram calls (Fanuc, Haas).
void Interpreter::convert_stops_and_calls(const BlockValues& v) {
  // A stop issues the moves compensation holds (their ends as they are); the end of the program
  // turns compensation off.
  for (int m : v.m)
    if (m == 0 || m == 1 || m == 2 || m == 30 || m == 60) {
      if (!comp_.queue.empty() && comp_.offsetting())
        comp_move_end(plane_point(comp_.tool, comp_.plane), 0);
      comp_release();
      if (m == 2 || m == 30) comp_.side = CompSide::Off, comp_.first = true;
    }
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
    if (m == 98 || m == 97) fanuc_call(v, m);
    if (m == 99) fanuc_return(v);
  }
}

} // namespace ncjoule::detail
