// `ncjoule strip IN [-o OUT | --in-place]`: takes ncjoule's annotations out of a program and
// gives back the bytes it had before `ncjoule annotate`. Comments a user wrote are never
// touched, even when they look like ncjoule's (docs/annotation.md).
#include <iostream>
#include <memory>
#include <string>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "in_place.hpp"
#include "ncjoule/annotate.hpp"
#include "output_file.hpp"

namespace ncjoule::cli {
namespace {

struct StripCliOptions {
  std::string file;
  std::string output; // empty: standard output, unless in_place
  bool in_place = false;
  bool follow_symlinks = false;
  double input_limit_mib = double(kDefaultMaxProgramBytes >> 20);
};

int run_strip(const StripCliOptions& o) {
  if (o.in_place && o.file == "-") {
    std::cerr << "ncjoule: --in-place needs a file, not standard input\n";
    return kUsage;
  }
  FileStamp stamp;
  if (o.in_place) {
    if (const std::string why = in_place_refusal(o.file, o.follow_symlinks, stamp); !why.empty()) {
      std::cerr << "ncjoule: " << why << "; " << printable(o.file) << " is untouched\n";
      return kOutputError;
    }
  }
  const auto input = read_source(o.file, std::size_t(o.input_limit_mib * 1024 * 1024));
  if (!input) return kInputError;
  const StripResult stripped = strip_checked(input->text);
  const std::string& text = stripped.text;
  if (stripped.by_form)
    std::cerr << "ncjoule: " << printable(input->path)
              << ": its annotations no longer match the seal in its header (edited since it was "
                 "annotated, or the header deleted): every comment in the annotations' form was "
                 "taken out, a note of that form added since too\n";
  // A file without annotations is left alone, so that its time stamp does not change.
  if (o.in_place && text == input->text) return kOk;
  // Replacing in place: checked again once the new text is on disk, right before the rename.
  // Stripping takes no time to speak of: only a writer that came or a change since the read are
  // looked for, not a quiet period.
  const InPlaceCheck check{stamp, true};
  return write_program(o.file, o.output, o.in_place ? &check : nullptr, text);
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<StripCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "strip", "Remove ncjoule's annotations and give back the program's original bytes");
  cmd->add_option("file", options->file, "Annotated NC program (- for standard input)")->required();
  CLI::Option* output = cmd->add_option("-o,--output", options->output,
                                        "Stripped program (- for standard output, the default)");
  CLI::Option* in_place =
      cmd->add_flag("-i,--in-place", options->in_place,
                    "Replace the input file (refused while another program is still writing it, "
                    "or when it is a symbolic link)")
          ->excludes(output);
  cmd->add_flag("--follow-symlinks", options->follow_symlinks,
                "With --in-place on a symbolic link: replace the file it points to")
      ->needs(in_place);
  cmd->add_option("--input-limit", options->input_limit_mib,
                  "Largest program read, in MiB (default 512)")
      ->check(CLI::Range(0.001, 1e6));
  cmd->footer("Exit codes: 0 written; 1 bad command line; 2 unreadable input; "
              "3 nothing was written: the output could not be written, or --in-place found the "
              "file still being written or changed (the file is untouched).");
  cmd->callback([options, &exit_code] { exit_code = run_strip(*options); });
});

} // namespace
} // namespace ncjoule::cli
