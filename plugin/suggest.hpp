// "Did you mean ...?" for a misspelt command or option: the closest name CLI11 knows.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace ncjoule::cli {

// A sentence naming what the command line most likely meant, for a parse error `error` of
// `app` on `argv`: the subcommand nearest an unknown first word ("estimat": "estimate"), or the
// option of the chosen subcommand nearest an unknown "--word" ("--stok": "--stock"). Empty when
// nothing is near enough (more than a third of the word's letters differ).
std::string suggestion(const CLI::App& app, const CLI::ParseError& error, int argc,
                       const char* const* argv);

// Edits (insert, delete, replace, swap two neighbours) that turn `a` into `b`.
std::size_t edit_distance(const std::string& a, const std::string& b);

} // namespace ncjoule::cli
