// What the report draws of a program's logged runs: the line each usable run had reached over
// time beside the line the prediction reaches, and the check's figures as the report's rows.
#include <algorithm>
#include <cmath>

#include "ncjoule/calibrate_timing.hpp"

namespace ncjoule {
namespace {

MeasuredOverlay::Figure figure(const std::string& name, const MeasuredRange& measured,
                               double predicted_s) {
  MeasuredOverlay::Figure f;
  f.name = name;
  f.median_s = measured.median;
  f.min_s = measured.min;
  f.max_s = measured.max;
  f.runs = measured.runs;
  f.predicted_s = predicted_s;
  return f;
}

// A step line: each line held from when it was reached until the next one was.
void add_step(Series& s, double t_s, double line) {
  if (!s.value.empty()) {
    if (s.value.back() == line) return;
    s.t_s.push_back(t_s);
    s.value.push_back(s.value.back());
  }
  s.t_s.push_back(t_s);
  s.value.push_back(line);
}

void finish_step(Series& s, double end_s) {
  if (s.value.empty()) return;
  s.t_s.push_back(end_s);
  s.value.push_back(s.value.back());
}

Series measured_progress(const LogEvidence& e, const LoggedRun& r) {
  const LogRun& run = e.runs[r.run];
  Series s;
  for (const TimedValue& m : e.alignments[r.run].marks)
    add_step(s, std::max(0.0, m.t_s - run.start_s), m.value);
  finish_step(s, run.end_s - run.start_s);
  return s;
}

// The prediction's line over time at the overrides the run was logged at, stretch by stretch (as
// check_programs predicts it).
Series predicted_progress(const LogEvidence& e, const LoggedRun& r, const LineTimes& t) {
  Series s;
  double now = 0;
  const int lines = int(t.a.size());
  for (const LineGroup& g : r.groups) {
    const double rapid = e.rapid_at(r, g.start_s), feed = e.feed_at(r, g.start_s);
    const int end = int(std::min<long long>(g.next, lines));
    for (int l = g.first; l < end; ++l) {
      const double dt = t.between(l, l + 1, rapid, feed);
      if (dt <= 0) continue; // a comment or a modal word: reached and left at once
      add_step(s, now, l);
      now += dt;
    }
  }
  finish_step(s, now);
  return s;
}

std::string lines_label(const BlockCheck& b, int program_lines) {
  if (b.next == b.first + 1 || b.next > program_lines) return std::to_string(b.first);
  return std::to_string(b.first) + "-" + std::to_string(b.next - 1);
}

} // namespace

MeasuredOverlay measured_overlay(const LogEvidence& evidence, const ProgramCheck& check,
                                 const LineTimes& times) {
  MeasuredOverlay o;
  const LoggedProgram& program = evidence.programs[check.program];
  for (const ControllerLog::File& f : evidence.log.files)
    o.logs += (o.logs.empty() ? "" : ", ") + f.path;
  std::vector<const LoggedRun*> usable;
  for (const LoggedRun& r : evidence.program_runs) {
    if (r.program != check.program) continue;
    const LogRun& run = evidence.runs[r.run];
    MeasuredOverlay::Run row;
    row.start = format_log_time(run.start_s);
    row.time_s = r.measured_s;
    row.ended = run.ended;
    row.usable = r.usable;
    for (const std::string& w : r.why)
      row.why += (row.why.empty() ? "" : "; ") + w;
    o.runs.push_back(row);
    if (r.usable) usable.push_back(&r);
  }
  o.usable_runs = check.usable_runs;
  o.total = figure(program.outline.name, check.measured, check.predicted_s);
  for (const OperationCheck& op : check.operations) {
    MeasuredOverlay::Figure f = figure(op.name, op.measured, op.predicted_s);
    f.tool = op.tool;
    f.line = op.line;
    o.operations.push_back(f);
  }
  for (const BlockCheck& b : check.worst_blocks) {
    MeasuredOverlay::Figure f =
        figure(lines_label(b, program.outline.lines) + ": " + b.text, b.measured, b.predicted_s);
    f.line = b.first;
    o.worst_blocks.push_back(f);
  }
  if (usable.empty()) return o;
  // The run of median time is drawn over the others, and the prediction at its overrides.
  std::vector<const LoggedRun*> by_time = usable;
  std::stable_sort(by_time.begin(), by_time.end(), [](const LoggedRun* x, const LoggedRun* y) {
    return x->measured_s < y->measured_s;
  });
  const LoggedRun* median = by_time[(by_time.size() - 1) / 2];
  o.predicted = predicted_progress(evidence, *median, times);
  auto run_number = [&](const LoggedRun* r) {
    std::size_t k = 0;
    for (const LoggedRun& each : evidence.program_runs)
      if (each.program == check.program) {
        ++k;
        if (&each == r) break;
      }
    return k;
  };
  o.measured.push_back({"measured, run " + std::to_string(run_number(median)) +
                            (usable.size() > 1 ? " (median)" : ""),
                        measured_progress(evidence, *median), true});
  for (const LoggedRun* r : usable)
    if (r != median)
      o.measured.push_back(
          {"run " + std::to_string(run_number(r)), measured_progress(evidence, *r), false});
  return o;
}

} // namespace ncjoule
