// `ncjoule strip IN [-o OUT | --in-place]`: takes ncjoule's annotations out of a program and
// gives back the bytes it had before `ncjoule annotate`. Comments a user wrote are never
// touched, even when they look like ncjoule's (docs/annotation.md).
#include <iostream>
#include <memory>
#include <string>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "ncjoule/annotate.hpp"
#include "output_file.hpp"

namespace ncjoule::cli {
namespace {

struct StripCliOptions {
  std::string file;
  std::string output; // empty: standard output, unless in_place
  bool in_place = false;
};

int run_strip(const StripCliOptions& o) {
  if (o.in_place && o.file == "-") {
    std::cerr << "ncjoule: --in-place needs a file, not standard input\n";
    return kUsage;
  }
  const auto input = read_source(o.file);
  if (!input) return kInputError;
  const std::string text = strip(input->text);
  // A file without annotations is left alone, so that its time stamp does not change.
  if (o.in_place && text == input->text) return kOk;
  return write_program(o.file, o.output, o.in_place, text);
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<StripCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "strip", "Remove ncjoule's annotations and give back the program's original bytes");
  cmd->add_option("file", options->file, "Annotated NC program (- for standard input)")->required();
  CLI::Option* output = cmd->add_option("-o,--output", options->output,
                                        "Stripped program (- for standard output, the default)");
  cmd->add_flag("-i,--in-place", options->in_place, "Replace the input file")->excludes(output);
  cmd->footer("Exit codes: 0 written; 1 bad command line; 2 unreadable input; "
              "3 the output could not be written (the target is untouched).");
  cmd->callback([options, &exit_code] { exit_code = run_strip(*options); });
});

} // namespace
} // namespace ncjoule::cli
