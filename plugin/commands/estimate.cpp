// `ncjoule estimate FILE --machine PROFILE [--dialect NAME] [--json]`: interprets the program,
// plans it on the machine, and prints its time per block and in total (docs/json.md describes
// the JSON form).
//
// The report is built in two steps so that later stages can add their numbers in one place
// each: the timeline is folded into one BlockSummary per source line, and each summary becomes
// one JSON object in block_json().
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <spdlog/spdlog.h>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/energy.hpp"
#include "ncjoule/kinematics.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/removal.hpp"

namespace ncjoule::cli {
namespace {

using Json = nlohmann::ordered_json;

struct EstimateOptions {
  std::string file;
  std::string machine;
  std::string dialect;
  std::string stock; // "box:..." or an STL file; empty: the box of the cutting moves
  std::string engine = "dexel";
  double grid_mm = 0;
  bool no_removal = false;
  std::optional<double> co2_kg_per_kwh, price_per_kwh;
  bool json = false;
};

// ---------------------------------------------------------------------------------------------
// Per-line summaries
// ---------------------------------------------------------------------------------------------

// Everything the report says about one source line, over every time it ran.
struct BlockSummary {
  int line = 0;                 // 0-based
  std::string kind = "setting"; // what the line does (see kind_name)
  int commands = 0;             // canonical commands the line produced, over all its runs
  double start_s = 0;           // when it first ran
  double time_s = 0;            // over all its runs
  double length_mm = 0;
  double entry_speed_mm_s = 0; // at its first move
  double exit_speed_mm_s = 0;  // at its last move
  double peak_speed_mm_s = 0;
  std::vector<std::string> notes;
  bool has_move = false;
  // Removal and energy, over every time the line ran.
  double removed_mm3 = 0;
  double mrr_peak_mm3_s = 0;
  double energy_j = 0;
  double power_peak_w = 0;
  ComponentValues components_j{};
};

std::string kind_name(CanonKind kind) {
  switch (kind) {
  case CanonKind::Traverse:
    return "rapid";
  case CanonKind::Feed:
    return "feed";
  case CanonKind::Arc:
    return "arc";
  case CanonKind::Probe:
    return "probe";
  case CanonKind::Dwell:
    return "dwell";
  case CanonKind::SelectTool:
    return "select_tool";
  case CanonKind::ChangeTool:
    return "tool_change";
  case CanonKind::SpindleSpeed:
  case CanonKind::SpindleClockwise:
  case CanonKind::SpindleCounterClockwise:
  case CanonKind::SpindleStop:
    return "spindle";
  case CanonKind::MistOn:
  case CanonKind::FloodOn:
  case CanonKind::MistOff:
  case CanonKind::FloodOff:
    return "coolant";
  case CanonKind::ProgramStop:
    return "program_stop";
  case CanonKind::OptionalStop:
    return "optional_stop";
  case CanonKind::ProgramEnd:
    return "program_end";
  case CanonKind::Message:
    return "message";
  case CanonKind::Comment:
    return "comment";
  default:
    return "setting"; // feed rate, units, plane, offsets, path control, ...
  }
}

// Whether a kind says more about a line than another: moves first, then what takes time.
int kind_rank(CanonKind kind) {
  switch (kind) {
  case CanonKind::Arc:
  case CanonKind::Feed:
  case CanonKind::Probe:
    return 5;
  case CanonKind::Traverse:
    return 4;
  case CanonKind::ChangeTool:
  case CanonKind::Dwell:
    return 3;
  case CanonKind::ProgramStop:
  case CanonKind::OptionalStop:
  case CanonKind::ProgramEnd:
  case CanonKind::SpindleSpeed:
  case CanonKind::SpindleClockwise:
  case CanonKind::SpindleCounterClockwise:
  case CanonKind::SpindleStop:
    return 2;
  case CanonKind::Comment:
  case CanonKind::Message:
    return 0;
  default:
    return 1;
  }
}

// True when the line holds something besides comments, whitespace and a '%' tape mark.
bool has_code(std::string_view text, const Dialect& dialect) {
  int depth = 0;
  for (char ch : text) {
    if (dialect.paren_comments && ch == '(') {
      depth = dialect.nested_paren_comments ? depth + 1 : 1;
      continue;
    }
    if (depth > 0) {
      if (ch == ')') --depth;
      continue;
    }
    if (dialect.semicolon_comments && ch == ';') break;
    if (ch == ' ' || ch == '\t' || ch == '%' || ch == '\r' || ch == '\n') continue;
    return true;
  }
  return false;
}

std::vector<BlockSummary> summarise_blocks(const SourceFile& source, const Dialect& dialect,
                                           const Timeline& timeline, const RemovalResult* removal,
                                           const EnergyResult& energy) {
  std::vector<BlockSummary> lines(source.lines.size());
  std::vector<int> best_rank(source.lines.size(), -1);
  for (std::size_t k = 0; k < timeline.commands.size(); ++k) {
    const TimedCommand& c = timeline.commands[k];
    if (c.line < 0 || static_cast<std::size_t>(c.line) >= lines.size()) continue;
    BlockSummary& b = lines[c.line];
    if (removal && k < removal->commands.size()) {
      b.removed_mm3 += removal->commands[k].removed_mm3;
      b.mrr_peak_mm3_s = std::max(b.mrr_peak_mm3_s, removal->commands[k].mrr_peak_mm3_s);
    }
    if (k < energy.commands.size()) {
      const CommandEnergy& e = energy.commands[k];
      b.energy_j += e.energy_j;
      b.power_peak_w = std::max(b.power_peak_w, e.peak_power_w);
      for (std::size_t i = 0; i < kPowerComponentCount; ++i)
        b.components_j[i] += e.components_j[i];
    }
    const bool move = c.kind == CanonKind::Traverse || c.kind == CanonKind::Feed ||
                      c.kind == CanonKind::Arc || c.kind == CanonKind::Probe;
    if (b.commands++ == 0) b.start_s = c.start_s;
    b.time_s += c.duration_s;
    b.length_mm += c.length_mm;
    b.peak_speed_mm_s = std::max(b.peak_speed_mm_s, c.peak_speed_mm_s);
    if (move) {
      if (!b.has_move) b.entry_speed_mm_s = c.entry_speed_mm_s;
      b.exit_speed_mm_s = c.exit_speed_mm_s;
      b.has_move = true;
    }
    if (!c.note.empty() && std::find(b.notes.begin(), b.notes.end(), c.note) == b.notes.end())
      b.notes.push_back(c.note);
    if (kind_rank(c.kind) > best_rank[c.line]) {
      best_rank[c.line] = kind_rank(c.kind);
      b.kind = kind_name(c.kind);
    }
  }
  std::vector<BlockSummary> blocks;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    // Lines of comments only are left out; lines with code are kept even when they take no
    // time (G90, G21), so that every block of the program has its entry.
    const bool acts = lines[i].commands > 0 && best_rank[i] > 0;
    if (!acts && !has_code(source.line_text(i), dialect)) continue;
    lines[i].line = static_cast<int>(i);
    blocks.push_back(std::move(lines[i]));
  }
  return blocks;
}

// ---------------------------------------------------------------------------------------------
// JSON
// ---------------------------------------------------------------------------------------------

const char* severity_name(Severity s) {
  switch (s) {
  case Severity::Note:
    return "note";
  case Severity::Warning:
    return "warning";
  case Severity::Error:
    return "error";
  }
  return "error";
}

Json components_json(const ComponentValues& values) {
  Json j = Json::object();
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    j[std::string(component_name(PowerComponent(i)))] = values[i];
  return j;
}

Json block_json(const BlockSummary& b) {
  Json j;
  j["line"] = b.line + 1;
  j["kind"] = b.kind;
  j["time_s"] = b.time_s;
  j["start_s"] = b.start_s;
  j["length_mm"] = b.length_mm;
  j["entry_speed_mm_s"] = b.entry_speed_mm_s;
  j["exit_speed_mm_s"] = b.exit_speed_mm_s;
  j["peak_speed_mm_s"] = b.peak_speed_mm_s;
  j["commands"] = b.commands;
  j["removed_mm3"] = b.removed_mm3;
  j["mrr_mm3_s"] = b.time_s > 0 ? b.removed_mm3 / b.time_s : 0.0;
  j["mrr_peak_mm3_s"] = b.mrr_peak_mm3_s;
  j["power_w"] = b.time_s > 0 ? b.energy_j / b.time_s : 0.0;
  j["power_peak_w"] = b.power_peak_w;
  j["energy_j"] = b.energy_j;
  j["components"] = components_json(b.components_j);
  if (!b.notes.empty()) j["notes"] = b.notes;
  return j;
}

Json diagnostic_json(const Diagnostic& d) {
  return Json{{"file", d.file},
              {"line", d.line},
              {"column", d.column},
              {"severity", severity_name(d.severity)},
              {"message", d.message}};
}

Json program_json(const SourceFile& source, const MachineProfile& machine, const Dialect& dialect,
                  const Timeline& timeline, const RemovalResult* removal,
                  const EnergyResult& energy, const std::vector<BlockSummary>& blocks,
                  const std::vector<Diagnostic>& diagnostics) {
  Json j;
  j["file"] = source.path;
  j["machine"] = Json{{"name", machine.name},
                      {"file", machine.source_path},
                      {"power_model", energy.model_description}};
  j["dialect"] = dialect.name;
  j["time_s"] = timeline.total_s;
  j["removed_mm3"] = energy.removed_mm3;
  j["stock"] = removal ? removal->stock_description : std::string("not simulated");
  j["energy_j"] = energy.energy_j;
  j["sec_j_mm3"] = energy.sec_j_mm3;
  j["co2_kg"] = energy.co2_kg;
  j["cost"] = energy.cost;
  j["currency"] = energy.currency;
  j["components"] = components_json(energy.components_j);
  Json list = Json::array();
  for (const BlockSummary& b : blocks)
    list.push_back(block_json(b));
  j["blocks"] = std::move(list);
  Json warnings = Json::array();
  for (const Diagnostic& d : diagnostics)
    warnings.push_back(diagnostic_json(d));
  j["warnings"] = std::move(warnings);
  return j;
}

// ---------------------------------------------------------------------------------------------
// Human summary
// ---------------------------------------------------------------------------------------------

std::string clock_text(double seconds) {
  const long whole = static_cast<long>(seconds);
  char text[64];
  if (whole >= 3600)
    std::snprintf(text, sizeof text, "%ld h %02ld min %04.1f s", whole / 3600, whole / 60 % 60,
                  seconds - static_cast<double>(whole / 60 * 60));
  else if (whole >= 60)
    std::snprintf(text, sizeof text, "%ld min %04.1f s", whole / 60,
                  seconds - static_cast<double>(whole / 60 * 60));
  else
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  return text;
}

// Where the program's time goes, by what the machine does.
struct TimeBreakdown {
  double rapid_s = 0, cutting_s = 0, tool_change_s = 0, other_s = 0;
  int tool_changes = 0;
};

TimeBreakdown break_down(const Timeline& timeline) {
  TimeBreakdown b;
  for (const TimedCommand& c : timeline.commands) {
    switch (c.kind) {
    case CanonKind::Traverse:
      b.rapid_s += c.duration_s;
      break;
    case CanonKind::Feed:
    case CanonKind::Arc:
    case CanonKind::Probe:
      b.cutting_s += c.duration_s;
      break;
    case CanonKind::ChangeTool:
      b.tool_change_s += c.duration_s;
      ++b.tool_changes;
      break;
    default:
      b.other_s += c.duration_s;
      break;
    }
  }
  return b;
}

void print_summary(const SourceFile& source, const MachineProfile& machine,
                   const Timeline& timeline, const EnergyResult& energy, std::size_t block_count) {
  const TimeBreakdown b = break_down(timeline);
  std::printf("%s on %s\n", source.path.c_str(), machine.name.c_str());
  std::printf("  time        %s (%.3f s), %zu blocks\n", clock_text(timeline.total_s).c_str(),
              timeline.total_s, block_count);
  std::printf("  rapids      %s\n", clock_text(b.rapid_s).c_str());
  std::printf("  feed moves  %s\n", clock_text(b.cutting_s).c_str());
  std::printf("  tool change %s (%d)\n", clock_text(b.tool_change_s).c_str(), b.tool_changes);
  std::printf("  other       %s (dwell, spindle ramps)\n", clock_text(b.other_s).c_str());
  std::printf("  energy      %.4f kWh (%.1f kJ), mean power %.0f W, peak %.0f W\n",
              energy.energy_j / 3.6e6, energy.energy_j / 1000, energy.mean_power_w,
              energy.peak_power_w);
  std::printf("  removed     %.0f mm^3, SEC %.2f J/mm^3\n", energy.removed_mm3, energy.sec_j_mm3);
  std::printf("  CO2         %.4f kg, cost %.4f %s\n", energy.co2_kg, energy.cost,
              energy.currency.c_str());
  for (std::size_t i = 0; i < kPowerComponentCount; ++i) {
    if (energy.components_j[i] == 0) continue;
    std::printf("    %-12s %10.1f kJ (%.1f%%)\n",
                std::string(component_name(PowerComponent(i))).c_str(),
                energy.components_j[i] / 1000,
                energy.energy_j > 0 ? 100 * energy.components_j[i] / energy.energy_j : 0.0);
  }
}

// ---------------------------------------------------------------------------------------------

int run_estimate(const EstimateOptions& o) {
  MachineProfile machine;
  try {
    machine = load_profile(o.machine);
  } catch (const ProfileError& e) {
    std::cerr << "ncjoule: bad machine profile: " << e.what() << '\n';
    return kInputError;
  }
  auto source = read_source(o.file);
  if (!source) return kInputError;

  InterpreterOptions options;
  if (!o.dialect.empty()) {
    options.dialect = dialect_from_option(o.dialect);
    if (!options.dialect) return kUsage;
  } else {
    // The machine's controller reads the program (load_profile checked the name).
    options.dialect = find_dialect(machine.dialect);
  }
  // Stage times go to the log (-v): bench/planner.sh reads them.
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  Toolpath toolpath = interpret(*source, options);
  const auto t1 = Clock::now();
  // Tools come from the program's header comments; removal needs every tool it uses.
  std::vector<Diagnostic> diagnostics = toolpath.result.diagnostics;
  std::map<int, Tool> tools = parse_tool_comments(*source, diagnostics);
  std::optional<StockSpec> stock;
  if (!o.no_removal) {
    std::vector<Diagnostic> missing = check_tools_defined(toolpath.commands, tools, source->path);
    if (!missing.empty()) {
      print_diagnostics(diagnostics);
      print_diagnostics(missing);
      std::cerr << "ncjoule: define the tools in the program's header comments, or run with "
                   "--no-removal to estimate without material removal\n";
      return kInputError;
    }
    if (!o.stock.empty()) {
      std::string error;
      stock = parse_stock_spec(o.stock, &error);
      if (!stock) {
        std::cerr << "ncjoule: bad --stock '" << o.stock << "': " << error << '\n';
        return kUsage;
      }
    } else {
      stock = StockSpec{}; // the box of the cutting moves
    }
  }
  RemovalOptions removal_options;
  removal_options.engine = o.engine == "voxel" ? EngineKind::Voxel : EngineKind::Dexel;
  removal_options.grid_mm = o.grid_mm;
  removal_options.source_path = source->path;
  PlanOptions plan_options;
  if (stock && !tools.empty()) {
    const double grid =
        removal_options.grid_mm > 0 ? removal_options.grid_mm : default_grid_spacing(tools);
    plan_options.max_sample_step_mm = recommended_sample_step(tools, grid);
  }
  const Timeline timeline = plan(toolpath.commands, machine, plan_options);
  const auto t2 = Clock::now();
  std::optional<RemovalResult> removal;
  if (stock) {
    try {
      removal = simulate_removal(toolpath.commands, timeline, tools, *stock, removal_options);
    } catch (const std::exception& e) {
      std::cerr << "ncjoule: material removal failed: " << e.what() << '\n';
      return kInputError;
    }
    diagnostics.insert(diagnostics.end(), removal->diagnostics.begin(), removal->diagnostics.end());
  }
  EnergyOptions energy_options;
  energy_options.co2_kg_per_kwh = o.co2_kg_per_kwh;
  energy_options.price_per_kwh = o.price_per_kwh;
  const EnergyResult energy = estimate_energy(
      toolpath.commands, timeline, removal ? &*removal : nullptr, machine.power, energy_options);
  diagnostics.insert(diagnostics.end(), energy.diagnostics.begin(), energy.diagnostics.end());
  spdlog::info("interpret: {} blocks, {} commands in {:.3f} s", toolpath.result.blocks,
               toolpath.commands.size(), std::chrono::duration<double>(t1 - t0).count());
  spdlog::info("plan: {} commands in {:.3f} s", toolpath.commands.size(),
               std::chrono::duration<double>(t2 - t1).count());

  for (Diagnostic d : timeline.diagnostics) {
    d.file = source->path;
    diagnostics.push_back(std::move(d));
  }
  const std::vector<BlockSummary> blocks = summarise_blocks(
      *source, toolpath.result.dialect, timeline, removal ? &*removal : nullptr, energy);
  if (o.json) {
    std::cout << program_json(*source, machine, toolpath.result.dialect, timeline,
                              removal ? &*removal : nullptr, energy, blocks, diagnostics)
                     .dump(1)
              << '\n';
  } else {
    print_summary(*source, machine, timeline, energy, blocks.size());
  }
  std::cout.flush();
  std::fflush(stdout);
  print_diagnostics(diagnostics);
  for (const Diagnostic& d : diagnostics)
    if (d.severity == Severity::Error) return kInputError;
  return kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<EstimateOptions>();
  CLI::App* cmd =
      app.add_subcommand("estimate", "Predict the run time of a program on a machine, per block");
  cmd->add_option("file", options->file, "NC program (- for standard input)")->required();
  cmd->add_option("-m,--machine", options->machine, "Machine profile (.toml)")->required();
  cmd->add_option("--dialect", options->dialect,
                  "Controller dialect (linuxcnc, fanuc, haas, grbl, mach3, siemens); "
                  "default: the machine profile's, else detected from the file");
  cmd->add_option("--stock", options->stock,
                  "Stock: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm) or an STL file; "
                  "default: the bounding box of the cutting moves");
  cmd->add_option("--engine", options->engine, "Removal engine: dexel (default) or voxel")
      ->check(CLI::IsMember({"dexel", "voxel"}));
  cmd->add_option("--grid", options->grid_mm,
                  "Removal grid spacing in mm (default: from the tools)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--no-removal", options->no_removal,
                "Do not simulate material removal (no tools needed; cutting power is zero)");
  cmd->add_option("--co2", options->co2_kg_per_kwh, "kg of CO2 per kWh (overrides the profile)");
  cmd->add_option("--price", options->price_per_kwh, "Price per kWh (overrides the profile)");
  cmd->add_flag("--json", options->json, "Print the per-block results as JSON (docs/json.md)");
  cmd->callback([options, &exit_code] { exit_code = run_estimate(*options); });
});

} // namespace
} // namespace ncjoule::cli
