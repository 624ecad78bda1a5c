// Logs of a known machine: a program planned on a profile whose timing keys the test knows, its
// line changes written as SHDR the way a control logs them (each line when it starts, a run
// from ACTIVE to PROGRAM_COMPLETED), so that a fit from another profile must find those keys.
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ncjoule/calibrate_timing.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule::test {

inline MachineProfile shipped_profile(const std::string& name) {
  return load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/" + name + ".toml");
}

// A small job in the Hurco's style: two tools, M1 between them, coolant, rapids, chains of feed
// lines at two feeds, a drilled row, M30.
inline const char* kSyntheticProgram = R"(%
O0001(SYNTHETIC)
N10 G20
N20 G0 G17 G40 G49 G80 G90
N30 T1 M6
N40 G0 G90 G54 X1. Y1. S8000 M3
N50 Z.25 M8
N60 Z.1
N70 G1 Z-.1 F40.
N80 X2.
N90 Y1.5
N100 X1.
N110 Y1.
N120 X1.1 F120.
N130 X1.2
N140 X1.3
N150 X1.4
N160 X1.5
N170 X1.6
N180 X1.7
N190 X1.8
N200 X1.9
N210 X2.
N220 G0 Z.25
N230 X4. Y3.
N240 Z.1
N250 G1 Z-.05 F30.
N260 X5. F150.
N270 Y4.
N280 X4.
N290 Y3.
N300 G0 Z.25
N310 M5
N320 G91 G28 Z0. M9
N330 M01
N340 T2 M6
N350 G0 G90 G54 X.5 Y.5 S4000 M3
N360 Z.25 M8
N370 Z.1
N380 G1 Z-.2 F20.
N390 G0 Z.1
N400 X1.5
N410 G1 Z-.2 F20.
N420 G0 Z.1
N430 X2.5
N440 G1 Z-.2 F20.
N450 G0 Z.25
N460 X6. Y-2.
N470 M5
N480 G91 G28 Z0. M9
N490 M30
%
)";

// The run's SHDR: ACTIVE, then each line with time when it starts, PROGRAM_COMPLETED. `jitter`
// moves each change by up to that many seconds (deterministic), as a sample period does.
inline std::string synthetic_run(const Estimate& e, double t0, double jitter, int seed,
                                 double rapid_override_pct = -1) {
  auto stamp = [](double t) {
    const long long whole = static_cast<long long>(std::floor(t));
    const double frac = t - double(whole);
    char text[64];
    const int s = int(whole % 60), m = int(whole / 60 % 60), h = int(whole / 3600 % 24);
    std::snprintf(text, sizeof text, "2020-03-02T%02d:%02d:%02d.%06dZ", h, m, s,
                  int(std::lround(frac * 1e6)) % 1000000);
    return std::string(text);
  };
  std::string out;
  if (rapid_override_pct >= 0)
    out += stamp(t0 - 5) + "|Rapid_Override|" + std::to_string(rapid_override_pct) + "\n";
  out += stamp(t0 - 2) + "|program|SYNTHETIC.NC|line|0\n";
  out += stamp(t0) + "|execution|ACTIVE\n";
  unsigned state = unsigned(seed) * 2654435761u + 1;
  for (const LineSummary& l : e.lines) {
    if (l.time_s <= 0) continue;
    state = state * 1664525u + 1013904223u;
    const double noise = jitter * (double(state >> 8) / double(1u << 24) - 0.5) * 2;
    out +=
        stamp(t0 + l.start_s + std::max(0.0, noise)) + "|line|" + std::to_string(l.line + 1) + "\n";
  }
  out += stamp(t0 + e.time_s) + "|execution|PROGRAM_COMPLETED\n";
  return out;
}

// Evidence from runs of `program`, run k planned on truths[k], compared with `machine`.
inline LogEvidence synthetic_evidence_of(const std::vector<MachineProfile>& truths,
                                         const MachineProfile& machine, double jitter,
                                         double rapid_override_pct = -1,
                                         const char* program = kSyntheticProgram) {
  LogEvidence evidence;
  LoggedProgram p;
  p.source = make_source("synthetic.nc", program);
  p.outline = outline_program(p.source);
  p.options.simulate_removal = false;
  std::string shdr;
  for (std::size_t k = 0; k < truths.size(); ++k) {
    MachineProfile true_run = truths[k];
    if (rapid_override_pct >= 0)
      for (AxisLimits& a : true_run.kinematics.axes)
        a.rapid_mm_s *= rapid_override_pct / 100;
    const Estimate e = estimate_program(p.source, true_run, p.options);
    shdr += synthetic_run(e, 3600.0 * double(k + 1), jitter, int(k) + 1, rapid_override_pct);
  }
  std::vector<Diagnostic> d;
  LogMapping mapping;
  mapping.items[LogSignal::RapidOverride] = "Rapid_Override";
  LogReadOptions read;
  read.mapping = &mapping;
  REQUIRE(parse_controller_log(shdr, "synthetic.shdr", evidence.log, read, d));
  finish_controller_log(evidence.log, d);
  evidence.runs = find_runs(evidence.log);
  p.estimate = estimate_program(p.source, machine, p.options);
  evidence.programs.push_back(std::move(p));
  gather_runs(evidence);
  return evidence;
}

// Evidence from `runs` runs of `program` planned on `truth`, compared with `machine`.
inline LogEvidence synthetic_evidence(const MachineProfile& truth, const MachineProfile& machine,
                                      int runs, double jitter, double rapid_override_pct = -1,
                                      const char* program = kSyntheticProgram) {
  return synthetic_evidence_of(std::vector<MachineProfile>(std::size_t(runs), truth), machine,
                               jitter, rapid_override_pct, program);
}

inline std::vector<LineTimes> plan_all(const LogEvidence& e, const MachineProfile& machine) {
  std::vector<LineTimes> times;
  for (std::size_t p = 0; p < e.programs.size(); ++p)
    times.push_back(plan_line_times(e.programs[p], machine, needs_rapid_override(e, p)));
  return times;
}

inline const FittedTimingKey& key_of(const TimingFit& fit, TimingKey k) {
  for (const FittedTimingKey& f : fit.keys)
    if (f.key == k) return f;
  FAIL("key not in the fit");
  return fit.keys.front();
}

} // namespace ncjoule::test
