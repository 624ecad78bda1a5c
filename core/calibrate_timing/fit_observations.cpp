// The fit's observations: the undisturbed stretches of the usable runs, as the fit weighs them.
#include <algorithm>
#include <optional>

#include "timing_model.hpp"

namespace ncjoule::timing_detail {

std::vector<Observation> fit_observations(const LogEvidence& evidence,
                                          const TimingFitOptions& options, std::size_t& runs_used,
                                          std::vector<std::string>& notes) {
  // The observations: the undisturbed stretches of every usable run, consecutive ones joined
  // until they last min_stretch_s (a line's time the log gives to its neighbour is then inside
  // one observation), none across a change of override. A run whose rapid override was not
  // logged gives its stretches without rapids only.
  std::vector<Observation> observations;
  std::vector<char> run_used(evidence.program_runs.size(), 0);
  notes.clear();
  std::size_t left_out_rapid = 0;
  for (std::size_t i = 0; i < evidence.program_runs.size(); ++i) {
    const LoggedRun& r = evidence.program_runs[i];
    if (!r.usable) continue;
    // Unknown only where the log holds a rapid override at all: a log that never records one is
    // taken to run at 100%.
    const std::size_t device = evidence.runs[r.run].device;
    const bool logs_overrides =
        device < evidence.log.items.size() &&
        !evidence.log.items[device][std::size_t(LogSignal::RapidOverride)].empty();
    const bool rapid_known = evidence.alignments[r.run].rapid_override_known || !logs_overrides;
    const Estimate& e = evidence.programs[r.program].estimate;
    std::vector<int> rapid_before(evidence.programs[r.program].source.lines.size() + 2, 0);
    for (const LineSummary& l : e.lines)
      if (l.kind == LineKind::Rapid && l.time_s > 0 &&
          std::size_t(l.line) + 2 < rapid_before.size())
        rapid_before[std::size_t(l.line) + 2] = 1; // marks line l+1 (1-based); summed below
    for (std::size_t l = 1; l < rapid_before.size(); ++l)
      rapid_before[l] += rapid_before[l - 1];
    auto has_rapid = [&](int first, int next) {
      const int n = int(rapid_before.size()) - 1;
      return rapid_before[std::size_t(std::min(next, n))] -
                 rapid_before[std::size_t(std::min(first, n))] >
             0;
    };
    std::optional<Observation> open;
    auto close = [&] {
      if (!open) return;
      if (!rapid_known && has_rapid(open->first, open->next))
        ++left_out_rapid;
      else {
        open->sigma_s = options.stretch_sigma_s + options.stretch_sigma_rel * open->measured_s;
        observations.push_back(*open);
        run_used[i] = 1;
      }
      open.reset();
    };
    for (const LineGroup& g : r.groups) {
      if (g.disturbed) {
        close();
        continue;
      }
      const double rapid = evidence.rapid_at(r, g.start_s), feed = evidence.feed_at(r, g.start_s);
      if (open && (open->rapid != rapid || open->feed != feed || open->next != g.first)) close();
      if (!open) {
        open = Observation{};
        open->program = r.program;
        open->run = i;
        open->first = g.first;
        open->rapid = rapid;
        open->feed = feed;
      }
      open->next = g.next;
      open->measured_s += g.duration_s;
      if (open->measured_s >= options.min_stretch_s) close();
    }
    close();
  }
  if (left_out_rapid > 0)
    notes.push_back(std::to_string(left_out_rapid) +
                    " stretches with rapids are left out: their runs' rapid override was not "
                    "logged where the log records it");
  runs_used = std::size_t(std::count(run_used.begin(), run_used.end(), 1));
  return observations;
}

} // namespace ncjoule::timing_detail
