#include "result_fold.hpp"

#include <algorithm>
#include <cstdio>

namespace ncjoule::estimate_detail {
namespace {

// Whether a kind says more about a line than another: moves first, then what takes time.
int kind_rank(LineKind kind) {
  switch (kind) {
  case LineKind::Arc:
  case LineKind::Feed:
  case LineKind::Probe:
    return 5;
  case LineKind::Rapid:
    return 4;
  case LineKind::ToolChange:
  case LineKind::Dwell:
    return 3;
  case LineKind::ProgramStop:
  case LineKind::OptionalStop:
  case LineKind::ProgramEnd:
  case LineKind::Spindle:
    return 2;
  case LineKind::Comment:
  case LineKind::Message:
    return 0;
  default:
    return 1;
  }
}

} // namespace

ResultFolder::ResultFolder(const SourceFile& source, const Dialect& dialect,
                           const PowerConstants& power, const EstimateOptions& options,
                           std::vector<RemovalSimulator*> removals, SetupIndex setups,
                           const std::vector<SetupStart>& starts, std::size_t expected_commands,
                           Estimate& out)
    : source_(source), dialect_(dialect), power_constants_(power), options_(options),
      removals_(std::move(removals)), setups_(std::move(setups)), out_(out),
      expected_commands_(expected_commands), line_count_(source.lines.size()),
      energy_(power, options.energy), operations_(source, dialect) {
  for (const SetupStart& start : starts)
    setup_totals_.push_back(SetupSummary{start.line, start.reason});
  for (const RemovalSimulator* r : removals_)
    guessed_setups_.push_back(r->stock_source() == StockSource::Guessed);
  if (setup_totals_.empty()) setup_totals_.push_back(SetupSummary{0, "the program's start"});
  // The lines' memory is taken now and written as the lines run (fold): zeroing 110 bytes a
  // line of a million-line program was a serial stretch before the stream.
  lines_.reserve(line_count_);
}

void ResultFolder::take(const RemovedBatch& batch) {
  const std::size_t n = batch.commands.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t index = batch.first_index + k;
    const CanonCommand& command = batch.commands[k];
    const TimedCommand& timed = batch.timed[k];
    const CommandRemoval* removed = batch.removal_known ? &batch.removed[k] : nullptr;
    segments_.clear();
    segment_powers_.clear();
    const CommandEnergy energy =
        energy_.add(index, command, timed, removed, segments_, &out_.diagnostics, &segment_powers_);
    const std::size_t operation = operations_.take(command, timed);
    const std::size_t setup_index = setups_.of(index);
    const bool guessed = batch.removal_known && !guessed_setups_.empty() &&
                         guessed_setups_[std::min(setup_index, guessed_setups_.size() - 1)];
    fold(command, timed, removed, energy, operation, guessed);
    follow_guess(timed, removed, energy, guessed);
    SetupSummary& setup = setup_totals_[std::min(setup_index, setup_totals_.size() - 1)];
    setup.time_s += timed.duration_s;
    setup.energy_j += energy.energy_j;
    if (removed) setup.removed_mm3 += removed->removed_mm3;
    follow_path(command, timed, segments_, segment_powers_);
    if (options_.keep_trace)
      out_.trace.insert(out_.trace.end(), segments_.begin(), segments_.end());
  }
  const std::size_t folded = batch.first_index + n;
  if (options_.progress && expected_commands_ > 0 && folded - last_progress_ >= 4096) {
    last_progress_ = folded;
    options_.progress(0.1 + 0.9 * std::min(1.0, double(folded) / double(expected_commands_)));
  }
}

RemovalResult ResultFolder::merged_removal() const {
  RemovalResult merged = removals_.front()->summary();
  if (removals_.size() == 1) return merged;
  merged.stock_description = "setup 1: " + merged.stock_description;
  for (std::size_t k = 1; k < removals_.size(); ++k) {
    const RemovalResult r = removals_[k]->summary();
    merged.removed_mm3 += r.removed_mm3;
    merged.memory_bytes += r.memory_bytes;
    merged.stock_volume_mm3 += r.stock_volume_mm3;
    merged.stock_description += "; setup " + std::to_string(k + 1) + ": " + r.stock_description;
  }
  return merged;
}

void ResultFolder::follow_guess(const TimedCommand& timed, const CommandRemoval* removed,
                                const CommandEnergy& energy, bool stock_guessed) {
  // A block over the rating under a guessed stock cuts material that is not there.
  const bool wrong = stock_guessed && energy.spindle_load > 1;
  if (timed.duration_s > 0) {
    plausible_peak_w_ = std::max(plausible_peak_w_,
                                 wrong ? energy.peak_power_without_cutting_w : energy.peak_power_w);
    guess_.peak_power_floor_w =
        std::max(guess_.peak_power_floor_w,
                 stock_guessed ? energy.peak_power_without_cutting_w : energy.peak_power_w);
  }
  if (!stock_guessed) return;
  guess_.guessed = true;
  if (removed) guess_.removed_mm3 += removed->removed_mm3;
  guess_.cutting_energy_j += energy.components_j[static_cast<std::size_t>(PowerComponent::Cutting)];
  if (!wrong) return;
  if (guess_.first_overload_line < 0 || timed.line != last_overload_line_) ++guess_.overload_blocks;
  last_overload_line_ = timed.line;
  if (guess_.first_overload_line < 0) guess_.first_overload_line = timed.line;
  if (energy.spindle_load > guess_.worst_load) {
    guess_.worst_load = energy.spindle_load;
    guess_.worst_overload_line = timed.line;
  }
}

void ResultFolder::fold(const CanonCommand& command, const TimedCommand& timed,
                        const CommandRemoval* removed, const CommandEnergy& energy,
                        std::size_t operation, bool stock_guessed) {
  const double removed_mm3 = removed ? removed->removed_mm3 : 0.0;
  const bool removal_known = removed != nullptr;
  time_.add(command.kind, timed.duration_s, removed_mm3 > 0, removal_known);
  operations_.add(operation, command.kind, timed.duration_s, energy.energy_j, energy.components_j,
                  removed_mm3, removal_known);
  if (timed.line < 0 || std::size_t(timed.line) >= line_count_) return;
  if (std::size_t(timed.line) >= lines_.size()) lines_.resize(std::size_t(timed.line) + 1);
  LineSummary& b = lines_[std::size_t(timed.line)];
  b.removed_mm3 += removed_mm3;
  if (removed) b.mrr_peak_mm3_s = std::max(b.mrr_peak_mm3_s, float(removed->mrr_peak_mm3_s));
  b.energy_j += energy.energy_j;
  b.power_peak_w = std::max(b.power_peak_w, float(energy.peak_power_w));
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    b.components_j[i] += float(energy.components_j[i]);
  const LineKind kind = line_kind(command.kind);
  if (b.commands == 0 || kind_rank(kind) > kind_rank(b.kind)) b.kind = kind;
  if (b.commands++ == 0) b.start_s = timed.start_s;
  b.time_s += timed.duration_s;
  b.end_s = std::max(b.end_s, timed.start_s + timed.duration_s);
  b.length_mm += float(timed.length_mm);
  b.peak_speed_mm_s = std::max(b.peak_speed_mm_s, float(timed.peak_speed_mm_s));
  if (is_move(command.kind)) {
    if (!b.has_move) b.entry_speed_mm_s = float(timed.entry_speed_mm_s);
    b.exit_speed_mm_s = float(timed.exit_speed_mm_s);
    b.has_move = true;
  }
  if (!timed.note.empty() && b.note == 0) b.note = note_index(timed.note);
  if (energy.spindle_load > 1 && !stock_guessed) {
    if (b.spindle_load <= 1) {
      ++overloaded_;
      if (first_overloaded_line_ < 0) first_overloaded_line_ = timed.line;
    }
    if (energy.spindle_load > worst_load_) {
      worst_load_ = energy.spindle_load;
      worst_load_line_ = timed.line;
    }
  }
  b.spindle_load = std::max(b.spindle_load, float(energy.spindle_load));
  if (b.operation == 0) b.operation = std::uint16_t(std::min<std::size_t>(operation + 1, 65535));
}

// The power and MRR series, and the path: one point per end of every segment.
void ResultFolder::follow_path(const CanonCommand& command, const TimedCommand& timed,
                               const std::vector<OperatingSegment>& segments,
                               const std::vector<SegmentPower>& powers) {
  const bool move = is_move(command.kind);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const OperatingSegment& seg = segments[i];
    if (!(seg.t1_s > seg.t0_s)) continue; // instants draw nothing
    power_.add(seg.t0_s, powers[i].start_w);
    power_.add(seg.t1_s, powers[i].end_w);
    mrr_.add(seg.t0_s, seg.start.mrr_mm3_s);
    mrr_.add(seg.t1_s, seg.end.mrr_mm3_s);
  }
  if (!move) return;
  // Path points at the move's samples (or its ends), with the power of the step that ends there.
  const std::vector<MotionSample>& samples = timed.samples;
  std::size_t s = 0;
  auto power_at = [&](double t) {
    while (s + 1 < segments.size() && segments[s].t1_s < t)
      ++s;
    if (segments.empty()) return std::pair{0.0, 0.0};
    return std::pair{powers[s].end_w, segments[s].end.mrr_mm3_s};
  };
  auto add = [&](const Pose& at, double t) {
    const auto [power, mrr] = power_at(t);
    path_.add({float(at.x), float(at.y), float(at.z), float(power), float(mrr), timed.line,
               command.kind == CanonKind::Traverse});
  };
  if (samples.size() >= 2) {
    for (const MotionSample& m : samples)
      add(m.position, m.t_s);
  } else {
    add(command.start, timed.start_s);
    add(command.end, timed.start_s + timed.duration_s);
  }
}

std::uint16_t ResultFolder::note_index(const std::string& note) {
  const auto it = notes_.find(note);
  if (it != notes_.end()) return it->second;
  if (out_.notes.size() >= 65535) return 0;
  out_.notes.push_back(note);
  const std::uint16_t index = std::uint16_t(out_.notes.size());
  notes_.emplace(note, index);
  return index;
}

void ResultFolder::finish(double total_s) {
  out_.time_s = total_s;
  out_.time = time_;
  out_.energy = energy_.totals(total_s);
  for (Diagnostic d : out_.energy.diagnostics) {
    d.file = source_.path;
    out_.diagnostics.push_back(std::move(d));
  }
  out_.energy.diagnostics.clear();
  if (overloaded_ > 0) {
    const bool placeholder = power_constants_.placeholder_spindle;
    const char* reading =
        placeholder ? "this profile's rating is a placeholder, so this says only that the cut is "
                      "far beyond what the profile was fitted on "
                    : "the cut would stall, or the CAM feeds and speeds are wrong";
    char text[520];
    std::snprintf(text, sizeof text,
                  "%zu block(s) ask the spindle for more than its rated power, the first at line "
                  "%d, up to %.0f%% of the rating at line %d: %s%s",
                  overloaded_, first_overloaded_line_ + 1, 100 * worst_load_, worst_load_line_ + 1,
                  reading, placeholder ? kPlaceholderSpindleAdvice : "");
    out_.diagnostics.push_back(
        {Severity::Warning, source_.path, first_overloaded_line_ + 1, 0, text});
  }
  if (guess_.overload_blocks > 0) {
    // Under a guessed stock the likelier reading is the guess: material the CAM knew was gone
    // (rest machining, a lead-in from outside the part) is cut there.
    char text[640];
    std::snprintf(text, sizeof text,
                  "the guessed stock is wrong where %zu block(s) would ask the spindle for more "
                  "than its rated power (the first at line %d, up to %.0f%% of the rating at line "
                  "%d): the CAM knew the material there was gone (rest machining, a lead-in from "
                  "outside the part). Their cutting is left out of the peak power (%.0f W with "
                  "it); give the stock to know the real cut",
                  guess_.overload_blocks, guess_.first_overload_line + 1, 100 * guess_.worst_load,
                  guess_.worst_overload_line + 1, out_.energy.peak_power_w);
    out_.diagnostics.push_back(
        {Severity::Warning, source_.path, guess_.first_overload_line + 1, 0, text});
  }
  if (guess_.guessed) {
    guess_.peak_power_guess_w = out_.energy.peak_power_w;
    out_.energy.peak_power_w = plausible_peak_w_;
  }
  out_.stock_guess = guess_;
  if (std::any_of(removals_.begin(), removals_.end(),
                  [](const RemovalSimulator* r) { return r->ready(); })) {
    out_.removal = merged_removal();
    out_.removal->diagnostics.clear(); // the estimate's diagnostics have them
    out_.energy.removed_mm3 = out_.removal->removed_mm3;
    out_.energy.sec_j_mm3 =
        out_.energy.removed_mm3 > 0 ? out_.energy.energy_j / out_.energy.removed_mm3 : 0.0;
  }
  for (std::size_t k = 0; k < setup_totals_.size() && k < removals_.size(); ++k) {
    const RemovalResult r = removals_[k]->summary();
    setup_totals_[k].stock = r.stock_description;
    setup_totals_[k].stock_source = r.stock_source;
    setup_totals_[k].stock_from = r.stock_from;
    setup_totals_[k].stock_origin = r.stock_origin;
    if (r.stock_source != StockSource::None) setup_totals_[k].stock_box = r.stock_box;
  }
  out_.setups = setup_totals_;
  out_.series.power_w = power_.result();
  out_.series.mrr_mm3_s = mrr_.result();
  out_.path = path_.result();

  lines_.resize(line_count_); // the lines after the last that ran
  // Operations: names look no further than the lines that cut.
  std::vector<std::uint16_t> index_map;
  out_.operations = operations_.finish(
      [this](int line) {
        if (line < 0 || std::size_t(line) >= lines_.size()) return false;
        const LineKind k = lines_[std::size_t(line)].kind;
        return lines_[std::size_t(line)].commands > 0 &&
               (k == LineKind::Feed || k == LineKind::Arc || k == LineKind::Probe);
      },
      out_.energy, index_map);

  // Lines of comments only are left out; lines with code are kept even when they take no time
  // (G90, G21), so that every block of the program has its entry.
  // A line that issues no command (G17 G90) is read when the line before it has run: that is its
  // start and end, so a column of start times stays in step with the program.
  std::size_t kept = 0;
  double read_at = 0;
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    LineSummary& b = lines_[i];
    if (b.commands > 0)
      read_at = b.end_s;
    else
      b.start_s = b.end_s = read_at;
    const bool acts = b.commands > 0 && kind_rank(b.kind) > 0;
    if (!acts && !line_comments(source_.line_text(i), dialect_).has_code) continue;
    b.line = std::int32_t(i);
    if (b.operation > 0 && b.operation <= index_map.size())
      b.operation = index_map[b.operation - 1];
    lines_[kept++] = b;
  }
  lines_.resize(kept);
  // Shrinking copies: worth it only when much was dropped (a copy would double the peak).
  if (kept < lines_.capacity() / 2) lines_.shrink_to_fit();
  out_.lines = std::move(lines_);
}

} // namespace ncjoule::estimate_detail
