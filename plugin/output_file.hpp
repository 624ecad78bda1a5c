// Writing a command's output so that a failure never leaves a half-written file and a name never
// leads the text somewhere it was not meant to go. Every command that writes a file uses it
// (annotate, strip, report, calibrate, doctor's check, and the C API):
//
//  - standard output and error by any of their names (-, /dev/stdout, /dev/stderr, /dev/fd/N,
//    /proc/self/fd/N, a link to one of them) are written where they point, at their position:
//    `-o /dev/stdout >> log` appends to the log, never replaces it;
//  - a device, a pipe or a socket is written directly (it cannot be replaced);
//  - a regular file is replaced through a temporary file in its own folder, created with
//    O_EXCL and O_NOFOLLOW under a name nobody can guess, written and flushed to disk, then
//    renamed over the target. Where the system has them (Linux, O_TMPFILE) the temporary has no
//    name until it is complete, so a killed run (kill -9, a power cut) leaves nothing behind;
//    otherwise its name, ".NAME.ncjoule-PID-RANDOM", lets the next write to NAME (and `ncjoule
//    doctor` in the folder) recognise it once process PID has ended, and remove it;
//  - a symbolic link is followed only when it is the user's own or the system's (owned by
//    root): a link another user planted in a shared folder is refused;
//  - replacing the file that was read (in place) is checked once more after the new text is on
//    disk, right before the rename (in_place.hpp).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "command_registry.hpp"
#include "in_place.hpp"
#include "ncjoule/diagnostic.hpp"

namespace ncjoule::cli {

struct WriteOptions {
  // Replacing the file that was read: checked after the temporary is complete, right before it
  // is renamed over the file (in_place_changed, and on POSIX a QuietProof).
  const InPlaceCheck* in_place = nullptr;
  // What was done besides writing, for the user (a stale temporary removed); may be null.
  std::vector<std::string>* notes = nullptr;
};

// Writes `text` to `target` ("-": standard output). Returns an empty string on success, else
// what went wrong; then the target is as it was and no temporary file is left behind.
std::string write_output_file(const std::string& target, std::string_view text,
                              const WriteOptions& options = {});

// Creates a new file in `folder` under a name nobody can guess, `stem` followed by random
// characters (never an existing file or a link: O_EXCL and O_NOFOLLOW, CREATE_NEW on Windows),
// holding `text`, readable by the user only; its path in `path`. Empty, or why not.
std::string create_new_file(const std::string& folder, const std::string& stem,
                            std::string_view text, std::string& path);

// Temporary files of ncjoule's left in `folder` by runs that ended without removing them
// (killed with SIGKILL, a power cut): those whose process has ended, of the user's own. With
// `remove`, they are removed. Each entry is a sentence naming one file.
std::vector<std::string> stale_temporaries(const std::string& folder, bool remove);

// Writes a rewritten program where the command line says: over `file` when `in_place` is given
// (then checked as InPlaceCheck says), else to `output` ("" or "-": standard output). Returns the
// exit code, after saying why on failure.
inline int write_program(const std::string& file, const std::string& output,
                         const InPlaceCheck* in_place, std::string_view text) {
  const std::string target = in_place ? file : (output.empty() ? "-" : output);
  std::vector<std::string> notes;
  const std::string error = write_output_file(target, text, {in_place, &notes});
  for (const std::string& note : notes)
    std::fprintf(stderr, "ncjoule: %s\n", printable(note).c_str());
  if (!error.empty()) {
    // The names in it are the user's: printed so that they cannot drive the terminal.
    std::fprintf(stderr, "ncjoule: %s; %s\n", printable(error).c_str(),
                 in_place ? (printable(file) + " is untouched").c_str() : "nothing was written");
    return kOutputError;
  }
  return 0;
}

} // namespace ncjoule::cli
