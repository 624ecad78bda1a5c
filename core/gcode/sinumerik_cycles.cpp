// Sinumerik drilling cycles CYCLE81 ... CYCLE89 (and CYCLE840), expanded into the moves the
// control makes at the current position. Parameters as in the SINUMERIK 840D sl Programming
// Manual, Cycles, "Drilling cycles":
//   CYCLE81(RTP, RFP, SDIS, DP, DPR)                    drilling, centring
//   CYCLE82(RTP, RFP, SDIS, DP, DPR, DTB)               drilling, counterboring (dwell DTB s)
//   CYCLE83(RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB, DTS, FRF, VARI)  deep-hole drilling
//   CYCLE84(RTP, RFP, SDIS, DP, DPR, DTB, SDAC, MPIT, PIT, POSS, SST, SST1) rigid tapping
//   CYCLE840(RTP, RFP, SDIS, DP, DPR, DTB, SDR, SDAC, ENC, MPIT, PIT)       tapping, chuck
//   CYCLE85(RTP, RFP, SDIS, DP, DPR, DTB, FFR, RFF)     boring 1 (feed in FFR, out RFF)
//   CYCLE86(RTP, RFP, SDIS, DP, DPR, DTB, SDIR, ...)    boring 2 (spindle stop, rapid out)
//   CYCLE87(RTP, RFP, SDIS, DP, DPR, SDIR)              boring 3 (spindle stop, M0, out)
//   CYCLE88(RTP, RFP, SDIS, DP, DPR, DTB, SDIR)         boring 4 (dwell, stop, M0, out)
//   CYCLE89(RTP, RFP, SDIS, DP, DPR, DTB)               boring 5 (dwell, feed out)
// RTP retraction plane and RFP reference plane are absolute; SDIS is the safety distance above
// RFP where feeding begins; the final depth is DP (absolute) or, when DPR is given, RFP - DPR.
// Every cycle rapids to RFP + SDIS, does its work, and leaves the tool at RTP.
#include <algorithm>
#include <cmath>

#include "interpreter_impl.hpp"

namespace ncjoule::detail {

void Interpreter::sinumerik_cycle(const SinumerikCycle& c) {
  auto arg = [&](std::size_t i) -> std::optional<double> {
    return i < c.args.size() ? c.args[i] : std::nullopt;
  };
  const double u = unit();
  const std::string upper_name = [&] {
    std::string s = c.name;
    for (char& ch : s)
      ch = char(std::toupper(static_cast<unsigned char>(ch)));
    return s;
  }();
  if (!arg(0) || !arg(1)) {
    warning(c.column, upper_name + " needs RTP and RFP (its first two arguments): skipped");
    return;
  }
  // Heights along Z in the frame's coordinates; frame_shift_.z moves them all.
  const double shift = frame_shift_.z;
  const double rtp = *arg(0) * u + shift, rfp = *arg(1) * u + shift;
  const double sdis = std::abs(arg(2).value_or(0)) * u;
  double bottom;
  if (arg(4) && *arg(4) != 0)
    bottom = rfp - std::abs(*arg(4)) * u;
  else if (arg(3))
    bottom = *arg(3) * u + shift;
  else {
    warning(c.column, upper_name + " needs DP or DPR (the final depth): skipped");
    return;
  }
  const double approach = rfp + sdis;
  if (bottom > approach) {
    warning(c.column, upper_name + ": the final depth is above the reference plane: skipped");
    return;
  }
  if (state_.feed <= 0 && c.name != "cycle84")
    warning(c.column, upper_name + " with no feed rate (F word missing)");

  auto at = [&](double z) {
    Pose p = pos_;
    p.z = z;
    return p;
  };
  auto traverse = [&](double z) { straight(CanonKind::Traverse, at(z)); };
  auto feed = [&](double z, std::string text = {}) {
    straight(CanonKind::Feed, at(z), std::move(text));
  };
  auto dwell = [&](std::optional<double> seconds) {
    // A negative DTB is in spindle revolutions.
    if (!seconds || *seconds == 0) return;
    double s = *seconds;
    if (s < 0) s = state_.spindle_rpm > 0 ? -s * 60.0 / state_.spindle_rpm : 0;
    emit_simple(CanonKind::Dwell, s);
  };
  auto with_feed = [&](std::optional<double> feed_mm_min, auto&& moves) {
    // A cycle's own feed rate (FFR, RFF, tapping pitch x speed) for its moves only.
    const ModalState saved = state_;
    if (feed_mm_min && *feed_mm_min > 0) {
      state_.feed_mode = FeedMode::UnitsPerMinute;
      state_.feed = *feed_mm_min;
    }
    moves();
    const Pose here = pos_;
    state_ = saved;
    pos_ = here;
  };
  auto stop_spindle = [&] {
    if (state_.spindle == SpindleDir::Off) return SpindleDir::Off;
    const SpindleDir dir = state_.spindle;
    state_.spindle = SpindleDir::Off;
    emit_simple(CanonKind::SpindleStop);
    return dir;
  };
  auto restart_spindle = [&](SpindleDir dir) {
    if (dir == SpindleDir::Off) return;
    state_.spindle = dir;
    emit_simple(dir == SpindleDir::CounterClockwise ? CanonKind::SpindleCounterClockwise
                                                    : CanonKind::SpindleClockwise);
  };
  auto reverse_spindle = [&] {
    const SpindleDir dir = state_.spindle == SpindleDir::CounterClockwise
                               ? SpindleDir::Clockwise
                               : SpindleDir::CounterClockwise;
    restart_spindle(dir);
  };

  if (pos_.z < approach) traverse(std::max(rtp, approach));
  traverse(approach);
  const std::string& n = c.name;
  if (n == "cycle81" || n == "cycle82") {
    feed(bottom);
    if (n == "cycle82") dwell(arg(5));
  } else if (n == "cycle83") {
    // FDEP/FDPR: first depth; DAM: each later peck is that much shorter, never below DAM;
    // VARI 0 chip breaking (back off 1 mm), 1 swarf removal (out to RFP + SDIS each time).
    double first = rfp - bottom;
    if (arg(6) && *arg(6) != 0)
      first = std::abs(*arg(6)) * u;
    else if (arg(5))
      first = rfp - (*arg(5) * u + shift);
    if (first <= 0) first = rfp - bottom;
    const double dam = std::abs(arg(7).value_or(0)) * u;
    const bool swarf_removal = arg(11).value_or(0) == 1;
    const double frf = arg(10).value_or(1) > 0 ? arg(10).value_or(1) : 1;
    double depth = rfp, step = first;
    bool first_peck = true;
    while (depth - step > bottom + 1e-9) {
      const double target = depth - step;
      if (first_peck)
        with_feed(state_.feed * frf, [&] { feed(target); });
      else
        feed(target);
      first_peck = false;
      dwell(arg(8));
      if (swarf_removal) {
        traverse(approach);
        dwell(arg(9));
        traverse(target + 1.0 * u);
      } else {
        traverse(target + 1.0 * u);
      }
      depth = target;
      if (dam > 0) step = std::max(dam, step - dam);
    }
    feed(bottom);
    dwell(arg(8));
  } else if (n == "cycle84" || n == "cycle840") {
    // Rigid tapping (CYCLE84): feed = pitch x tapping speed; CYCLE840 taps at the programmed
    // feed with a compensating chuck. Out again at SST1 (or SST), spindle reversed.
    const bool rigid = n == "cycle84";
    const std::optional<double> pitch = rigid ? arg(8) : arg(10);
    const std::optional<double> sst = rigid ? arg(10) : std::nullopt;
    const std::optional<double> sst1 = rigid ? arg(11) : std::nullopt;
    const double speed_in = sst && *sst > 0 ? *sst : state_.spindle_rpm;
    const double speed_out = sst1 && *sst1 > 0 ? *sst1 : speed_in;
    std::optional<double> feed_in, feed_out;
    if (pitch && *pitch != 0 && speed_in > 0) {
      feed_in = std::abs(*pitch) * u * speed_in;
      feed_out = std::abs(*pitch) * u * speed_out;
    }
    with_feed(feed_in, [&] { feed(bottom, "tap"); });
    dwell(arg(5));
    const SpindleDir dir = state_.spindle;
    reverse_spindle();
    with_feed(feed_out, [&] { feed(approach, "tap retract"); });
    restart_spindle(dir);
  } else if (n == "cycle85") {
    const auto ffr = arg(6), rff = arg(7);
    with_feed(ffr ? std::optional<double>(*ffr * u) : std::nullopt, [&] { feed(bottom); });
    dwell(arg(5));
    with_feed(rff ? std::optional<double>(*rff * u) : std::nullopt, [&] { feed(approach); });
  } else if (n == "cycle86" || n == "cycle87" || n == "cycle88") {
    feed(bottom);
    if (n != "cycle87") dwell(arg(5));
    const SpindleDir dir = stop_spindle();
    if (n != "cycle86") emit_simple(CanonKind::ProgramStop); // the operator takes the tool out
    traverse(rtp);
    restart_spindle(dir);
  } else if (n == "cycle89") {
    feed(bottom);
    dwell(arg(5));
    feed(approach);
  }
  if (pos_.z != rtp) traverse(rtp);
}

} // namespace ncjoule::detail
