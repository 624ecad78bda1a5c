// A run whose lines fit several programs alike (one toolpath posted at several feeds, a test
// plan of feeds and speeds) is taken as the program whose feeds its logged path speeds show,
// whatever order the programs are given in: the first given is not the one that ran.
#include "synthetic_log.hpp"

#include <algorithm>
#include <utility>

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

// The same lines at a feed of `feed` mm/min on the long cuts.
std::string program_at(int feed) {
  const std::string f = std::to_string(feed);
  return "%\nO0002(ALIKE)\nN10 G21\nN20 G0 G17 G40 G49 G80 G90\nN30 T1 M6\n"
         "N40 G0 G54 X0 Y0 S6000 M3\nN50 Z5.\nN60 G1 Z-1. F300.\nN70 G1 X60. F" +
         f +
         ".\nN80 Y20.\nN90 X0.\nN100 Y40.\nN110 X60.\nN120 Y60.\nN130 X0.\nN140 Y80.\n"
         "N150 G0 Z5.\nN160 M30\n%\n";
}

LoggedProgram logged(const std::string& name, const std::string& text, const MachineProfile& m) {
  LoggedProgram p;
  p.source = make_source(name, text);
  p.outline = outline_program(p.source);
  p.options.simulate_removal = false;
  p.estimate = estimate_program(p.source, m, p.options);
  return p;
}

// One run of `ran` as a control logs it: each line when it starts, and the path speed half a
// second into each feed line of a second or more (the estimate's peak speed there).
std::string run_log(const Estimate& ran) {
  const double t0 = 3600;
  std::vector<std::pair<double, std::string>> records{
      {t0 - 2, "line|0"},
      {t0, "execution|ACTIVE"},
      {t0 + ran.time_s, "execution|PROGRAM_COMPLETED"}};
  for (const LineSummary& l : ran.lines) {
    if (l.time_s <= 0) continue;
    records.emplace_back(t0 + l.start_s, "line|" + std::to_string(l.line + 1));
    if (l.kind == LineKind::Feed && l.time_s >= 1.0)
      records.emplace_back(t0 + l.start_s + 0.5,
                           "path_feedrate|" + std::to_string(l.peak_speed_mm_s));
  }
  std::stable_sort(records.begin(), records.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string out;
  for (const auto& [t, text] : records) {
    char stamp[64];
    std::snprintf(stamp, sizeof stamp, "2020-03-02T%02d:%02d:%09.6fZ|", int(t / 3600),
                  int(std::fmod(t, 3600) / 60), std::fmod(t, 60.0));
    out += stamp + text + "\n";
  }
  return out;
}

} // namespace

TEST_CASE("a run that fits programs alike is taken as the one whose feeds it ran") {
  const MachineProfile m = shipped_profile("hurco-vmx24");
  const LoggedProgram slow = logged("ALIKE-600.NC", program_at(600), m);
  const LoggedProgram fast = logged("ALIKE-900.NC", program_at(900), m);
  const LoggedProgram faster = logged("ALIKE-1200.NC", program_at(1200), m);
  const std::string shdr = run_log(fast.estimate);
  for (const std::vector<const LoggedProgram*>& order :
       {std::vector<const LoggedProgram*>{&slow, &fast, &faster},
        std::vector<const LoggedProgram*>{&faster, &slow, &fast}}) {
    LogEvidence evidence;
    std::vector<Diagnostic> d;
    REQUIRE(parse_controller_log(shdr, "alike.shdr", evidence.log, {}, d));
    finish_controller_log(evidence.log, d);
    evidence.runs = find_runs(evidence.log);
    for (const LoggedProgram* p : order)
      evidence.programs.push_back(*p);
    gather_runs(evidence);
    REQUIRE(evidence.program_runs.size() == 1);
    CHECK(evidence.alignments[evidence.program_runs[0].run].alike.size() == 3);
    judge_runs(evidence, plan_all(evidence, m));
    const LoggedRun& r = evidence.program_runs[0];
    CHECK(evidence.programs[r.program].outline.name == "ALIKE-900.NC");
    CHECK(r.usable);
    CHECK(r.feed_ratio == doctest::Approx(1.0).epsilon(0.02));
    bool said = false;
    for (const std::string& n : r.notes)
      said = said || n.find("taken as ALIKE-900.NC") != std::string::npos;
    CHECK(said);
  }
}
