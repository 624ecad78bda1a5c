#include "multi_estimate.hpp"

#include <iostream>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/profile.hpp"
#include "progress.hpp"

namespace ncjoule::cli {

void add_estimate_settings(CLI::App& cmd, EstimateSettings& s) {
  cmd.add_option("-m,--machine", s.machine, "Machine profile (.toml)")->required();
  cmd.add_option("--dialect", s.dialect,
                 "Controller dialect (linuxcnc, fanuc, haas, grbl, mach3, siemens); "
                 "default: the machine profile's, else detected from each file");
  cmd.add_option("--stock", s.stock,
                 "Stock for every program: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm) or an STL file; "
                 "default: the bounding box of each program's cutting moves");
  cmd.add_option("--engine", s.engine, "Removal engine: dexel (default) or voxel")
      ->check(CLI::IsMember({"dexel", "voxel"}));
  cmd.add_option("--grid", s.grid_mm, "Removal grid spacing in mm (default: from the tools)")
      ->check(CLI::PositiveNumber);
  cmd.add_flag("--no-removal", s.no_removal,
               "Do not simulate material removal (no tools needed; cutting power is zero)");
  cmd.add_option("--co2", s.co2_kg_per_kwh, "kg of CO2 per kWh (overrides the profile)");
  cmd.add_option("--price", s.price_per_kwh, "Price per kWh (overrides the profile)");
}

int estimate_files(const std::vector<std::string>& files, const EstimateSettings& s,
                   MachineProfile& machine, std::vector<EstimatedProgram>& programs) {
  try {
    machine = load_profile(s.machine);
  } catch (const ProfileError& e) {
    std::cerr << "ncjoule: bad machine profile: " << e.what() << '\n';
    return kInputError;
  }
  EstimateOptions options;
  if (!s.dialect.empty()) {
    options.dialect = dialect_from_option(s.dialect);
    if (!options.dialect) return kUsage;
  }
  options.simulate_removal = !s.no_removal;
  if (!s.stock.empty()) {
    std::string error;
    options.stock = parse_stock_spec(s.stock, &error);
    if (!options.stock) {
      std::cerr << "ncjoule: bad --stock '" << s.stock << "': " << error << '\n';
      return kUsage;
    }
  }
  options.removal.engine = s.engine == "voxel" ? EngineKind::Voxel : EngineKind::Dexel;
  options.removal.grid_mm = s.grid_mm;
  options.energy.co2_kg_per_kwh = s.co2_kg_per_kwh;
  options.energy.price_per_kwh = s.price_per_kwh;

  // Read everything first, so that a missing file is reported before minutes of estimating.
  std::vector<SourceFile> sources;
  for (const std::string& file : files) {
    auto source = read_source(file);
    if (!source) return kInputError;
    sources.push_back(std::move(*source));
  }
  int status = kOk;
  ProgressBar progress("estimating", sources.size());
  for (std::size_t i = 0; i < sources.size(); ++i) {
    progress.begin(i, sources[i].path);
    Estimate e = estimate_program(sources[i], machine, options);
    programs.push_back({std::move(sources[i]), std::move(e)});
  }
  progress.finish();
  for (const EstimatedProgram& p : programs) {
    print_diagnostics(p.estimate.diagnostics);
    bool error = p.estimate.failed;
    for (const Diagnostic& d : p.estimate.diagnostics)
      error = error || d.severity == Severity::Error;
    if (p.estimate.failed)
      std::cerr << "ncjoule: " << p.source.path
                << " cannot be estimated (see above); define the tools in the program's header "
                   "comments, or use --no-removal\n";
    if (error) status = kInputError;
  }
  return status;
}

} // namespace ncjoule::cli
