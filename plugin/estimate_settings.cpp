#include "estimate_settings.hpp"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/projects.hpp"
#include "ncjoule/text.hpp"
#include "ncjoule/text_file.hpp"
#include "setting_sources.hpp"
#include "user_config.hpp"

namespace ncjoule::cli {

namespace {

// A number within [low, high]; NaN and infinities are refused (CLI11's own ranges let NaN by).
CLI::Validator finite_between(double low, double high) {
  return CLI::Validator(
      [low, high](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || v < low || v > high)
          return "must be a number from " + CLI::detail::to_string(low) + " to " +
                 CLI::detail::to_string(high);
        return {};
      },
      "", "finite range");
}

} // namespace

void add_estimate_settings(CLI::App& cmd, EstimateSettings& s) {
  cmd.add_option("-m,--machine", s.machine,
                 "Machine profile: a .toml file, or a shipped one by name (haas-vf2, "
                 "router-2.2kw-vfd, ...: `ncjoule profiles` lists them); default: the user "
                 "config's (machine = ...), else the generic 3-axis profile");
  cmd.add_option("--dialect", s.dialect,
                 "Controller dialect (auto, linuxcnc, fanuc, haas, grbl, mach3, siemens, "
                 "heidenhain, reprap); default: the machine profile's (auto: detected from the "
                 "file)");
  cmd.add_option("--stock", s.stock,
                 "Stock: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX or an STL file, in the program's "
                 "units unless a value says its own (box:0,0,-1in,4in,3in,0); default: the job "
                 "file's, else PROGRAM.stock, else a CAMotics or FreeCAD project beside the "
                 "program, else the user config's, else the program's header (docs/stock.md), "
                 "else the bounding box of the cutting moves");
  cmd.add_option("--stock-from", s.stock_from,
                 "The CAM hook that passes --stock, named as where the stock came from "
                 "(fusion360, freecad, ...: lowercase letters, digits and '-'); the hooks ncjoule "
                 "ships pass it")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            const bool ok = !text.empty() && text.size() <= 24 &&
                            text.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-") ==
                                std::string::npos;
            return ok ? "" : "must be 1 to 24 lowercase letters, digits or '-'";
          },
          "NAME", "hook name"));
  cmd.add_option("--job", s.job,
                 "Job file (TOML): stock = \"box:...\" or stock_stl = \"part.stl\", and "
                 "[[tool]] entries; --stock and --tool override it; default: PROGRAM.ncjoule.toml "
                 "next to the program");
  cmd.add_option("--tool", s.tools,
                 "Tool N:TYPE:DIAMETER[:EXTRA], e.g. 1:flat:6, 2:ball:6, 3:bullnose:10:1.5, "
                 "4:drill:6.8:118, 5:chamfer:12:90 (repeatable; overrides header comments)")
      ->allow_extra_args(false); // one tool per --tool, so the program's file name is not taken
  cmd.add_option(
      "--material", s.material,
      "Workpiece material (aluminium-alloy, cast-aluminium, brass, cast-iron, mild-steel, "
      "medium-carbon-steel, alloy-steel, stainless-steel, titanium-alloy, plastic, wood, "
      "softwood, mdf, ...; docs/models.md): the "
      "cutting energy of profiles that take it from the material; default: the job "
      "file's, else the profile's");
  cmd.add_option("-t,--tool-table", s.tool_table,
                 "LinuxCNC tool table (.tbl): lengths for G43, and a tool for every entry with "
                 "a diameter (its comment names the shape, else a flat end mill)");
  cmd.add_option("--tool-units", s.tool_units,
                 "Units of the tool table's lengths and diameters (the machine's units): mm "
                 "(default) or inch")
      ->check(CLI::IsMember({"mm", "inch"}));
  cmd.add_option("--macro-dir", s.macro_dirs,
                 "Folder of the programs the control holds (O9xxx macros, probing cycles, "
                 "LinuxCNC subroutine files: O9810.nc, probe.ngc): a call to a program not in "
                 "the file runs the one found there (repeatable; searched before the profile's "
                 "[setup] macro_dirs)")
      ->check(CLI::ExistingDirectory)
      ->allow_extra_args(false);
  cmd.add_option("--engine", s.engine, "Removal engine: dexel (default) or voxel")
      ->check(CLI::IsMember({"dexel", "voxel"}));
  cmd.add_option("--grid", s.grid_mm,
                 "Removal grid spacing in mm, 0.001 to 100 (default: from the tools)")
      ->check(finite_between(0.001, 100));
  cmd.add_option("--memory-limit", s.memory_limit_mib,
                 "Memory the run may take, in MiB (default: a quarter of this machine's memory, "
                 "or half of the process's ulimit): the program's lines and results first, the "
                 "stock model the rest; a program or a --grid that needs more is refused, the "
                 "automatic grid is coarsened")
      ->check(finite_between(1, 1e9));
  cmd.add_option("--input-limit", s.input_limit_mib, "Largest program read, in MiB (default 512)")
      ->check(finite_between(0.001, 1e6));
  // The work budgets: a run that would pass one stops with exit 5 (a program that asks for more
  // work than allowed, which a control may well run), not 2.
  cmd.add_option("--max-moves", s.max_moves,
                 "Most moves (canonical commands) the program may expand to through its loops, "
                 "canned cycles and splines (default 20000000; max_moves in the user config); "
                 "beyond it the run stops, exit 5")
      ->check(finite_between(1, 1e15));
  cmd.add_option("--max-path-samples", s.max_path_samples,
                 "Most path samples the planner may make for the program (default 100000000; "
                 "max_path_samples in the user config); beyond it the run stops, exit 5")
      ->check(finite_between(1, 1e15));
  cmd.add_option("--max-removal-work", s.max_removal_work,
                 "Most removal work, in grid columns under the tool summed over its steps "
                 "(default 2e10; max_removal_work in the user config); beyond it the run stops, "
                 "exit 5")
      ->check(finite_between(1, 1e18));
  cmd.add_flag("--no-removal", s.no_removal,
               "Do not simulate material removal (no tools needed; cutting power is zero)");
  cmd.add_option("--co2", s.co2_kg_per_kwh,
                 "kg of CO2 per kWh (overrides the user config's co2_kg_per_kwh and the profile)")
      ->check(finite_between(0, 100));
  cmd.add_option("--price", s.price_per_kwh,
                 "Price per kWh (overrides the user config's price_per_kwh and the profile)")
      ->check(finite_between(0, 1e6));
  cmd.add_option(
         "--machine-rate", s.machine_rate_per_hour,
         "Machine-hour rate besides electricity (depreciation, space, operator), per "
         "hour in the profile's currency; added to the cost (overrides the user config's and "
         "the profile's machine_rate_per_hour)")
      ->check(finite_between(0, 1e7));
}

bool load_machine(const EstimateSettings& s, MachineProfile& machine, const std::string& program,
                  std::string* from) {
  const auto& config = user_config();
  if (!config) return false;
  // The job's machine comes between the command line's and the user config's, as its stock does.
  std::string job_machine;
  if (s.machine.empty()) {
    const std::string job = !s.job.empty() ? s.job : program_job_file(program);
    if (!job.empty()) {
      std::vector<Diagnostic> ignored; // estimate_options reads the job again and reports
      if (const auto read = read_job_file(job, ignored)) job_machine = read->machine;
    }
  }
  std::string path = resolve_machine(!s.machine.empty()     ? s.machine
                                     : !job_machine.empty() ? job_machine
                                                            : config->machine);
  if (path.empty()) {
    path = default_machine_profile();
    if (path.empty()) {
      std::cerr << "ncjoule: no machine profile: give --machine PROFILE, or machine = \"...\" in "
                << user_config_path() << "\n";
      return false;
    }
    std::cerr << "ncjoule: note: no machine profile given, the generic 3-axis one is used (" << path
              << "); give yours with --machine or machine = \"...\" in " << user_config_path()
              << "\n";
  }
  if (from)
    *from = !s.machine.empty() ? "command line (--machine)"
            : !job_machine.empty()
                ? "job file " + (!s.job.empty() ? s.job : program_job_file(program))
            : !config->machine.empty() ? "user config " + config->path
                                       : "default (none named)";
  try {
    machine = load_profile(path, machine_profile_dirs());
    machine.by_default = s.machine.empty() && job_machine.empty() && config->machine.empty();
    return true;
  } catch (const ProfileError& e) {
    print_diagnostics({e.diagnostic()});
    std::cerr << "ncjoule: the machine profile " << path << " cannot be used (see above)\n";
    if (path.find('/') == std::string::npos && path.find(".toml") == std::string::npos) {
      std::cerr << "ncjoule: shipped profiles (ncjoule profiles):";
      for (const auto& [stem, _] : shipped_profiles())
        std::cerr << ' ' << stem;
      std::cerr << '\n';
    }
    return false;
  }
}

std::size_t memory_budget_bytes(const EstimateSettings& s) {
  return s.memory_limit_mib > 0 ? std::size_t(s.memory_limit_mib * 1024 * 1024)
                                : default_memory_budget_bytes();
}

std::size_t input_limit_bytes(const EstimateSettings& s) {
  return std::size_t(s.input_limit_mib * 1024 * 1024);
}

// The settings with what the command line left open filled in from the program's own files
// and the user config (user_config.hpp says which wins).
std::optional<EstimateSettings> completed(EstimateSettings s, const std::string& program) {
  const auto& config = user_config();
  if (!config) return std::nullopt;
  if (s.job.empty()) s.job = program_job_file(program);
  if (s.stock.empty()) {
    if (const std::string file = program_stock_file(program); !file.empty()) {
      std::vector<Diagnostic> problems;
      const std::optional<std::string> text = read_text_file(file, "a stock file", problems);
      if (!text) {
        print_diagnostics(problems);
        return std::nullopt;
      }
      // The first line, trimmed; its column kept for the diagnostics of what it says.
      const std::string_view first_line = std::string_view(*text).substr(0, text->find('\n'));
      const std::string_view stock = trim(first_line);
      s.program_stock_origin = {file, 1, int(stock.data() - first_line.data()) + 1};
      const std::string line(stock);
      if (line.empty()) {
        std::cerr << "ncjoule: " << file << " is empty: give one stock (box:... or an STL file)\n";
        return std::nullopt;
      }
      s.program_stock = line.rfind("box:", 0) == 0
                            ? line
                            : (std::filesystem::path(file).parent_path() / line).string();
    }
  }
  // The work budgets, where the command line gave none (the costs are resolve_settings').
  if (!s.max_moves) s.max_moves = config->max_moves;
  if (!s.max_path_samples) s.max_path_samples = config->max_path_samples;
  if (!s.max_removal_work) s.max_removal_work = config->max_removal_work;
  s.config_stock = config->stock;
  s.config_stock_origin = config->stock_origin;
  return s;
}

std::optional<ResolvedSettings> settings_for(const EstimateSettings& given,
                                             const std::string& program,
                                             const MachineProfile& machine, int& exit_code) {
  const std::optional<EstimateSettings> settings = completed(given, program);
  if (!settings) return exit_code = kInputError, std::nullopt;
  std::string job_material;
  if (!settings->job.empty()) {
    std::vector<Diagnostic> ignored; // estimate_options reads the job again and reports
    if (const auto job = read_job_file(settings->job, ignored)) job_material = job->material;
  }
  return resolve_settings(*settings, *user_config(), machine, settings->job, job_material);
}

std::optional<EstimateOptions> estimate_options(const EstimateSettings& given,
                                                const std::string& program,
                                                const MachineProfile& machine, int& exit_code) {
  const std::optional<EstimateSettings> settings = completed(given, program);
  if (!settings) return exit_code = kInputError, std::nullopt;
  const EstimateSettings& s = *settings;
  EstimateOptions options;
  std::optional<JobFile> job;
  if (!s.job.empty()) {
    std::vector<Diagnostic> job_diagnostics;
    job = read_job_file(s.job, job_diagnostics);
    print_diagnostics(job_diagnostics);
    if (!job) return exit_code = kInputError, std::nullopt;
  }
  const ResolvedSettings r =
      resolve_settings(s, *user_config(), machine, s.job, job ? job->material : std::string());
  if (r.dialect == "auto") {
    options.detect_dialect = true;
  } else if (!r.dialect.empty()) {
    options.dialect = dialect_from_option(r.dialect);
    if (!options.dialect) return exit_code = kUsage, std::nullopt;
  }
  if (!r.tool_table.empty()) {
    const auto table = read_source(r.tool_table, kMaxSettingsFileBytes);
    if (!table) return exit_code = kInputError, std::nullopt;
    std::vector<Diagnostic> diagnostics;
    options.tool_table = parse_tool_table(*table, r.tool_units == "inch", diagnostics);
    options.tool_table_path = r.tool_table;
    print_diagnostics(diagnostics);
    for (const Diagnostic& d : diagnostics)
      if (d.severity == Severity::Error) return exit_code = kInputError, std::nullopt;
  }
  options.simulate_removal = !s.no_removal;
  options.macro_dirs = s.macro_dirs;
  if (!s.material.empty() && !find_material(s.material)) {
    std::cerr << "ncjoule: unknown material '" << s.material << "'; known materials:";
    for (const Material& m : materials())
      std::cerr << ' ' << m.name;
    std::cerr << '\n';
    return exit_code = kUsage, std::nullopt;
  }
  if (job) {
    if (job->stock) options.stock = job->stock;
    options.setup_stocks = job->setup_stocks;
    options.work_offsets = job->work_offsets;
    options.cutter_compensation = job->cutter_compensation;
    options.tools = job->tools;
  }
  options.material = r.material; // empty: the profile's own

  // Stock: --stock, the job file's, PROGRAM.stock, a CAM project beside the program, the user
  // config's; the program's own comments come after them all (estimate.cpp). docs/stock.md.
  if (!s.stock_from.empty() && s.stock.empty()) {
    std::cerr << "ncjoule: --stock-from " << s.stock_from
              << " names where --stock came from; give --stock too\n";
    return exit_code = kUsage, std::nullopt;
  }
  // Parses one stock text into options.stock; false (with the problem printed) when it is bad.
  auto take = [&](const std::string& text, const TextOrigin& origin, std::string from) {
    std::vector<Diagnostic> problems;
    options.stock = parse_stock_spec(text, &problems, origin);
    if (!options.stock) return print_diagnostics(problems), false;
    options.stock->from = std::move(from);
    return true;
  };
  if (!s.stock.empty()) {
    if (!take(s.stock, TextOrigin{"--stock '" + s.stock + "'"},
              s.stock_from.empty() ? "option" : "hook-" + s.stock_from))
      return exit_code = kUsage, std::nullopt;
    if (!s.stock_from.empty())
      options.stock->origin = "the " + s.stock_from + " hook's --stock '" + s.stock + "'";
  }
  if (!options.stock && !s.program_stock.empty() &&
      !take(s.program_stock, s.program_stock_origin, "stock-file"))
    return exit_code = kInputError, std::nullopt;
  // A project beside the program: its stock in its place, its tools under the job file's and
  // the command line's (and over the program's comments).
  if (program != "-") {
    std::vector<Diagnostic> found;
    if (auto project = project_beside(program, found)) {
      if (!options.stock && project->stock) options.stock = project->stock;
      for (const auto& [number, tool] : project->tools)
        options.tools.emplace(number, tool);
    }
    print_diagnostics(found);
  }
  if (!options.stock && !s.config_stock.empty() &&
      !take(s.config_stock, s.config_stock_origin, "user-config"))
    return exit_code = kInputError, std::nullopt;
  for (const std::string& text : s.tools) {
    std::vector<Diagnostic> problems;
    const auto tool = parse_tool_spec(text, &problems, TextOrigin{"--tool '" + text + "'"});
    if (!tool) {
      print_diagnostics(problems);
      return exit_code = kUsage, std::nullopt;
    }
    options.tools[tool->number] = *tool;
  }
  options.removal.engine = s.engine == "voxel" ? EngineKind::Voxel : EngineKind::Dexel;
  options.removal.grid_mm = s.grid_mm;
  options.removal.memory_budget_bytes = memory_budget_bytes(s);
  if (s.max_moves) options.limits.max_commands = std::size_t(*s.max_moves);
  if (s.max_path_samples) options.max_path_samples = std::size_t(*s.max_path_samples);
  if (s.max_removal_work) options.max_removal_work = *s.max_removal_work;
  options.energy.co2_kg_per_kwh = r.co2_kg_per_kwh;
  options.energy.price_per_kwh = r.price_per_kwh;
  options.energy.machine_rate_per_hour = r.machine_rate_per_hour;
  if (!r.currency.empty()) options.energy.currency = r.currency;
  for (const SourcedSetting& shown : r.shown) {
    if (shown.name == "price_per_kwh") options.energy.price_from = shown.from;
    if (shown.name == "machine_rate_per_hour") options.energy.rate_from = shown.from;
  }
  return options;
}

} // namespace ncjoule::cli
