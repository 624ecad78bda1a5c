// `ncjoule annotate IN --machine PROFILE [-o OUT | --in-place]`: writes the program back with
// its predicted time, MRR, power and energy as a comment on every block, per-operation subtotals
// at tool changes and a summary header (docs/annotation.md).
//
// Old annotations are taken out before the program is estimated, so annotating an annotated
// file gives the same result as annotating the original. Nothing is written when the program
// cannot be estimated; the output goes through a temporary file, so a failed write leaves the
// target as it was.
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "estimate_settings.hpp"
#include "in_place.hpp"
#include "ncjoule/annotate.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"
#include "output_file.hpp"
#include "progress.hpp"

namespace ncjoule::cli {
namespace {

struct AnnotateCliOptions {
  std::string file;
  std::string output; // empty: standard output, unless in_place
  bool in_place = false;
  bool follow_symlinks = false; // --in-place on a link replaces the file it points to
  bool no_header = false;
  std::string fields; // --fields T,E,...; empty: all (or the compact set)
  bool compact = false;
  EstimateSettings settings;
};

int run_annotate(const AnnotateCliOptions& o) {
  if (o.in_place && o.file == "-") {
    std::cerr << "ncjoule: --in-place needs a file, not standard input\n";
    return kUsage;
  }
  int status = kOk;
  MachineProfile machine;
  if (!load_machine(o.settings, machine, o.file)) return kInputError;
  const std::optional<EstimateOptions> options =
      estimate_options(o.settings, o.file, machine, status);
  if (!options) return status;
  // A file replaced in place must be one no other program is still writing.
  FileStamp stamp;
  if (o.in_place) {
    if (const std::string why = in_place_refusal(o.file, o.follow_symlinks, stamp); !why.empty()) {
      std::cerr << "ncjoule: " << why << "; " << printable(o.file) << " is untouched\n";
      return kOutputError;
    }
  }
  const auto input =
      read_source(o.file, input_limit_bytes(o.settings), memory_budget_bytes(o.settings));
  if (!input) return kInputError;

  ProgressBar progress("estimating", 1);
  progress.begin(0, input->path);
  EstimateOptions with_progress = *options;
  with_progress.progress = progress.callback();
  AnnotateOptions annotate_options;
  annotate_options.header = !o.no_header;
  if (o.compact) annotate_options.fields = compact_block_fields();
  if (!o.fields.empty()) {
    std::vector<Diagnostic> problems;
    const auto fields =
        parse_block_fields(o.fields, problems, TextOrigin{"--fields '" + o.fields + "'"});
    if (!fields) {
      print_diagnostics(problems);
      return kUsage;
    }
    annotate_options.fields = *fields;
    annotate_options.fields.omit_zero = o.compact;
  }
  const AnnotatedProgram result =
      annotate_program(input->path, input->text, machine, with_progress, annotate_options);
  progress.finish();
  print_diagnostics(result.estimate.diagnostics, result.estimate.diagnostics_dropped);
  if (result.estimate.failed) {
    std::cerr << "ncjoule: " << printable(input->path)
              << " could not be estimated (see above); nothing was written\n";
    return failed_status(result.estimate);
  }
  // Errors are what the controller itself would refuse: the program is still annotated (the
  // header lists them), and the exit status says so.
  const int done = result.has_errors ? kInputError : kOk;
  const char* with_errors =
      result.has_errors ? ", with errors a controller would refuse (see above)" : "";
  if (o.in_place && result.text == input->text) {
    std::cerr << "ncjoule: " << printable(o.file) << " unchanged: already annotated this way"
              << with_errors << '\n';
    return done;
  }
  // Replacing in place: checked again once the new text is on disk, right before the rename
  // (output_file.hpp), so that a post appending meanwhile is never lost.
  const InPlaceCheck check{stamp, result.estimate.program_end};
  if (const int written =
          write_program(o.file, o.output, o.in_place ? &check : nullptr, result.text);
      written != kOk)
    return written;
  if (o.in_place)
    std::cerr << "ncjoule: annotated " << printable(o.file) << with_errors << '\n';
  else if (!o.output.empty() && o.output != "-")
    std::cerr << "ncjoule: wrote " << printable(o.output) << with_errors << '\n';
  else if (result.has_errors)
    std::cerr << "ncjoule: " << printable(input->path)
              << " has errors a controller would refuse (see above); annotated anyway\n";
  return done;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<AnnotateCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "annotate", "Write the program back with its predicted time, MRR, power and energy as a "
                  "comment on every block (ncjoule strip removes them)");
  cmd->add_option("file", options->file, "NC program (- for standard input)")->required();
  CLI::Option* output = cmd->add_option("-o,--output", options->output,
                                        "Annotated program (- for standard output, the default)");
  CLI::Option* in_place =
      cmd->add_flag("-i,--in-place", options->in_place,
                    "Replace the input file (refused while another program is still writing it, "
                    "or when it is a symbolic link)")
          ->excludes(output);
  cmd->add_flag("--follow-symlinks", options->follow_symlinks,
                "With --in-place on a symbolic link: replace the file it points to")
      ->needs(in_place);
  add_estimate_settings(*cmd, options->settings);
  cmd->add_flag("--no-header", options->no_header, "Leave out the summary header");
  cmd->add_option("--fields", options->fields,
                  "Fields of each block's comment, from T,E,P,MRR,CUM,OP (default: all; "
                  "docs/annotation.md)");
  cmd->add_flag("--compact", options->compact,
                "Smaller annotations: T, E, MRR and OP, zero values left out (about 60% of the "
                "bytes the default adds)");
  cmd->footer(
      "Exit codes: 0 written; 1 bad command line; 2 bad input: unreadable or not G-code (nothing "
      "is written), or a program with errors its controller would refuse (annotated all the "
      "same when it could be estimated, its header listing them; the last line says "
      "'annotated FILE, with errors'); 3 nothing was written: the output could not be written, "
      "or --in-place found the file still being written or changed (the file is untouched); 5 "
      "a work budget (--max-moves, --max-path-samples, --max-removal-work) stopped the run: "
      "nothing was written.");
  cmd->callback([options, &exit_code] { exit_code = run_annotate(*options); });
});

} // namespace
} // namespace ncjoule::cli
