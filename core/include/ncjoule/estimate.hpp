// ncjoule: the whole pipeline behind one call. Interprets a program, plans it on a machine,
// simulates material removal and integrates power, and folds the results into one summary per
// source line: what the command line, the annotator, the reports and the C API all show.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/energy.hpp"
#include "ncjoule/gcode.hpp"
#include "ncjoule/kinematics.hpp"
#include "ncjoule/machine.hpp"
#include "ncjoule/removal.hpp"

namespace ncjoule {

struct EstimateOptions {
  std::optional<Dialect> dialect; // empty: the machine's dialect, else detected from the file
  bool detect_dialect = false;    // detect even when the machine names a dialect (--dialect auto)
  std::optional<StockSpec> stock; // empty: the bounding box of the cutting moves
  bool simulate_removal = true;   // false: no tools needed, cutting power is zero
  RemovalOptions removal;
  EnergyOptions energy;
  // A LinuxCNC tool table: lengths for G43, and a tool for every entry with a diameter.
  ToolTable tool_table;
  std::string tool_table_path; // for diagnostics
  // Tools from a job file or the command line; a tool here replaces the program's header
  // comment (and the tool table) for the same number.
  std::map<int, Tool> tools;
  // The tool of moves that select and describe none; empty: the machine profile's.
  std::optional<Tool> default_tool;
};

// A job file (TOML) says what a program is cut from and with:
//   stock = "box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX"   (mm; or an .stl path)   or   stock_stl = "x.stl"
//   [[tool]]  number = 1, type = "flat" | "ball" | "bullnose" | "drill" | "chamfer",
//             diameter_mm, corner_radius_mm, point_angle_deg, tip_diameter_mm,
//             flute_length_mm, shank_diameter_mm
// Paths are relative to the job file's folder.
struct JobFile {
  std::string path;
  std::optional<StockSpec> stock; // empty: the job gives none
  std::map<int, Tool> tools;
};
// Parses the text of a job file that lives at `path`. Errors (file, line, column, key and what
// is wrong) go to `diagnostics` and give std::nullopt; unknown keys are warnings.
std::optional<JobFile> parse_job_file(std::string_view text, const std::string& path,
                                      std::vector<Diagnostic>& diagnostics);
// The same, reading the file.
std::optional<JobFile> read_job_file(const std::string& path, std::vector<Diagnostic>& diagnostics);

// Everything the results say about one source line, over every time it ran.
struct LineSummary {
  int line = 0;                 // 0-based
  std::string kind = "setting"; // what the line does, by its most telling command (kind_name)
  int commands = 0;             // canonical commands the line produced, over all its runs
  double start_s = 0;           // when it first ran
  double time_s = 0;            // over all its runs
  double length_mm = 0;
  double entry_speed_mm_s = 0; // at its first move
  double exit_speed_mm_s = 0;  // at its last move
  double peak_speed_mm_s = 0;
  std::vector<std::string> notes;
  bool has_move = false;
  double removed_mm3 = 0;
  double mrr_peak_mm3_s = 0;
  double energy_j = 0;
  double power_peak_w = 0;
  ComponentValues components_j{};
};

struct Estimate {
  std::string file;
  Dialect dialect;
  Toolpath toolpath;
  Timeline timeline;
  std::map<int, Tool> tools;            // by the number moves carry; 0: moves with none selected
  std::vector<int> unsimulated_tools;   // tools moves use that nothing describes (no removal)
  std::optional<RemovalResult> removal; // empty when removal was not simulated
  EnergyResult energy;
  std::vector<LineSummary> lines;      // one per source line that holds code, in file order
  std::vector<Diagnostic> diagnostics; // interpreter, planner, removal and energy, in order
  bool failed = false;                 // an error made the numbers meaningless (see diagnostics)
};

// Runs the pipeline. Never throws for bad input: problems are diagnostics, and `failed` is set
// only when no estimate could be made (the removal stage failed outright). What cannot be
// modelled (a tool nothing describes, an unknown code) is a warning and a labelled
// approximation.
Estimate estimate_program(const SourceFile& source, const MachineProfile& machine,
                          const EstimateOptions& options = {});

// "rapid", "feed", "arc", "probe", "dwell", "tool_change", "spindle", "coolant", ...
std::string kind_name(CanonKind kind);

} // namespace ncjoule
