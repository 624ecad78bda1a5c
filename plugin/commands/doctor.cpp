// `ncjoule doctor`: checks the installation (the program and its library, the machine profiles,
// the user config, the features built in, writing files here, the reference interpreter and the
// post-processor hooks), says what it found and what is missing and how to fix it, and exits 0
// when ncjoule can work as set up.
//
// The checks are the list in checks() below, run in order; each prints its findings through
// Findings. A platform adds its own checks there; where the program runs from comes from
// platform.hpp, the library's file from library_path() below.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#ifndef _WIN32
#include <dlfcn.h>
#include <unistd.h>
#endif

#include "command_registry.hpp"
#include "ncjoule.h"
#include "ncjoule/profile.hpp"
#include "ncjoule/text_file.hpp"
#include "output_file.hpp"
#include "platform.hpp"
#include "user_config.hpp"

namespace ncjoule::cli {
namespace {

namespace fs = std::filesystem;

// One finding: "ok", "note" (optional and absent, or worth knowing) or "FAIL" (ncjoule cannot
// work as set up). The fix is printed on the next line. Findings quote paths, a config's values
// and profile names: each line is printed escaped (printable), the line breaks kept.
struct Findings {
  int failures = 0;
  static std::string shown(const std::string& text) {
    std::string out;
    for (std::size_t start = 0; start <= text.size();) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      out += printable(std::string_view(text).substr(start, end - start));
      if (end < text.size()) out += '\n';
      start = end + 1;
    }
    return out;
  }
  void ok(const std::string& what) { std::printf("ok    %s\n", shown(what).c_str()); }
  void note(const std::string& what, const std::string& fix = {}) {
    std::printf("note  %s\n", shown(what).c_str());
    if (!fix.empty()) std::printf("      %s\n", shown(fix).c_str());
  }
  void fail(const std::string& what, const std::string& fix) {
    ++failures;
    std::printf("FAIL  %s\n      %s\n", shown(what).c_str(), shown(fix).c_str());
  }
};

struct Check {
  const char* name; // what `doctor` looks at, for the reader of this file
  void (*run)(Findings&);
};

bool exists(const fs::path& p) {
  std::error_code ec;
  return fs::exists(p, ec);
}

// ---- platform: the running program's library (platform.hpp has the rest) --------------------

// The file of the C library (libncjoule) this program runs with; empty when it cannot be told.
std::string library_path() {
#ifdef _WIN32
  return {};
#else
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&ncjoule_version), &info) != 0 && info.dli_fname)
    return info.dli_fname;
  return {};
#endif
}

// The first folder of $PATH that holds an executable `name`; empty when none does.
// (Windows: `name` as given, or with the extension of a program, .exe .cmd .bat; a folder of
// PATH may be written in double quotes.)
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::string dirs = path;
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(platform::kPathListSeparator, start), dirs.size());
    std::string dir = dirs.substr(start, end - start);
#ifdef _WIN32
    std::erase(dir, '"');
    for (const char* extension : {"", ".exe", ".cmd", ".bat"}) {
      const fs::path candidate = platform::path_from_utf8(dir + "\\" + name + extension);
      std::error_code ec;
      if (!dir.empty() && fs::is_regular_file(candidate, ec))
        return platform::utf8_from_path(candidate);
    }
#else
    const fs::path candidate = fs::path(dir) / name;
    std::error_code ec;
    if (end > start && fs::is_regular_file(candidate, ec) &&
        (fs::status(candidate, ec).permissions() & fs::perms::owner_exec) != fs::perms::none)
      return candidate.string();
#endif
    start = end + 1;
  }
  return {};
}

std::string home_path(const std::string& relative) {
  const char* home = std::getenv("HOME");
  return home ? std::string(home) + "/" + relative : std::string();
}

// The installed data folder (share/ncjoule next to the program's bin folder); empty when the
// program's folder cannot be told.
fs::path installed_data_dir() {
  const fs::path exe = platform::program_file();
  return exe.empty() ? fs::path() : exe.parent_path().parent_path() / "share" / "ncjoule";
}

bool check_profile(Findings& f, const std::string& path, const std::string& role) {
  try {
    const MachineProfile m = load_profile(path);
    f.ok(role + ": " + path + " (" + m.name + ")");
    return true;
  } catch (const std::exception& e) {
    f.fail(role + ": " + path + " does not load: " + e.what(),
           "fix the profile (docs/machine-profiles.md), or name another one");
    return false;
  }
}

// ---- the checks ------------------------------------------------------------------------------

void check_program(Findings& f) {
  const fs::path exe = platform::program_file();
  f.ok(std::string("ncjoule ") + NCJOULE_VERSION +
       (exe.empty() ? " (its location cannot be told here)"
                    : " at " + platform::utf8_from_path(exe)));
#ifdef _WIN32
  // The manifest makes the process's code page UTF-8 on Windows 10 1903 and later; before,
  // file names are read in the system's code page.
  if (platform::utf8_code_page())
    f.ok("file names in any language (the program runs with the UTF-8 code page)");
  else
    f.note("this Windows does not run ncjoule with the UTF-8 code page (Windows 10 1903 and later "
           "do): file names with letters outside the system's language cannot be opened",
           "rename such files, or update Windows");
#endif
}

// The C library the program runs with: the one it was built with, not a stale copy found first.
void check_library(Findings& f) {
  const std::string where = library_path();
  const std::string version = ncjoule_version() ? ncjoule_version() : "";
  const std::string what =
      "C library (libncjoule) " + version + (where.empty() ? std::string() : " at " + where);
  if (version != NCJOULE_VERSION)
    f.fail(what + ", but this program is " + NCJOULE_VERSION,
           "another version of libncjoule is found first (LD_LIBRARY_PATH, /usr/local/lib): "
           "remove it or reinstall ncjoule");
  else
    f.ok(what);
}

// Features: the removal engines run in parallel with TBB; calibrate fits with Ceres.
void check_features(Findings& f) {
#ifdef NCJOULE_TBB_VERSION
  f.ok(std::string("material removal in parallel with TBB ") + NCJOULE_TBB_VERSION);
#else
  f.note("material removal without TBB (one thread)");
#endif
#ifdef NCJOULE_CERES_VERSION
  f.ok(std::string("calibrate with Ceres ") + NCJOULE_CERES_VERSION);
#else
  f.note("calibrate is not built in (no Ceres)");
#endif
}

// The machine profiles: every folder searched, the names `-m NAME` takes, and that each loads.
void check_profiles(Findings& f) {
  const std::vector<std::string> dirs = machine_profile_dirs();
  for (const std::string& dir : dirs) {
    std::error_code ec;
    std::size_t count = 0;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      if (it->path().extension() == ".toml") ++count;
    if (!exists(dir))
      f.note("machine profile folder " + dir + ": not there");
    else
      f.ok("machine profile folder " + dir + ": " + std::to_string(count) + " profile" +
           (count == 1 ? "" : "s"));
  }
  const auto shipped = shipped_profiles();
  if (shipped.empty()) {
    std::string looked;
    for (const std::string& dir : dirs)
      looked += (looked.empty() ? "" : ", ") + dir;
    f.fail("no machine profiles found (looked in " + looked + ")",
           "reinstall ncjoule (its profiles go to share/ncjoule/machines next to its bin "
           "folder), set NCJOULE_DATA_DIR to a folder holding machines/, or give --machine FILE");
    return;
  }
  std::string names;
  std::size_t broken = 0;
  for (const auto& [stem, path] : shipped) {
    names += (names.empty() ? "" : ", ") + stem;
    try {
      (void)load_profile(path);
    } catch (const std::exception& e) {
      ++broken;
      f.fail("machine profile " + path + " does not load: " + e.what(),
             "reinstall ncjoule, or fix or remove the file");
    }
  }
  if (broken < shipped.size()) f.ok("profiles by name (-m NAME, `ncjoule profiles`): " + names);

  const std::string fallback = default_machine_profile();
  if (fallback.empty())
    f.fail("no generic-3axis profile, the one used when no machine is named",
           "reinstall ncjoule, or always give --machine (or machine = ... in the user config)");
  else if (resolve_machine("generic-3axis") != fallback)
    f.note("-m generic-3axis takes " + resolve_machine("generic-3axis") +
           ", but the default without -m is " + fallback);
}

// The user config: where it is looked for, and whether it parses and what it names exists.
void check_user_config(Findings& f) {
  const std::string path = user_config_path();
  const bool named = std::getenv("NCJOULE_CONFIG") != nullptr;
  if (path.empty()) {
#ifdef _WIN32
    f.note("no user config (APPDATA is not set)");
#else
    f.note("no user config (HOME is not set)");
#endif
    return;
  }
  if (!exists(path)) {
    if (named)
      f.note("NCJOULE_CONFIG names " + path + ", which does not exist: no user config is used");
    else
      f.note("no user config (" + path + ")",
             "optional: machine = \"mill.toml\", material, tool_table, stock in it set them once "
             "for every command (README, \"Set once\")");
    return;
  }
  std::vector<Diagnostic> diagnostics;
  const auto text = read_text_file(path, "a user config (TOML)", diagnostics);
  const auto config = text ? parse_user_config(*text, path, diagnostics) : std::nullopt;
  std::string errors, warnings;
  for (const Diagnostic& d : diagnostics)
    (d.severity == Severity::Error ? errors : warnings) += "\n      " + format_diagnostic(d);
  if (!config) {
    f.fail("the user config " + path + " cannot be used:" + errors,
           "fix it" + std::string(named ? ", or point NCJOULE_CONFIG at another file"
                                        : " (README, \"Set once\")"));
    return;
  }
  f.ok("user config " + path + warnings);
  if (!config->machine.empty())
    check_profile(f, resolve_machine(config->machine), "its machine profile");
  if (!config->tool_table.empty() && !exists(config->tool_table))
    f.fail("its tool table " + config->tool_table + " does not exist", "fix tool_table in " + path);
}

// Writing here: annotate -o and --in-place write a temporary file next to the target and rename
// it over the target. The check does both on a file of its own in the current folder, created
// under a name nobody can guess and never through a link (a folder others may write in, such as
// /tmp, may hold a link planted where a predictable name would be). Temporaries that runs killed
// with SIGKILL left here are removed, and named.
void check_write_here(Findings& f) {
  std::error_code ec;
  const fs::path here = fs::current_path(ec);
  const std::string folder = ec ? std::string(".") : here.string();
  for (const std::string& removed : stale_temporaries(".", true))
    f.note(removed, "an annotate or strip killed before it could finish left it (ncjoule removes "
                    "such files itself the next time it writes in their folder)");
  std::string probe;
  if (const std::string error = create_new_file(".", ".ncjoule-doctor-", "first\n", probe);
      !error.empty()) {
    f.note("cannot write a file in the current folder " + folder + ": " + error,
           "annotate -o and --in-place need a folder they may write in");
    return;
  }
  const std::string error = write_output_file(probe, "second\n");
  std::string read_back;
  if (std::ifstream in(probe, std::ios::binary); in)
    read_back.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  fs::remove(probe, ec);
  if (!error.empty())
    f.fail("cannot replace a file in the current folder " + folder + ": " + error,
           "annotate --in-place cannot work here; write with -o to another folder");
  else if (read_back != "second\n")
    f.fail("a file replaced in the current folder " + folder + " does not read back as written",
           "annotate --in-place cannot be trusted here; report this with the file system used");
  else
    f.ok("files can be written and replaced atomically in the current folder " + folder);
}

// LinuxCNC's stand-alone interpreter: optional, for comparing `ncjoule canon` with it.
void check_rs274(Findings& f) {
#ifdef _WIN32
  return; // LinuxCNC runs on Linux only
#endif
  if (const std::string rs274 = on_path("rs274"); rs274.empty())
    f.note("LinuxCNC's rs274 is not on the PATH",
           "optional: install linuxcnc-uspace to compare `ncjoule canon` with LinuxCNC");
  else
    f.ok("LinuxCNC's rs274 at " + rs274);
}

// The hooks: where they are installed, and those installed where a CAM system runs them
// (postprocessor-templates/*/README.md say how to install each).
void check_hooks(Findings& f) {
  std::vector<fs::path> candidates;
  if (const char* data = std::getenv("NCJOULE_DATA_DIR"); data && *data)
    candidates.push_back(fs::path(data) / "hooks");
  if (const fs::path data = installed_data_dir(); !data.empty())
    candidates.push_back(data / "hooks");
#ifdef _WIN32
  // The Windows zip keeps them at its top, next to bin (docs/windows.md).
  if (const fs::path exe = platform::program_file(); !exe.empty())
    candidates.push_back(exe.parent_path().parent_path() / "hooks");
#endif
  bool found = false;
  std::string hooks = "postprocessor-templates"; // where their READMEs are, for the notes below
  for (const fs::path& dir : candidates) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    std::string names;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      if (it->is_directory(ec))
        names += (names.empty() ? "" : ", ") + platform::utf8_from_path(it->path().filename());
    f.ok("post-processor hooks in " + platform::utf8_from_path(dir) +
         (names.empty() ? "" : " (" + names + ")"));
    hooks = platform::utf8_from_path(dir);
    found = true;
    break;
  }
  if (!found)
    f.note("no installed post-processor hooks (share/ncjoule/hooks next to the program)",
           "from the source tree: postprocessor-templates/");

#ifdef _WIN32
  // Windows CAM systems: the generic hook's .cmd (the Fusion hook lives inside the post).
  if (const std::string hook = on_path("ncjoule-hook.cmd"); hook.empty())
    f.note("the generic post hook (ncjoule-hook.cmd) is not on the PATH",
           "optional: hooks\\generic\\README.md in the zip (Fusion 360: "
           "hooks\\fusion360\\README.md)");
  else
    f.ok("generic post hook at " + hook);
  const char* appdata = std::getenv("APPDATA");
  const std::string freecad_macro =
      appdata ? std::string(appdata) + "\\FreeCAD\\Macro\\ncjoule_post.py" : std::string();
  std::error_code ec;
  if (freecad_macro.empty() || !fs::exists(platform::path_from_utf8(freecad_macro), ec))
    f.note("the FreeCAD post (ncjoule_post.py) is not in FreeCAD's macro folder",
           "optional: postprocessor-templates/freecad/README.md");
  else
    f.ok("FreeCAD post at " + freecad_macro);
  return;
#endif
  if (const std::string filter = on_path("ncjoule-filter"); filter.empty())
    f.note("the LinuxCNC filter (ncjoule-filter) is not on the PATH",
           "optional: " + hooks + "/linuxcnc/README.md");
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
           "optional: " + hooks + "/freecad/README.md");
  else
    f.ok("FreeCAD post at " + freecad);
  if (const std::string hook = on_path("ncjoule-hook.sh"); hook.empty())
    f.note("the generic post hook (ncjoule-hook.sh) is not on the PATH",
           "optional: " + hooks + "/generic/README.md (Fusion 360: " + hooks +
               "/fusion360/README.md)");
  else
    f.ok("generic post hook at " + hook);
}

// Every check, in the order they are printed.
const std::vector<Check>& checks() {
  static const std::vector<Check> list = {
      {"the program", check_program},           // version, where it runs from
      {"the C library", check_library},         // libncjoule's file, and the same version
      {"features built in", check_features},    // TBB, Ceres
      {"machine profiles", check_profiles},     // folders, names for -m, each loads
      {"the user config", check_user_config},   // where, parses, what it names exists
      {"writing files here", check_write_here}, // a file written and replaced atomically
      {"LinuxCNC's rs274", check_rs274},        // optional
      {"post-processor hooks", check_hooks},    // installed, and where CAM systems run them
  };
  return list;
}

int run_doctor() {
  Findings f;
  for (const Check& check : checks())
    check.run(f);
  std::printf("%s\n",
              f.failures ? "ncjoule cannot work as set up: see FAIL above" : "ncjoule is ready");
  std::fflush(stdout);
  return f.failures ? kInputError : kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  CLI::App* cmd = app.add_subcommand(
      "doctor", "Check the installation (the program and its library, the machine profiles, the "
                "user config, writing files here, LinuxCNC's rs274, the post-processor hooks) "
                "and say what is missing; exit 0 when ncjoule can work as set up");
  cmd->callback([&exit_code] { exit_code = run_doctor(); });
});

} // namespace
} // namespace ncjoule::cli
