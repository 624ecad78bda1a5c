// `ncjoule annotate IN --machine PROFILE [-o OUT | --in-place]`: writes the program back with
// its predicted time, MRR, power and energy as a comment on every block, per-operation subtotals
// at tool changes and a summary header (docs/annotation.md).
//
// Old annotations are taken out before the program is estimated, so annotating an annotated
// file gives the same result as annotating the original. Nothing is written when the program
// cannot be estimated; the output goes through a temporary file, so a failed write leaves the
// target as it was.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/annotate.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"
#include "output_file.hpp"

namespace ncjoule::cli {
namespace {

struct AnnotateCliOptions {
  std::string file;
  std::string machine;
  std::string output; // empty: standard output, unless in_place
  bool in_place = false;
  std::string dialect;
  std::string stock;
  std::string engine = "dexel";
  double grid_mm = 0;
  bool no_removal = false;
  bool no_header = false;
  std::optional<double> co2_kg_per_kwh, price_per_kwh;
};

// The estimate's options from the command line; nullopt (after saying why) when one is bad.
std::optional<EstimateOptions> estimate_options(const AnnotateCliOptions& o) {
  EstimateOptions options;
  if (!o.dialect.empty()) {
    options.dialect = dialect_from_option(o.dialect);
    if (!options.dialect) return std::nullopt;
  }
  options.simulate_removal = !o.no_removal;
  if (!o.stock.empty()) {
    std::string error;
    options.stock = parse_stock_spec(o.stock, &error);
    if (!options.stock) {
      std::cerr << "ncjoule: bad --stock '" << o.stock << "': " << error << '\n';
      return std::nullopt;
    }
  }
  options.removal.engine = o.engine == "voxel" ? EngineKind::Voxel : EngineKind::Dexel;
  options.removal.grid_mm = o.grid_mm;
  options.energy.co2_kg_per_kwh = o.co2_kg_per_kwh;
  options.energy.price_per_kwh = o.price_per_kwh;
  return options;
}

int run_annotate(const AnnotateCliOptions& o) {
  if (o.in_place && o.file == "-") {
    std::cerr << "ncjoule: --in-place needs a file, not standard input\n";
    return kUsage;
  }
  const std::optional<EstimateOptions> options = estimate_options(o);
  if (!options) return kUsage;
  MachineProfile machine;
  try {
    machine = load_profile(o.machine);
  } catch (const ProfileError& e) {
    std::cerr << "ncjoule: bad machine profile: " << e.what() << '\n';
    return kInputError;
  }
  // read_source() does not expect a directory (reading one throws): say so here.
  if (o.file != "-" && std::filesystem::is_directory(o.file)) {
    std::cerr << "ncjoule: cannot read " << o.file << ": it is a directory\n";
    return kInputError;
  }
  const auto input = read_source(o.file);
  if (!input) return kInputError;

  // The program as it was before any earlier annotation: what is estimated and written back.
  const SourceFile program = make_source(input->path, strip(input->text));
  const Estimate e = estimate_program(program, machine, *options);
  print_diagnostics(e.diagnostics);
  bool errors = e.failed;
  for (const Diagnostic& d : e.diagnostics)
    if (d.severity == Severity::Error) errors = true;
  if (errors) {
    std::cerr << "ncjoule: " << program.path
              << " was not annotated (see above); nothing was written"
              << (e.failed ? ". Define the tools in the program's header comments, or use "
                             "--no-removal"
                           : "")
              << '\n';
    return kInputError;
  }

  AnnotateOptions annotate_options;
  annotate_options.header = !o.no_header;
  const std::string text = annotate(program, e, machine, annotate_options);

  const std::string target = o.in_place ? o.file : (o.output.empty() ? "-" : o.output);
  if (const std::string error = write_output_file(target, text); !error.empty()) {
    std::cerr << "ncjoule: " << error << "; "
              << (o.in_place ? o.file + " is untouched" : "nothing was written") << '\n';
    return kOutputError;
  }
  return kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<AnnotateCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "annotate", "Write the program back with its predicted time, MRR, power and energy as a "
                  "comment on every block (ncjoule strip removes them)");
  cmd->add_option("file", options->file, "NC program (- for standard input)")->required();
  cmd->add_option("-m,--machine", options->machine, "Machine profile (.toml)")->required();
  CLI::Option* output = cmd->add_option("-o,--output", options->output,
                                        "Annotated program (- for standard output, the default)");
  cmd->add_flag("-i,--in-place", options->in_place, "Replace the input file")->excludes(output);
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
  cmd->add_flag("--no-header", options->no_header, "Leave out the summary header");
  cmd->add_option("--co2", options->co2_kg_per_kwh, "kg of CO2 per kWh (overrides the profile)");
  cmd->add_option("--price", options->price_per_kwh, "Price per kWh (overrides the profile)");
  cmd->footer("Exit codes: 0 written; 1 bad command line; 2 bad input (nothing written); "
              "3 the output could not be written (the target is untouched).");
  cmd->callback([options, &exit_code] { exit_code = run_annotate(*options); });
});

} // namespace
} // namespace ncjoule::cli
