// `ncjoule doctor`: checks the installation (the program, its profiles, the user config, the
// reference interpreter and the post-processor hooks) and says what is missing and how to fix it.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "command_registry.hpp"
#include "ncjoule/profile.hpp"
#include "user_config.hpp"

namespace ncjoule::cli {
namespace {

namespace fs = std::filesystem;

// One finding: "ok", "note" (optional and absent) or "FAIL" (ncjoule cannot work as set up).
struct Findings {
  int failures = 0;
  void ok(const std::string& what) { std::printf("ok    %s\n", what.c_str()); }
  void note(const std::string& what, const std::string& fix) {
    std::printf("note  %s\n      %s\n", what.c_str(), fix.c_str());
  }
  void fail(const std::string& what, const std::string& fix) {
    ++failures;
    std::printf("FAIL  %s\n      %s\n", what.c_str(), fix.c_str());
  }
};

bool exists(const fs::path& p) {
  std::error_code ec;
  return fs::exists(p, ec);
}

// The first folder of $PATH that holds an executable `name`; empty when none does.
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::string dirs = path;
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
    std::error_code ec;
    if (end > start && fs::is_regular_file(candidate, ec) &&
        (fs::status(candidate, ec).permissions() & fs::perms::owner_exec) != fs::perms::none)
      return candidate.string();
    start = end + 1;
  }
  return {};
}

std::string home_path(const std::string& relative) {
  const char* home = std::getenv("HOME");
  return home ? std::string(home) + "/" + relative : std::string();
}

bool check_profile(Findings& f, const std::string& path, const std::string& role) {
  try {
    const MachineProfile m = load_profile(path);
    f.ok(role + ": " + path + " (" + m.name + ")");
    return true;
  } catch (const std::exception& e) {
    f.fail(role + ": " + path + " does not load: " + e.what(),
           "fix the profile (docs/profiles.md), or name another one");
    return false;
  }
}

int run_doctor() {
  Findings f;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  f.ok(std::string("ncjoule ") + NCJOULE_VERSION + (ec ? "" : " at " + exe.string()));

  // Profiles: where they are looked for, and the one used when none is named.
  std::size_t bundled = 0;
  for (const std::string& dir : machine_profile_dirs()) {
    if (!exists(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir, ec))
      if (entry.path().extension() == ".toml") ++bundled;
    f.ok("machine profiles in " + dir + " (" + std::to_string(bundled) + ")");
    break;
  }
  const std::string fallback = default_machine_profile();
  if (fallback.empty())
    f.fail("no bundled machine profile found (looked in share/ncjoule/machines next to the "
           "program, and $NCJOULE_DATA_DIR/machines)",
           "reinstall ncjoule, or set NCJOULE_DATA_DIR, or always give --machine");
  else
    check_profile(f, fallback, "default machine profile");

  // The user config.
  const std::string config_path = user_config_path();
  if (config_path.empty() || !exists(config_path)) {
    f.note("no user config (" + (config_path.empty() ? "HOME is not set" : config_path) + ")",
           "optional: machine = \"mill.toml\", material, tool_table, stock in it set them once "
           "for every command (README, \"Set once\")");
  } else if (const auto& config = user_config(); !config) {
    f.fail("the user config " + config_path + " cannot be used (see above)", "fix it");
  } else {
    f.ok("user config " + config_path);
    if (!config->machine.empty()) check_profile(f, config->machine, "its machine profile");
    if (!config->tool_table.empty() && !exists(config->tool_table))
      f.fail("its tool table " + config->tool_table + " does not exist",
             "fix tool_table in " + config_path);
  }

  // The reference interpreter (for `canon` comparisons and the LinuxCNC hook).
  if (const std::string rs274 = on_path("rs274"); rs274.empty())
    f.note("LinuxCNC's rs274 is not on the PATH",
           "optional: install linuxcnc-uspace to compare `ncjoule canon` with LinuxCNC");
  else
    f.ok("LinuxCNC's rs274 at " + rs274);

  // Hooks (postprocessor-templates/*/README.md say how to install each).
  if (const std::string filter = on_path("ncjoule-filter"); filter.empty())
    f.note("the LinuxCNC filter (ncjoule-filter) is not on the PATH",
           "optional: postprocessor-templates/linuxcnc/README.md");
  else
    f.ok("LinuxCNC filter at " + filter);
  std::string freecad;
  for (const char* folder : {".local/share/FreeCAD/Macro", ".FreeCAD/Macro",
                             ".local/share/FreeCAD/Mod/CAM/Path/Post/scripts"})
    if (const std::string p = home_path(std::string(folder) + "/ncjoule_post.py");
        !p.empty() && exists(p))
      freecad = p;
  if (freecad.empty())
    f.note("the FreeCAD post (ncjoule_post.py) is not in FreeCAD's macro folder",
           "optional: postprocessor-templates/freecad/README.md");
  else
    f.ok("FreeCAD post at " + freecad);
  if (const std::string hook = on_path("ncjoule-hook.sh"); hook.empty())
    f.note("the generic post hook (ncjoule-hook.sh) is not on the PATH",
           "optional: postprocessor-templates/generic/README.md (Fusion 360: "
           "postprocessor-templates/fusion360/README.md)");
  else
    f.ok("generic post hook at " + hook);

  std::printf("%s\n",
              f.failures ? "ncjoule cannot work as set up: see FAIL above" : "ncjoule is ready");
  return f.failures ? kInputError : kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  CLI::App* cmd = app.add_subcommand(
      "doctor", "Check the installation: profiles, user config, LinuxCNC's rs274 and the "
                "post-processor hooks, and say what is missing");
  cmd->callback([&exit_code] { exit_code = run_doctor(); });
});

} // namespace
} // namespace ncjoule::cli
