// Energy per command and per program: the trapezoid rule over every segment of the operating
// trace, component by component, so the components add up to the total by construction.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "ncjoule/energy.hpp"

namespace ncjoule {
namespace {

constexpr double kJoulesPerKwh = 3.6e6;

// Power of a command that has no duration: its modal state, nothing moving.
double instantaneous_power(const CanonCommand& cmd, const PowerConstants& constants) {
  OperatingPoint op;
  const ModalState& s = cmd.state;
  const bool on = s.spindle != SpindleDir::Off && s.spindle_rpm > 0;
  op.spindle_on = on ? 1.0 : 0.0;
  op.spindle_rpm = on ? s.spindle_rpm : 0.0;
  op.coolant_on = (s.mist || s.flood) ? 1.0 : 0.0;
  return component_sum(component_power_w(constants, op));
}

} // namespace

EnergyIntegrator::EnergyIntegrator(const PowerConstants& constants, const EnergyOptions& options)
    : constants_(constants), evaluate_power_(constants), options_(options) {}

void EnergyIntegrator::set_rpm_before(double rpm) {
  previous_rpm_ = rpm;
}

CommandEnergy EnergyIntegrator::integrate(std::size_t index, const CanonCommand& command,
                                          const TimedCommand& timed,
                                          const std::vector<OperatingSegment>& segments,
                                          double removed_mm3) {
  return integrate(index, command, timed, segments.data(), segments.data() + segments.size(),
                   removed_mm3);
}

// The mean chip of a cut of radial engagement a_e with a cutter of diameter D (Sandvik's
// milling formula, 90 deg entering angle): h_m = f_z * (2 a_e / D) / arccos(1 - 2 a_e / D),
// (2 / pi) f_z for a slot, thinner for a side cut. An engagement not known is taken as a slot.
double mean_chip_thickness_mm(double per_tooth_mm, double radial_width_mm, double diameter_mm) {
  constexpr double kSlot = 0.63661977236758134; // 2 / pi
  if (!(radial_width_mm > 0) || !(diameter_mm > 0)) return kSlot * per_tooth_mm;
  // Engagements of a hair's width (a column grazed at a step's end) are held at 1% of D.
  const double ratio = std::clamp(radial_width_mm / diameter_mm, 0.01, 1.0);
  return per_tooth_mm * 2 * ratio / std::acos(1 - 2 * ratio);
}

// Kienzle: the cutting force per chip area falls as the chip thickens. With the tool's flutes
// known (given, or EnergyOptions' typical number for its kind), the chip thickness at each point
// is the mean over the cut's engagement (mean_chip_thickness_mm, with the radial width removal
// measured), and the cutting term is scaled by k_c(h_m) / k_c.
void EnergyIntegrator::correct_for_chip_thickness(const CanonCommand& command,
                                                  OperatingSegment* first,
                                                  OperatingSegment* last) const {
  const auto& material = constants_.cutting_material;
  if (!material || !(material->kc11_n_mm2 > 0) || !(material->kc_j_mm3 > 0)) return;
  const auto flutes = options_.flutes.find(command.state.tool);
  if (flutes == options_.flutes.end() || flutes->second <= 0) return;
  if (command.state.feed_mode != FeedMode::UnitsPerMinute || !(command.state.feed > 0)) return;
  // The speed the cut turns at: the spindle's, or the one a stopped spindle is counted at.
  double rpm = command.state.spindle_rpm;
  for (const OperatingSegment* seg = first; !(rpm > 0) && seg != last; ++seg)
    rpm = std::max(seg->start.spindle_rpm, seg->end.spindle_rpm);
  if (!(rpm > 0)) return;
  const double per_tooth_mm = command.state.feed / (rpm * flutes->second);
  const auto diameter = options_.tool_diameters_mm.find(command.state.tool);
  const double d = diameter == options_.tool_diameters_mm.end() ? 0.0 : diameter->second;
  // A segment's end is the next one's start, and a steady cut keeps its width: the factor is
  // worked out again (an acos and a pow) only where the width changes.
  double width = std::numeric_limits<double>::quiet_NaN(), factor = 0;
  for (OperatingSegment* seg = first; seg != last; ++seg)
    for (OperatingPoint* p : {&seg->start, &seg->end}) {
      if (!(p->radial_width_mm == width)) {
        width = p->radial_width_mm;
        factor =
            material->kc_at(mean_chip_thickness_mm(per_tooth_mm, width, d)) / material->kc_j_mm3;
      }
      p->cutting_factor = factor;
    }
}

// The speeds the spindle runs at: above its maximum the control clamps the speed (counted so,
// and said once); outside the speeds its line was measured over, its power is extrapolated
// (said once in the totals, with how far).
void EnergyIntegrator::note_spindle(const CanonCommand& command, OperatingSegment* first,
                                    OperatingSegment* last) {
  const double max = constants_.spindle_max_rpm;
  for (OperatingSegment* seg = first; seg != last; ++seg)
    for (OperatingPoint* p : {&seg->start, &seg->end}) {
      if (!(p->spindle_on > 0) || !(p->spindle_rpm > 0)) continue;
      if (max > 0 && p->spindle_rpm > max) {
        if (over_max_line_ < 0) over_max_line_ = command.line, over_max_rpm_ = p->spindle_rpm;
        p->spindle_rpm = max;
      }
      if (spindle_rpm_max_ == 0 || p->spindle_rpm > spindle_rpm_max_)
        spindle_rpm_max_ = p->spindle_rpm, spindle_rpm_max_line_ = command.line;
      if (spindle_rpm_min_ == 0 || p->spindle_rpm < spindle_rpm_min_)
        spindle_rpm_min_ = p->spindle_rpm;
    }
}

// Material removed with the spindle stopped (no M3/M4 yet, an M5 before, or S0): on the machine
// the tool would break, unless the spindle is one switched by hand (a router's). Counted as
// turning at the speed the program last set (S without M3), else the profile's
// hand_spindle_rpm; with neither its spindle and cutting energy cannot be counted. Said once.
void EnergyIntegrator::spin_for_stopped_cut(const CanonCommand& command, OperatingSegment* first,
                                            OperatingSegment* last) {
  const ModalState& s = command.state;
  if (s.spindle != SpindleDir::Off && s.spindle_rpm > 0) return;
  if (stopped_cuts_++ == 0) {
    stopped_cut_line_ = command.line;
    stopped_cut_at_s0_ = s.spindle != SpindleDir::Off; // M3/M4 in force, at S0
    stopped_cut_rpm_ = s.spindle_rpm > 0 ? s.spindle_rpm : constants_.hand_spindle_rpm;
  }
  const double rpm = s.spindle_rpm > 0 ? s.spindle_rpm : constants_.hand_spindle_rpm;
  if (!(rpm > 0)) return;
  for (OperatingSegment* seg = first; seg != last; ++seg)
    for (OperatingPoint* p : {&seg->start, &seg->end})
      if (p->mrr_mm3_s > 0) p->spindle_rpm = rpm, p->spindle_on = 1;
}

void EnergyIntegrator::note_cutting(const OperatingPoint& p) {
  if (!(p.mrr_mm3_s > 0) || !(p.spindle_on > 0)) return;
  if (!cut_seen_) {
    cut_rpm_min_ = cut_rpm_max_ = p.spindle_rpm;
    cut_mrr_min_ = cut_mrr_max_ = p.mrr_mm3_s;
    cut_seen_ = true;
    return;
  }
  cut_rpm_min_ = std::min(cut_rpm_min_, p.spindle_rpm);
  cut_rpm_max_ = std::max(cut_rpm_max_, p.spindle_rpm);
  cut_mrr_min_ = std::min(cut_mrr_min_, p.mrr_mm3_s);
  cut_mrr_max_ = std::max(cut_mrr_max_, p.mrr_mm3_s);
}

const ComponentValues& EnergyIntegrator::power_at(const OperatingPoint& point) {
  // Bits, not ==: a point equal to the last but for the sign of a zero gets its own evaluation,
  // so reusing a result never changes one.
  if (!has_last_point_ || std::memcmp(&point, &last_point_, sizeof point) != 0) {
    last_point_ = point;
    last_power_ = evaluate_power_(point);
    has_last_point_ = true;
  }
  return last_power_;
}

CommandEnergy EnergyIntegrator::integrate(std::size_t index, const CanonCommand& command,
                                          const TimedCommand& timed, const OperatingSegment* first,
                                          const OperatingSegment* last, double removed_mm3,
                                          std::vector<SegmentPower>* powers) {
  CommandEnergy ce;
  ce.command = index;
  ce.line = timed.line;
  ce.duration_s = timed.duration_s;
  ce.removed_mm3 = removed_mm3;
  bool has_power = false;
  for (const OperatingSegment* it = first; it != last; ++it) {
    const OperatingSegment& seg = *it;
    const double dt = seg.t1_s - seg.t0_s;
    const ComponentValues a = power_at(seg.start);
    const ComponentValues b = power_at(seg.end);
    for (std::size_t c = 0; c < kPowerComponentCount; ++c)
      ce.components_j[c] += 0.5 * (a[c] + b[c]) * dt;
    const double sum_a = component_sum(a), sum_b = component_sum(b);
    if (powers) powers->push_back({sum_a, sum_b});
    const double peak = std::max(sum_a, sum_b);
    constexpr std::size_t kCutting = static_cast<std::size_t>(PowerComponent::Cutting);
    const double uncut = std::max(sum_a - a[kCutting], sum_b - b[kCutting]);
    ce.peak_power_w = has_power ? std::max(ce.peak_power_w, peak) : peak;
    ce.peak_power_without_cutting_w =
        has_power ? std::max(ce.peak_power_without_cutting_w, uncut) : uncut;
    has_power = true;
    note_cutting(seg.start);
    note_cutting(seg.end);
    // Load on the spindle: the cutting power it delivers against its rating at that speed.
    constexpr std::size_t kCut = static_cast<std::size_t>(PowerComponent::Cutting);
    for (const auto& [power, point] :
         {std::pair{a[kCut], &seg.start}, std::pair{b[kCut], &seg.end}}) {
      const double rated = rated_spindle_power_w(constants_, point->spindle_rpm);
      if (rated > 0 && power > 0)
        ce.spindle_load = std::max(ce.spindle_load, power * constants_.cutting_efficiency / rated);
    }
  }
  ce.energy_j = component_sum(ce.components_j);
  // The program's peak is over what runs for some time.
  totals_.peak_power_w = std::max(totals_.peak_power_w, ce.peak_power_w);
  if (ce.duration_s > 0) {
    ce.mean_power_w = ce.energy_j / ce.duration_s;
  } else {
    // A command without duration reports the power of its state.
    ce.mean_power_w = instantaneous_power(command, constants_);
    ce.peak_power_w = std::max(ce.peak_power_w, ce.mean_power_w);
  }
  if (ce.removed_mm3 > 0) ce.sec_j_mm3 = ce.energy_j / ce.removed_mm3;
  for (std::size_t c = 0; c < kPowerComponentCount; ++c)
    totals_.components_j[c] += ce.components_j[c];
  totals_.duration_s += ce.duration_s;
  totals_.removed_mm3 += ce.removed_mm3;
  return ce;
}

CommandEnergy EnergyIntegrator::add(std::size_t index, const CanonCommand& command,
                                    const TimedCommand& timed, const CommandRemoval* removal,
                                    std::vector<OperatingSegment>& segments,
                                    std::vector<Diagnostic>* diagnostics,
                                    std::vector<SegmentPower>* powers) {
  const std::size_t first = segments.size();
  append_operating_segments(index, command, timed, removal, previous_rpm_, segments, diagnostics);
  if (removal && removal->removed_mm3 > 0)
    spin_for_stopped_cut(command, segments.data() + first, segments.data() + segments.size());
  note_spindle(command, segments.data() + first, segments.data() + segments.size());
  correct_for_chip_thickness(command, segments.data() + first, segments.data() + segments.size());
  return integrate(index, command, timed, segments.data() + first,
                   segments.data() + segments.size(), removal ? removal->removed_mm3 : 0.0, powers);
}

EnergyResult EnergyIntegrator::totals(double program_duration_s) const {
  EnergyResult result = totals_;
  result.model_description = describe_power_constants(constants_);
  result.energy_j = component_sum(result.components_j);
  if (result.removed_mm3 > 0) result.sec_j_mm3 = result.energy_j / result.removed_mm3;
  if (program_duration_s > 0) result.duration_s = program_duration_s;
  if (result.duration_s > 0) result.mean_power_w = result.energy_j / result.duration_s;
  const double kwh = result.energy_j / kJoulesPerKwh;
  result.co2_kg = kwh * options_.co2_kg_per_kwh.value_or(constants_.co2_kg_per_kwh);
  result.electricity_cost = kwh * options_.price_per_kwh.value_or(constants_.price_per_kwh);
  result.machine_rate_per_hour =
      options_.machine_rate_per_hour.value_or(constants_.machine_rate_per_hour);
  result.machine_cost = result.duration_s / 3600 * result.machine_rate_per_hour;
  result.cost = result.electricity_cost + result.machine_cost;
  result.currency = options_.currency.value_or(constants_.currency);
  if (options_.price_per_kwh && !options_.price_from.empty())
    result.price_from = options_.price_from;
  if (options_.machine_rate_per_hour && !options_.rate_from.empty())
    result.rate_from = options_.rate_from;
  if (over_max_line_ >= 0) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "S%g is above the spindle's maximum of %g rpm (spindle_max_rpm): the control "
                  "runs it at %g rpm, and so is it counted%s%s",
                  over_max_rpm_, constants_.spindle_max_rpm, constants_.spindle_max_rpm,
                  constants_.placeholder_spindle ? "; this profile's maximum is a placeholder "
                                                 : "",
                  constants_.placeholder_spindle ? kPlaceholderSpindleAdvice : "");
    result.diagnostics.push_back({Severity::Warning, "", over_max_line_ + 1, 0, text});
  }
  const PavanaskarConstants& pav = constants_.pavanaskar;
  if (constants_.model != PowerModel::Zhou && pav.spindle_fitted_rpm_max > 0 &&
      spindle_rpm_max_ > 0 &&
      (spindle_rpm_max_ > pav.spindle_fitted_rpm_max ||
       spindle_rpm_min_ < pav.spindle_fitted_rpm_min)) {
    const bool above = spindle_rpm_max_ > pav.spindle_fitted_rpm_max;
    const double factor = above ? spindle_rpm_max_ / pav.spindle_fitted_rpm_max
                                : pav.spindle_fitted_rpm_min / spindle_rpm_min_;
    char text[320];
    std::snprintf(text, sizeof text,
                  "the spindle's power line was measured at %g-%g rpm; this program runs it at "
                  "%g-%g rpm (%.1fx %s): its spindle power is extrapolated",
                  pav.spindle_fitted_rpm_min, pav.spindle_fitted_rpm_max, spindle_rpm_min_,
                  spindle_rpm_max_, factor, above ? "above" : "below");
    result.diagnostics.push_back(
        {Severity::Warning, "", above ? spindle_rpm_max_line_ + 1 : 0, 0, text});
  }
  if (stopped_cuts_ > 0) {
    char text[480];
    const int more = int(stopped_cuts_ - 1);
    const std::string more_text =
        more ? " and in " + std::to_string(more) + " more moves" : std::string();
    if (stopped_cut_at_s0_ && stopped_cut_rpm_ > 0)
      std::snprintf(text, sizeof text,
                    "material is removed with the spindle on at S0 (M3/M4 with a speed of 0) "
                    "here%s: on the machine the tool would break unless the spindle is switched "
                    "by hand; counted as turning at %g rpm (the profile's hand_spindle_rpm)",
                    more_text.c_str(), stopped_cut_rpm_);
    else if (stopped_cut_at_s0_)
      std::snprintf(text, sizeof text,
                    "material is removed with the spindle on at S0 (M3/M4 with a speed of 0) "
                    "here%s: on the machine the tool would break; its spindle and cutting energy "
                    "are NOT counted (give the speed with an S word before the cut)",
                    more_text.c_str());
    else if (stopped_cut_rpm_ > 0)
      std::snprintf(
          text, sizeof text,
          "material is removed with the spindle stopped (no M3/M4 in force) here%s: on "
          "the machine the tool would break unless the spindle is switched by hand; "
          "counted as turning at %g rpm (%s)",
          more ? (" and in " + std::to_string(more) + " more moves").c_str() : "", stopped_cut_rpm_,
          constants_.hand_spindle_rpm == stopped_cut_rpm_ ? "the profile's hand_spindle_rpm"
                                                          : "the program's last S");
    else
      std::snprintf(text, sizeof text,
                    "material is removed with the spindle stopped (no M3/M4 and no S) here%s: "
                    "on the machine the tool would break unless the spindle is switched by "
                    "hand; its spindle and cutting energy are NOT counted (give the speed a hand "
                    "spindle runs at with hand_spindle_rpm under [power] in the profile)",
                    more ? (" and in " + std::to_string(more) + " more moves").c_str() : "");
    result.diagnostics.push_back({Severity::Warning, "", stopped_cut_line_ + 1, 0, text});
  }
  const ZhouConstants& z = constants_.zhou;
  // Zhou's idle line c1 + c2*n was fitted on the same speeds as its cutting term: outside them
  // the spindle's power is extrapolated too, cutting or not.
  if (constants_.model == PowerModel::Zhou && z.fitted_rpm_max > 0 && spindle_rpm_max_ > 0 &&
      (spindle_rpm_max_ > z.fitted_rpm_max || spindle_rpm_min_ < z.fitted_rpm_min)) {
    const bool above = spindle_rpm_max_ > z.fitted_rpm_max;
    const double factor =
        above ? spindle_rpm_max_ / z.fitted_rpm_max : z.fitted_rpm_min / spindle_rpm_min_;
    char text[320];
    std::snprintf(text, sizeof text,
                  "the idle spindle line c1 + c2*n was fitted at %g-%g rpm; this program runs the "
                  "spindle at %g-%g rpm (%.1fx %s): its spindle power is extrapolated",
                  z.fitted_rpm_min, z.fitted_rpm_max, spindle_rpm_min_, spindle_rpm_max_, factor,
                  above ? "above" : "below");
    result.diagnostics.push_back(
        {Severity::Warning, "", above ? spindle_rpm_max_line_ + 1 : 0, 0, text});
  }
  // A fitted cutting term used outside what it was fitted on: once per program, saying how far.
  const bool fitted =
      constants_.model != PowerModel::Pavanaskar && constants_.cutting_term == CuttingTerm::Fitted;
  if (fitted && cut_seen_) {
    char text[320];
    if (z.fitted_rpm_max > 0 &&
        (cut_rpm_max_ > z.fitted_rpm_max || cut_rpm_min_ < z.fitted_rpm_min)) {
      const double worst = cut_rpm_max_ > z.fitted_rpm_max ? cut_rpm_max_ / z.fitted_rpm_max
                                                           : z.fitted_rpm_min / cut_rpm_min_;
      std::snprintf(text, sizeof text,
                    "the cutting term c3*n^c4*MRR was fitted on %g-%g rpm; this program cuts at "
                    "%g-%g rpm (%.1fx outside): its cutting power is extrapolated",
                    z.fitted_rpm_min, z.fitted_rpm_max, cut_rpm_min_, cut_rpm_max_, worst);
      result.diagnostics.push_back({Severity::Warning, "", 0, 0, text});
    }
    // Only above: every cut passes through low removal rates as the tool enters and leaves.
    if (z.fitted_mrr_max_mm3_s > 0 && cut_mrr_max_ > z.fitted_mrr_max_mm3_s) {
      std::snprintf(text, sizeof text,
                    "the cutting term c3*n^c4*MRR was fitted on MRR %g-%g mm^3/s; this program "
                    "removes up to %.3g mm^3/s (%.1fx the highest): its cutting power is "
                    "extrapolated",
                    z.fitted_mrr_min_mm3_s, z.fitted_mrr_max_mm3_s, cut_mrr_max_,
                    cut_mrr_max_ / z.fitted_mrr_max_mm3_s);
      result.diagnostics.push_back({Severity::Warning, "", 0, 0, text});
    }
  }
  return result;
}

EnergyResult integrate_energy(const std::vector<OperatingSegment>& trace, const Timeline& timeline,
                              const RemovalResult* removal, const PowerConstants& constants,
                              const EnergyOptions& options) {
  // Segments by command (the trace is in program order; a command's segments are consecutive).
  EnergyIntegrator integrator(constants, options);
  EnergyResult result;
  result.commands.resize(timeline.commands.size());
  std::size_t s = 0;
  std::vector<OperatingSegment> mine;
  const CanonCommand still; // commands without segments: only their duration counts here
  for (std::size_t i = 0; i < timeline.commands.size(); ++i) {
    mine.clear();
    while (s < trace.size() && trace[s].command < i)
      ++s;
    while (s < trace.size() && trace[s].command == i)
      mine.push_back(trace[s++]);
    const double removed =
        removal && i < removal->commands.size() ? removal->commands[i].removed_mm3 : 0.0;
    result.commands[i] = integrator.integrate(i, still, timeline.commands[i], mine, removed);
    if (mine.empty() && timeline.commands[i].duration_s <= 0)
      result.commands[i].mean_power_w = result.commands[i].peak_power_w = 0;
  }
  const EnergyResult totals = integrator.totals(timeline.total_s);
  result.duration_s = totals.duration_s;
  result.energy_j = totals.energy_j;
  result.components_j = totals.components_j;
  result.removed_mm3 = removal ? removal->removed_mm3 : totals.removed_mm3;
  result.sec_j_mm3 = result.removed_mm3 > 0 ? result.energy_j / result.removed_mm3 : 0.0;
  result.mean_power_w = totals.mean_power_w;
  result.peak_power_w = totals.peak_power_w;
  result.co2_kg = totals.co2_kg;
  result.cost = totals.cost;
  result.electricity_cost = totals.electricity_cost;
  result.machine_cost = totals.machine_cost;
  result.machine_rate_per_hour = totals.machine_rate_per_hour;
  result.currency = totals.currency;
  result.price_from = totals.price_from;
  result.rate_from = totals.rate_from;
  result.model_description = totals.model_description;
  return result;
}

EnergyResult estimate_energy(const std::vector<CanonCommand>& commands, const Timeline& timeline,
                             const RemovalResult* removal, const PowerConstants& constants,
                             const EnergyOptions& options) {
  std::vector<Diagnostic> diagnostics;
  if (removal && removal->commands.size() != timeline.commands.size()) {
    diagnostics.push_back(
        {Severity::Warning, "", 1, 0,
         "removal results do not match the timeline (" + std::to_string(removal->commands.size()) +
             " vs " + std::to_string(timeline.commands.size()) + " commands): removal ignored"});
    removal = nullptr;
  }
  EnergyIntegrator integrator(constants, options);
  EnergyResult result;
  result.commands.reserve(timeline.commands.size());
  std::vector<OperatingSegment> segments;
  for (std::size_t i = 0; i < timeline.commands.size(); ++i) {
    const TimedCommand& tc = timeline.commands[i];
    if (tc.command >= commands.size()) {
      diagnostics.push_back({Severity::Warning, "", tc.line + 1, 0,
                             "timed command refers to a command that does not exist"});
      result.commands.push_back({});
      continue;
    }
    segments.clear();
    result.commands.push_back(integrator.add(i, commands[tc.command], tc,
                                             removal ? &removal->commands[i] : nullptr, segments,
                                             &diagnostics));
  }
  const EnergyResult totals = integrator.totals(timeline.total_s);
  std::vector<CommandEnergy> per_command = std::move(result.commands);
  result = totals;
  result.commands = std::move(per_command);
  if (removal) {
    result.removed_mm3 = removal->removed_mm3;
    result.sec_j_mm3 = result.removed_mm3 > 0 ? result.energy_j / result.removed_mm3 : 0.0;
  }
  result.diagnostics = std::move(diagnostics);
  return result;
}

} // namespace ncjoule
