#include "controller_logs_cli.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/duration.hpp"

namespace ncjoule::cli {
namespace {

bool has_errors(const std::vector<Diagnostic>& diagnostics) {
  return std::any_of(diagnostics.begin(), diagnostics.end(),
                     [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

std::string percent_error(double predicted, double measured) {
  if (!(measured > 0)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f%%", 100 * (predicted - measured) / measured);
  return text;
}

std::string seconds_range(const MeasuredRange& r) {
  char text[80];
  if (r.runs <= 1 || std::abs(r.max - r.min) < 0.05)
    std::snprintf(text, sizeof text, "%.1f", r.median);
  else
    std::snprintf(text, sizeof text, "%.1f (%.1f-%.1f)", r.median, r.min, r.max);
  return text;
}

std::string override_text(bool known, double lo, double hi) {
  if (!known) return "-";
  char text[32];
  if (std::abs(hi - lo) < 0.005)
    std::snprintf(text, sizeof text, "%.0f%%", 100 * lo);
  else
    std::snprintf(text, sizeof text, "%.0f-%.0f%%", 100 * lo, 100 * hi);
  return text;
}

} // namespace

void add_log_options(CLI::App& cmd, LogOptions& o) {
  cmd.add_option("--devices", o.devices,
                 "The MTConnect agent's device file (Devices.xml): gives SHDR item names their "
                 "MTConnect types")
      ->check(CLI::ExistingFile);
  cmd.add_option("--log-mapping", o.mapping,
                 "Mapping file (TOML) for a control whose log names its data otherwise "
                 "(docs/controller-logs.md)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--device", o.device, "Read only this device of the logs (its MTConnect name)");
  cmd.add_option("--line-numbering", o.line_numbering,
                 "What the logged line counts: auto (default: decided per run), file-line, "
                 "file-line-from-zero, n-word")
      ->check(CLI::IsMember({"auto", "file-line", "file-line-from-zero", "n-word"}));
}

int read_evidence(const LogOptions& o, const std::vector<std::string>& programs,
                  const EstimateOptions& estimate_options, const MachineProfile& machine,
                  LogEvidence& evidence, std::vector<LineTimes>& times) {
  std::vector<Diagnostic> diagnostics;
  std::optional<DeviceFile> devices;
  std::optional<LogMapping> mapping;
  if (!o.devices.empty()) devices = read_device_file(o.devices, diagnostics);
  if (!o.mapping.empty()) mapping = read_log_mapping(o.mapping, diagnostics);
  if (has_errors(diagnostics)) {
    print_diagnostics(diagnostics);
    return kInputError;
  }
  LogReadOptions read;
  read.devices = devices ? &*devices : nullptr;
  read.mapping = mapping ? &*mapping : nullptr;
  read.device = o.device;
  bool any = false;
  for (const std::string& path : o.logs)
    any = read_controller_log(path, evidence.log, read, diagnostics) || any;
  finish_controller_log(evidence.log, diagnostics);
  print_diagnostics(diagnostics);
  if (!any) {
    std::fprintf(stderr, "ncjoule: no log could be read (see above)\n");
    return kInputError;
  }
  evidence.runs = find_runs(evidence.log);
  for (const std::string& path : programs) {
    auto source = read_source(path);
    if (!source) return kInputError;
    LoggedProgram p;
    p.outline = outline_program(*source);
    p.source = std::move(*source);
    p.options = estimate_options;
    p.options.simulate_removal = false;
    evidence.programs.push_back(std::move(p));
  }
  EvidenceOptions options;
  if (!o.line_numbering.empty())
    options.align.numbering = *line_numbering_from_name(o.line_numbering);
  else if (mapping)
    options.align.numbering = mapping->line_numbering;
  gather_runs(evidence, options);
  // Plan the programs that have runs; the rest are not needed.
  times.assign(evidence.programs.size(), LineTimes{});
  for (std::size_t p = 0; p < evidence.programs.size(); ++p) {
    LoggedProgram& program = evidence.programs[p];
    const bool has_runs = std::any_of(evidence.program_runs.begin(), evidence.program_runs.end(),
                                      [&](const LoggedRun& r) { return r.program == p; });
    program.estimate = estimate_program(program.source, machine, program.options);
    // Only what stops the comparison: the estimate's own warnings are `ncjoule estimate`'s to say.
    std::vector<Diagnostic> errors;
    for (const Diagnostic& d : program.estimate.diagnostics)
      if (d.severity == Severity::Error) errors.push_back(d);
    print_diagnostics(errors);
    if (program.estimate.failed) {
      std::fprintf(stderr, "ncjoule: %s cannot be estimated (see above)\n",
                   program.source.path.c_str());
      return failed_status(program.estimate);
    }
    if (has_runs)
      times[p] = plan_line_times(program, machine, needs_rapid_override(evidence, p));
    else
      times[p] = plan_line_times(program, machine, false);
  }
  judge_runs(evidence, times, options);
  return kOk;
}

int measured_overlays(const LogOptions& o, const std::vector<std::string>& programs,
                      const std::string& dialect, const MachineProfile& machine,
                      std::vector<MeasuredOverlay>& overlays) {
  EstimateOptions options;
  if (!dialect.empty()) {
    options.dialect = dialect_from_option(dialect);
    if (!options.dialect) return kUsage;
  }
  LogEvidence evidence;
  std::vector<LineTimes> times;
  if (const int status = read_evidence(o, programs, options, machine, evidence, times);
      status != kOk)
    return status;
  const std::vector<ProgramCheck> checks = check_programs(evidence, times);
  for (const ProgramCheck& c : checks) {
    overlays.push_back(measured_overlay(evidence, c, times[c.program]));
    const MeasuredOverlay& m = overlays.back();
    std::fprintf(stderr, "ncjoule: %s: %zu run%s in the logs, %zu usable\n",
                 evidence.programs[c.program].source.path.c_str(), m.runs.size(),
                 m.runs.size() == 1 ? "" : "s", m.usable_runs);
  }
  return kOk;
}

// Every text these tables take from a log (device, item, program and block names, what ended a
// run) or a program (its name, operation names, a line's text) is printed escaped (printable):
// a log or a comment holding ESC ] 0;title BEL does not drive the terminal.
void print_log_summary(const LogEvidence& e) {
  const ControllerLog& log = e.log;
  std::printf("logs\n");
  for (const ControllerLog::File& f : log.files)
    std::printf("  %s: %s, %zu observations, %s to %s\n", printable(f.path).c_str(),
                printable(f.format).c_str(), f.observations, format_log_time(f.first_s).c_str(),
                format_log_time(f.last_s).c_str());
  if (log.coverage.size() > 1)
    std::printf("  the files cover %zu separate stretches of time: a value logged in one is not "
                "taken to hold in the next\n",
                log.coverage.size());
  for (std::size_t d = 0; d < log.devices.size() && d < log.items.size(); ++d) {
    std::string used;
    for (std::size_t s = 0; s < kLogSignalCount; ++s)
      if (!log.items[d][s].empty())
        used += (used.empty() ? "" : ", ") + std::string(log_signal_name(LogSignal(s))) + " = " +
                log.items[d][s];
    if (used.empty()) continue;
    std::printf("  device %s: %s\n",
                log.devices[d].empty() ? "(unnamed)" : printable(log.devices[d]).c_str(),
                printable(used).c_str());
  }
  if (!log.unused_items.empty()) {
    std::printf("  not used:");
    for (std::size_t i = 0; i < log.unused_items.size() && i < 12; ++i)
      std::printf("%s %s", i ? "," : "", printable(log.unused_items[i]).c_str());
    if (log.unused_items.size() > 12) std::printf(", and %zu more", log.unused_items.size() - 12);
    std::printf("\n");
  }
  std::size_t of_programs = e.program_runs.size(), usable = 0;
  for (const LoggedRun& r : e.program_runs)
    usable += r.usable;
  std::printf("  %zu run%s found: %zu of the programs given (%zu usable), %zu of other programs "
              "or none\n",
              e.runs.size(), e.runs.size() == 1 ? "" : "s", of_programs, usable,
              e.runs.size() - of_programs);
}

void print_run_table_legend() {
  std::printf(
      "  feed ovr, rapid ovr: the overrides logged during the run (-: not logged in its part "
      "of the log, taken as 100%%); speed/F: the logged path speed on steady feed lines over "
      "F x the feed override; rapids: the measured over the predicted time of its stretches "
      "of rapids alone\n");
}

void print_run_table(const LogEvidence& e) {
  if (e.program_runs.empty()) return;
  std::printf("runs of the programs given\n");
  std::printf("  %-4s %-20s %-24s %10s %-18s %-9s %-9s %7s %7s %s\n", "run", "start", "program",
              "time s", "ended", "feed ovr", "rapid ovr", "speed/F", "rapids", "usable / why not");
  std::size_t k = 0;
  for (const LoggedRun& r : e.program_runs) {
    const LogRun& run = e.runs[r.run];
    const RunAlignment& a = e.alignments[r.run];
    std::string why;
    for (const std::string& w : r.why)
      why += (why.empty() ? "" : "; ") + w;
    std::string name = printable(e.programs[r.program].outline.name);
    if (name.size() > 24) name = name.substr(0, 21) + "...";
    auto ratio = [](double x) {
      char text[16];
      std::snprintf(text, sizeof text, "%.2f", x);
      return x > 0 ? std::string(text) : std::string("-");
    };
    std::printf(
        "  %-4zu %-20s %-24s %10.1f %-18s %-9s %-9s %7s %7s %s\n", ++k,
        format_log_time(run.start_s).substr(0, 19).c_str(), name.c_str(), r.measured_s,
        printable(run.ended).c_str(),
        override_text(a.feed_override_known, a.feed_override_min, a.feed_override_max).c_str(),
        override_text(a.rapid_override_known, a.rapid_override_min, a.rapid_override_max).c_str(),
        ratio(r.feed_ratio).c_str(), ratio(r.rapid_ratio).c_str(),
        r.usable ? "usable" : printable(why).c_str());
    for (const std::string& n : r.notes)
      if (n.find("not logged") == std::string::npos)
        std::printf("       note: %s\n", printable(n).c_str());
  }
  print_run_table_legend();
}

void print_program_checks(const LogEvidence& e, const std::vector<ProgramCheck>& checks) {
  for (const ProgramCheck& c : checks) {
    const LoggedProgram& p = e.programs[c.program];
    if (c.runs == 0) {
      std::printf("%s: no run in the logs\n", printable(p.source.path).c_str());
      continue;
    }
    if (c.usable_runs == 0) {
      std::printf("%s: %zu run%s, none usable (see the runs above); predicted %.1f s\n",
                  printable(p.source.path).c_str(), c.runs, c.runs > 1 ? "s" : "", c.predicted_s);
      continue;
    }
    std::printf("%s: %zu usable run%s of %zu\n", printable(p.source.path).c_str(), c.usable_runs,
                c.usable_runs > 1 ? "s" : "", c.runs);
    std::printf("  time        measured %s s, predicted %.1f s (%s)\n",
                seconds_range(c.measured).c_str(), c.predicted_s,
                percent_error(c.predicted_s, c.measured.median).c_str());
    std::size_t width = 9;
    for (const OperationCheck& op : c.operations)
      width = std::max(width, printable(op.name).size());
    std::printf("  by operation (measured: median of the usable runs, and their range):\n");
    std::printf("    %-*s %4s %5s %22s %12s %8s\n", int(width), "operation", "tool", "line",
                "measured s", "predicted s", "error");
    for (const OperationCheck& op : c.operations)
      std::printf("    %-*s %4s %5d %22s %12.1f %8s\n", int(width), printable(op.name).c_str(),
                  op.tool > 0 ? ("T" + std::to_string(op.tool)).c_str() : "-", op.line,
                  seconds_range(op.measured).c_str(), op.predicted_s,
                  percent_error(op.predicted_s, op.measured.median).c_str());
    if (!c.worst_blocks.empty()) {
      std::printf("  worst blocks (stretches of 0.5 s or more as the log shows them; lines "
                  "first to next):\n");
      std::printf("    %-11s %-48s %12s %12s %8s\n", "lines", "its longest line", "measured s",
                  "predicted s", "error");
      for (const BlockCheck& b : c.worst_blocks) {
        const std::string lines = b.next == b.first + 1 || b.next > p.outline.lines
                                      ? std::to_string(b.first)
                                      : std::to_string(b.first) + "-" + std::to_string(b.next - 1);
        std::printf("    %-11s %-48s %12.2f %12.2f %8s\n", lines.c_str(), printable(b.text).c_str(),
                    b.measured.median, b.predicted_s,
                    percent_error(b.predicted_s, b.measured.median).c_str());
      }
    }
  }
}

std::string check_json(const LogEvidence& e, const std::vector<ProgramCheck>& checks,
                       const MachineProfile& machine) {
  using nlohmann::json;
  auto range = [](const MeasuredRange& r) {
    return json{{"median_s", r.median}, {"min_s", r.min}, {"max_s", r.max}, {"runs", r.runs}};
  };
  json doc;
  doc["machine"] = machine.name;
  doc["profile"] = machine.source_path;
  json runs = json::array();
  for (const LoggedRun& r : e.program_runs) {
    const LogRun& run = e.runs[r.run];
    const RunAlignment& a = e.alignments[r.run];
    json j{{"program", e.programs[r.program].source.path},
           {"start", format_log_time(run.start_s)},
           {"time_s", r.measured_s},
           {"ended", run.ended},
           {"usable", r.usable},
           {"why_not", r.why},
           {"notes", r.notes},
           {"line_numbering", std::string(line_numbering_name(a.numbering))}};
    if (a.feed_override_known) j["feed_override"] = {a.feed_override_min, a.feed_override_max};
    if (a.rapid_override_known) j["rapid_override"] = {a.rapid_override_min, a.rapid_override_max};
    if (r.feed_ratio > 0) j["speed_over_feed"] = r.feed_ratio;
    if (r.rapid_ratio > 0) j["rapids_over_predicted"] = r.rapid_ratio;
    runs.push_back(j);
  }
  doc["runs"] = runs;
  doc["other_runs"] = e.runs.size() - e.program_runs.size();
  json programs = json::array();
  for (const ProgramCheck& c : checks) {
    json p{{"program", e.programs[c.program].source.path},
           {"runs", c.runs},
           {"usable_runs", c.usable_runs},
           {"predicted_s", c.predicted_s}};
    if (c.usable_runs > 0) p["measured"] = range(c.measured);
    json ops = json::array();
    for (const OperationCheck& op : c.operations)
      ops.push_back({{"name", op.name},
                     {"tool", op.tool},
                     {"line", op.line},
                     {"measured", range(op.measured)},
                     {"predicted_s", op.predicted_s}});
    p["operations"] = ops;
    json blocks = json::array();
    for (const BlockCheck& b : c.worst_blocks)
      blocks.push_back({{"first_line", b.first},
                        {"next_line", b.next},
                        {"text", b.text},
                        {"measured", range(b.measured)},
                        {"predicted_s", b.predicted_s}});
    p["worst_blocks"] = blocks;
    programs.push_back(p);
  }
  doc["programs"] = programs;
  return doc.dump(1);
}

} // namespace ncjoule::cli
