// Runs: each device's observations cut from cycle start (EXECUTION ACTIVE) to program end, with
// what happened during each: the lines, the path and spindle speeds, the overrides, the holds.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include "ncjoule/logs.hpp"

namespace ncjoule {
namespace {

bool ends_run(std::string_view word) {
  return word == "PROGRAM_COMPLETED" || word == "READY" || word == "STOPPED" ||
         word == "UNAVAILABLE";
}

struct Last {
  bool known = false;
  const LogObservation* o = nullptr;
};

std::string at_time(double t) {
  return format_log_time(t).substr(11, 8);
}

struct RunBuilder {
  const ControllerLog& log;
  std::vector<LogRun>& runs;
  std::array<Last, kLogSignalCount> last{};
  std::optional<LogRun> run;
  std::array<bool, kLogSignalCount> unavailable_said{};

  // The value in force at the start, when it was logged in the same span of the log.
  const LogObservation* in_force(LogSignal s, double t) const {
    const Last& l = last[static_cast<std::size_t>(s)];
    if (!l.known || l.o->unavailable) return nullptr;
    if (log.span_of(l.o->t_s) != log.span_of(t)) return nullptr;
    return l.o;
  }

  void start(const LogObservation& o) {
    run.emplace();
    run->device = o.device;
    run->start_s = o.t_s;
    unavailable_said = {};
    // The line and tool in force keep the time they were logged (before the start): alignment
    // tells them from what the control logs as the run begins.
    if (const LogObservation* line = in_force(LogSignal::Line, o.t_s))
      run->lines.push_back({line->t_s, line->value});
    if (const LogObservation* p = in_force(LogSignal::Program, o.t_s)) run->program = log.text(*p);
    const std::pair<LogSignal, std::vector<TimedValue>*> with_start[] = {
        {LogSignal::FeedOverride, &run->feed_override},
        {LogSignal::RapidOverride, &run->rapid_override},
        {LogSignal::SpindleOverride, &run->spindle_override},
        {LogSignal::PathFeedrate, &run->feed},
        {LogSignal::SpindleSpeed, &run->spindle},
        {LogSignal::Tool, &run->tool}};
    for (const auto& [signal, values] : with_start)
      if (const LogObservation* v = in_force(signal, o.t_s))
        values->push_back({signal == LogSignal::Tool ? v->t_s : o.t_s, v->value});
  }

  void finish(double t, std::string ended) {
    run->end_s = t;
    run->ended = std::move(ended);
    const int span = log.span_of(run->start_s);
    if (span < 0 || run->end_s > log.coverage[std::size_t(span)].second + 1e-6)
      run->data_problems.push_back(
          "the log has a gap inside the run (its file ends at " +
          at_time(span < 0 ? run->start_s : log.coverage[std::size_t(span)].second) + ")");
    for (double jump : log.clock_jumps)
      if (jump >= run->start_s - 1 && jump <= run->end_s + 1) {
        run->data_problems.push_back("the clock jumps inside the run (at " + at_time(jump) + ")");
        break;
      }
    runs.push_back(std::move(*run));
    run.reset();
  }

  void record(const LogObservation& o) {
    if (o.unavailable) {
      auto& said = unavailable_said[static_cast<std::size_t>(o.signal)];
      if (!said && o.signal != LogSignal::Block && o.signal != LogSignal::Current &&
          o.signal != LogSignal::Power && o.signal != LogSignal::SpindleLoad)
        run->data_problems.push_back(std::string(log_signal_name(o.signal)) + " UNAVAILABLE at " +
                                     at_time(o.t_s) + " (the agent lost the control's data)");
      said = true;
      return;
    }
    switch (o.signal) {
    case LogSignal::Line:
      if (run->lines.empty() || run->lines.back().value != o.value)
        run->lines.push_back({o.t_s, o.value});
      break;
    case LogSignal::Program:
      if (run->program.empty()) run->program = log.text(o);
      break;
    case LogSignal::Block:
      run->blocks.emplace_back(o.t_s, log.text(o));
      break;
    case LogSignal::PathFeedrate:
      run->feed.push_back({o.t_s, o.value});
      break;
    case LogSignal::SpindleSpeed:
      run->spindle.push_back({o.t_s, o.value});
      break;
    case LogSignal::SpindleLoad:
      run->spindle_load.push_back({o.t_s, o.value});
      break;
    case LogSignal::Power:
      run->power.push_back({o.t_s, o.value});
      break;
    case LogSignal::Current:
      run->current.push_back({o.t_s, o.value});
      break;
    case LogSignal::Tool:
      run->tool.push_back({o.t_s, o.value});
      break;
    case LogSignal::FeedOverride:
      run->feed_override.push_back({o.t_s, o.value});
      break;
    case LogSignal::RapidOverride:
      run->rapid_override.push_back({o.t_s, o.value});
      break;
    case LogSignal::SpindleOverride:
      run->spindle_override.push_back({o.t_s, o.value});
      break;
    default:
      break;
    }
  }

  void feed(const LogObservation& o) {
    if (o.signal == LogSignal::Execution) {
      const std::string word = o.unavailable ? "UNAVAILABLE" : log.text(o);
      if (!run) {
        if (word == "ACTIVE") start(o);
      } else if (ends_run(word)) {
        finish(o.t_s, word);
      } else {
        run->states.emplace_back(o.t_s, word);
      }
    } else if (run && o.signal == LogSignal::Availability &&
               (o.unavailable || log.text(o) == "UNAVAILABLE")) {
      finish(o.t_s, "UNAVAILABLE");
    } else if (run) {
      record(o);
    }
    Last& l = last[static_cast<std::size_t>(o.signal)];
    l.known = true;
    l.o = &o;
  }
};

} // namespace

std::vector<LogRun> find_runs(const ControllerLog& log) {
  std::vector<LogRun> runs;
  for (std::size_t d = 0; d < log.devices.size(); ++d) {
    RunBuilder builder{log, runs, {}, std::nullopt, {}};
    double last_t = 0;
    for (const LogObservation& o : log.observations) {
      if (o.device != d) continue;
      builder.feed(o);
      last_t = o.t_s;
    }
    if (builder.run) builder.finish(last_t, "end of log");
  }
  std::stable_sort(runs.begin(), runs.end(),
                   [](const LogRun& a, const LogRun& b) { return a.start_s < b.start_s; });
  return runs;
}

} // namespace ncjoule
