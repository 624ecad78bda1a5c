// `ncjoule profiles`: the machine profiles shipped with ncjoule, one line each (the name
// --machine takes, the machine, its spindle and what its power constants rest on), so that a
// user can start from the class of machine they have.
#include <cstdio>
#include <string>

#include "command_registry.hpp"
#include "ncjoule/diagnostic.hpp"
#include "ncjoule/profile.hpp"
#include "user_config.hpp"

namespace ncjoule::cli {
namespace {

const Registration registration([](CLI::App& app, int& exit_code) {
  CLI::App* cmd = app.add_subcommand(
      "profiles", "List the machine profiles shipped with ncjoule: the name --machine takes, the "
                  "machine, its spindle, and where its numbers come from");
  cmd->callback([&exit_code] {
    const auto shipped = shipped_profiles();
    if (shipped.empty()) {
      std::fprintf(stderr, "ncjoule: no shipped profiles found (looked in:");
      for (const std::string& dir : machine_profile_dirs())
        std::fprintf(stderr, " %s", dir.c_str());
      std::fprintf(stderr, "); ncjoule doctor says more\n");
      exit_code = kInputError;
      return;
    }
    for (const auto& [stem, path] : shipped) {
      try {
        const MachineProfile m = load_profile(path);
        // File names and a profile's own texts, escaped (printable) as every output is.
        std::printf("%-24s %s%s%s\n", printable(stem).c_str(), printable(m.name).c_str(),
                    m.summary.empty() ? "" : ": ", printable(m.summary).c_str());
      } catch (const ProfileError& e) {
        std::printf("%-28s cannot be read: %s\n", printable(stem).c_str(),
                    printable(e.what()).c_str());
        exit_code = kInputError;
      }
    }
  });
});

} // namespace
} // namespace ncjoule::cli
