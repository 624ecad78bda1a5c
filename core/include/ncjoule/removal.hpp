// ncjoule stage 3: material removal. The volume each sampled step of the toolpath removes from
// the stock, hence the material removal rate (MRR) through every block.
//
// Inputs: the tools (shape and size, from a tool table or from the comments CAM posts write), the
// stock (a box, an STL solid, or the bounding box of the cutting moves) and the timed, sampled
// path from kinematics. A removal engine holds the stock and removes what a 3-axis tool sweeps
// between two consecutive samples. The default engine is a Z-dexel grid (every (x, y) column
// keeps its material as intervals along Z, exact in Z); a voxel engine in the manner of the
// Anziani thesis sits behind the same interface as a reference.
//
// Positions are tool-tip positions in program coordinates (mm), as MotionSample gives them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "ncjoule/gcode.hpp"
#include "ncjoule/kinematics.hpp"
#include "ncjoule/tool.hpp"

namespace ncjoule {

// ---------------------------------------------------------------------------------------------
// Tools
// ---------------------------------------------------------------------------------------------

// What tool descriptions are read against, learnt by the interpreter: how the program writes
// comments, its units, and the lines where it selects a tool (a description without a number
// takes the number selected next to it).
struct ToolCommentContext {
  Dialect dialect;
  bool inch = false;                    // the program's units (its first G20/G21, G70/G71)
  bool units_known = false;             // set by the first units code or move
  std::map<int, int> selected_tools;    // 0-based source line -> T number selected there
  bool moves_before_first_tool = false; // a move runs before any tool is selected
  // Learns the units and the tool selections from the interpreter's commands, in order.
  void add(const CanonCommand& command);
};

// Reads the tool descriptions CAM posts write in comments, in the formats of:
//  - Fusion 360 / HSM and the posts built on it: "(T1 D=6. CR=0. - ZMIN=-5. - FLAT END MILL)",
//    "TAPER=118deg" for drills (the point angle) and chamfer mills (measured from the axis);
//  - Mastercam: "(1/2 FLAT ENDMILL TOOL - 1 DIA. OFF. - 1 LEN. - 1 DIA. - .5)" and
//    "( T1 | 1/2 FLAT ENDMILL | H1 | ... )";
//  - CamBam "( T3 : 3.0 )"; Vectric's tool list "(5 = End Mill {0.2500 inch} UpDown)" and the
//    shop style "(T1 = .5 ENDMILL)";
//  - a number and a keyed diameter (NX, SolidCAM, SolidWorks CAM): "(T1 D10. R0.5 MILL)",
//    "(TOOL 3 DIA 12.0 CORNER RAD 1.)", "(T02 - 1/2 FLAT END MILL)";
//  - FreeCAD's tool controller "(TC: 6mm Ball End)", numbered by the tool change after it;
//  - a description with a size next to a tool change ("T2 M6 (Change tool: End mill 6mm)",
//    Estlcam; "(Tool: End Mill {0.25 inch})" on the line after, Vectric), and Estlcam's
//    "(Required tools:)" list, which stands for tool 0 when the program selects none.
// Sizes are in the program's units and returned in mm. Comments that look like tool
// descriptions but cannot be used become warnings.
std::map<int, Tool> parse_tool_comments(const SourceFile& source, const ToolCommentContext& context,
                                        std::vector<Diagnostic>& diagnostics);

// Which tool each move cuts with: the tools `described` (tool table, CAM comments, job file,
// command line), by the number the moves carry (CanonCommand::state.tool; 0 when the program has
// selected none). Rules, each with a diagnostic where it guesses:
//  - a described number is that tool;
//  - tool 0 (moves before any tool change, or a program that never selects one: grbl-style
//    posts, Estlcam, pcb2gcode) is the tool described as T0, else the one tool described, else
//    the program's only tool, else `default_tool` (the machine profile's [default_tool]);
//  - a number nothing describes is in `unsimulated`: its moves are timed but remove nothing, and
//    a warning names the tool and the ways to describe it.
// Rapids need no tool: tool 0 used only by rapids gives no diagnostic.
// The tools a program's moves use, gathered one command at a time: the first line (0-based)
// each tool number moves on, and the first it cuts on (feed, arc or probe).
struct ToolUsage {
  std::map<int, int> first_move, first_cut;
  void add(const CanonCommand& command);
};

struct ToolAssignment {
  std::map<int, Tool> tools;    // by number, 0 included when a fallback was found
  std::vector<int> unsimulated; // numbers moves use that no tool stands for
  bool fallback = false;        // moves with no tool selected cut with a tool that stood in
  std::vector<Diagnostic> diagnostics;
};
ToolAssignment assign_tools(const ToolUsage& usage, const std::map<int, Tool>& described,
                            const std::optional<Tool>& default_tool, std::string_view file = {});
ToolAssignment assign_tools(const std::vector<CanonCommand>& commands,
                            const std::map<int, Tool>& described,
                            const std::optional<Tool>& default_tool, std::string_view file = {});

// Tools from a LinuxCNC tool table: every entry with a diameter becomes a tool of that size, its
// shape read from the entry's comment ("6mm ball end mill"), else a flat end mill (a note says
// so). Lengths stay with the interpreter (G43).
std::map<int, Tool> tools_from_table(const ToolTable& table, std::vector<Diagnostic>& diagnostics,
                                     std::string_view file = {});

// ---------------------------------------------------------------------------------------------
// Stock
// ---------------------------------------------------------------------------------------------

struct Box3 {
  double xmin = 0, ymin = 0, zmin = 0;
  double xmax = 0, ymax = 0, zmax = 0;
  bool empty() const { return !(xmax > xmin && ymax > ymin && zmax > zmin); }
};

// The unit a length is written in: its own ("-1in", "25mm"), or none, and then the program's
// (G20/G21) once it is known. An inch program's stock typed in inches is what its programmer
// means; one typed without a unit is read so.
enum class LengthUnit : std::uint8_t { Program, Mm, Inch };

// What the user asked for. Default: the bounding box of the cutting moves (see
// default_stock_box).
// Where a stock came from: the user (an option, a job file, the user config), the program's own
// CAM comments, or a guess from the cutting moves; None when there is no stock to cut.
enum class StockSource : std::uint8_t { None, Given, Program, Guessed };

struct StockSpec {
  enum class Kind { Default, Box, Stl } kind = Kind::Default;
  Box3 box; // Kind::Box, as written, in box_units (mm once in_mm() has run)
  std::array<LengthUnit, 6> box_units{}; // of xmin, ymin, zmin, xmax, ymax, zmax
  std::string stl_path;                  // Kind::Stl
  LengthUnit stl_units = LengthUnit::Program;
  // Where it came from, for the summaries: "--stock", "job file x.ncjoule.toml", "Vectric
  // Material Size block, lines 5-7", "CAMotics project bear.camotics", ...
  std::string origin;
  // The kind of that source, one word for the JSON and the header (docs/stock.md lists them):
  // "option", "hook-fusion360", "job-file", "stock-file", "camotics", "freecad-job",
  // "user-config", "vectric", "stock-comment", "sinumerik-workpiece", "heidenhain-blk-form".
  // Empty for Kind::Default (the stock is guessed from the cuts).
  std::string from;
  bool stated_by_program = false; // read from the program's CAM comments (cam_stock.hpp)
  // Kind::Box known by its size only ("(STOCK 4.125 x 3.625 x 1.000)"): `box` runs from 0 to
  // the size, and the stock is placed where the cutting moves fit it (place_sized_stock).
  bool size_only = false;
  // The stock in millimetres for a program in inches (`program_inch`) or millimetres: values
  // written without a unit take the program's.
  StockSpec in_mm(bool program_inch) const;
  // Whether any value was written without a unit (and so follows the program's).
  bool follows_program_units() const;
};

// "box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX", a path ending in .stl (any case), or "" / "auto" for the
// default. A box value may carry a unit ("box:0,0,-1in,4in,3in,0"; mm, in, inch, or "): without
// one it is in `units` (LengthUnit::Program: the program's units). An STL is in `units`. Returns
// std::nullopt, with an error in `diagnostics` placed within `origin`, when the text is not
// understood.
std::optional<StockSpec> parse_stock_spec(std::string_view text,
                                          std::vector<Diagnostic>* diagnostics = nullptr,
                                          const TextOrigin& origin = {},
                                          LengthUnit units = LengthUnit::Program);
// Why a given stock (`stock_mm`, as `spec` was written) looks like one in the wrong units or
// place against the box of the program's cutting moves: it does not overlap them, or is more
// than 20 times larger or smaller (an inch stock read as mm is 25.4 times too small). Empty when
// it fits. The sentence names the unit mix-up it likely is.
std::string stock_mismatch(const Box3& stock_mm, const Box3& cuts_mm, const StockSpec& spec,
                           bool program_inch);
// Where a stock known by its size only sits: on each axis X and Y the placement a CAM origin
// takes (at the stock's low corner, its centre, or its high corner) that leaves the least of
// the cutting moves' box `cuts` outside; in Z the top at Z0, or the bottom at Z0 when the cuts
// are above it. Ties go to the low corner in X/Y and to the top at Z0; without cuts, the low
// corner and the top at Z0. `how` says the placement chosen ("X from 0, Y centred, top at Z0").
Box3 place_sized_stock(const Box3& size, const std::optional<Box3>& cuts, std::string& how);

// A length with an optional unit ("12.5", "-1in", "3mm", "0.5\""): its number and unit; nullopt
// when it is not one.
std::optional<std::pair<double, LengthUnit>> parse_length(std::string_view text);

// The default stock: the bounding box of the cutting moves (Feed, Arc), extended in X and Y by
// the radius of the tool making each move. Moves whose tool is unknown are left out.
//  - Bottom: the lowest tip Z of a cutting move.
//  - Top: the highest Z at which a cutting move travels in XY at constant Z (a line or an XY
//    arc at one level). CAM clears material level by level with such moves, while the moves
//    that bring the tool down (plunges, ramps, helical entries) often start at feed from a
//    clearance or retract plane above the material: counting those would raise the top to the
//    clearance plane, inflate the stock and make later rapids below that plane look like
//    collisions. Only when the program has no such level move (a drilling-only program) is the
//    top the highest Z a cutting move starts from.
//  - Positioning written as feed moves is not cutting: a level move at a feed far above the
//    cutting feed of the same tool (more than 2.5 times the feed it cuts its deepest level at:
//    Fusion's "high feed" G1 F5000 between passes), or at or above the height the tool's first
//    plunge starts from (a clearance plane crossed at feed, as posts without G0 write it),
//    neither raises the top nor widens the box.
// std::nullopt when the program has no cutting move; the box may have no height (every level
// move at one Z), which the caller reports.
std::optional<Box3> default_stock_box(const std::vector<CanonCommand>& commands,
                                      const Timeline& timeline, const std::map<int, Tool>& tools);

// What the stock guess reads of one tool's cuts (its feed moves that cut, positioning left out:
// see default_stock_box), in program coordinates (mm).
struct ToolCuts {
  int number = 0;
  double radius = 0;
  Box3 centre; // the extent of the tool tip's path (not widened by the radius)
  // The same of the path at or below Z0 (to kZ0ToleranceMm): without lead-ins and ramps that
  // start above a stock whose top is Z0. Empty where nothing cuts there.
  Box3 centre_below_z0;
  // XY length the tool travels while cutting above Z0 (beyond kZ0ToleranceMm) and at or below it.
  double length_above_z0 = 0, length_below_z0 = 0;
  // The Z levels it cuts across XY at (level moves), with the XY length at each, highest first;
  // a program of many levels (3D waterlines) keeps the highest few hundred.
  std::vector<std::pair<double, double>> levels;
  double level_length = 0; // XY length of all its level moves
  // Highest Z of a level move that cuts; of any cutting move's start; of a cutting move that
  // travels in XY (ramps, helices); -inf where there is none.
  double top_level = -std::numeric_limits<double>::infinity();
  double top_start = top_level, top_travel = top_level;
};
// A cut within this of Z0 is at Z0 (a surface engraved at Z-0.005, a post's rounding).
inline constexpr double kZ0ToleranceMm = 0.01;

// default_stock_box gathered one command at a time, for a pipeline that keeps no list of the
// program's commands: per tool number, the extent of its cutting moves (arcs walked along);
// box() widens each tool's by its radius once the tools are known.
class StockExtent {
public:
  void add(const CanonCommand& command);
  std::optional<Box3> box(const std::map<int, Tool>& tools) const;
  // What each tool of `tools` cuts (tools that cut nothing left out), by tool number.
  std::vector<ToolCuts> tool_cuts(const std::map<int, Tool>& tools) const;
  // The Z levels the cutting moves start and end at (the voxel engine's layer boundaries), up
  // to a few thousand.
  std::vector<double> cutting_levels() const;
  // Length of the cutting moves of tool `number` (mm), less its level moves at or above `top_z`
  // (to kZ0ToleranceMm): passes through the air over a stock whose top is there (a facing pass
  // at Z0 over a stock whose top is Z0) remove nothing. Plunges, ramps and 3D moves all count.
  double cutting_length(int number, double top_z = std::numeric_limits<double>::infinity()) const;
  // Feed moves box() took for positioning, not cutting (see default_stock_box), over all tools.
  std::size_t positioning_moves() const;

private:
  struct Extent {
    double xmin = std::numeric_limits<double>::infinity(), ymin = xmin, zmin = xmin;
    double xmax = -std::numeric_limits<double>::infinity(), ymax = xmax, zmax = xmax;
    void include(const Pose& p);
    void include(const Extent& e);
  };
  // XY length of level moves by their Z (to 1e-4 mm), up to kMaxLevelZs levels; past that, the
  // length is only split at Z0.
  struct LevelLengths {
    std::map<double, double> at;
    double above = 0, below = 0;
    void add(double z, double length);
  };
  // The level moves (across XY at one Z) of one tool at one feed rate, before its first plunge
  // and after it (those at or above that plunge's start are left out as they come).
  struct Level {
    double feed = 0; // mm/min (G94), or 0 where the feed is not a rate per minute
    Extent before, after;
    Extent before_low, after_low; // of the moves at or below Z0
    std::size_t moves_before = 0, moves_after = 0;
    LevelLengths length_before, length_after;
  };
  struct PerTool {
    Extent other;     // the tool's feed moves that are not level: plunges, ramps, helices
    Extent other_low; // their path at or below Z0
    double other_above = 0, other_below = 0; // their XY length above Z0 and at or below it
    double top_start = -std::numeric_limits<double>::infinity(); // of any cutting move
    double top_travel = top_start; // highest Z of a non-level move that travels in XY
    double first_plunge_start = std::numeric_limits<double>::quiet_NaN();
    std::vector<Level> levels;    // by feed, at most kMaxFeeds (beyond: folded into the last)
    std::size_t above_plunge = 0; // level moves after the first plunge at or above its start
    double length = 0;
    // A hop: level moves right after a straight rise in Z, held until the tool's next non-level
    // move. A descent next makes them a link at a retract height (left out, as personal-use
    // Fusion writes its retracts at the cutting feed); anything else makes them cuts.
    bool rose = false;
    Pose hop_from; // where the rise (or the last held move) ended
    std::vector<CanonCommand> hop;
  };
  static constexpr std::size_t kMaxHopMoves = 8;
  static constexpr std::size_t kMaxLevelZs = 256;
  // A level move of tool `t` into its levels (or left out above its first plunge).
  void add_level(PerTool& t, const CanonCommand& cmd);
  // Where a move counts in any case: its extent's corners and arc sides, length, levels.
  void include_move(PerTool& t, Extent& into, const CanonCommand& cmd);
  // An arc's points into an extent (its end points are included by the caller).
  static void include_arc(Extent& into, const CanonCommand& arc);
  // The tool's held hop moves as cuts.
  void flush_hop(PerTool& t);
  bool holds_hops() const;
  StockExtent settled() const; // a copy with every held hop taken as cuts
  static constexpr std::size_t kMaxLevels = 4096;
  static constexpr std::size_t kMaxFeeds = 64;
  // The feed at which the tool cuts its deepest level (0: none known); level moves more than
  // kHighFeedFactor times faster are positioning.
  static double cutting_feed_of(const PerTool& t);
  // Whether level bucket `l` (or its moves before the first plunge) holds positioning only.
  static bool positioning_feed(const PerTool& t, const Level& l);
  static bool before_plunge_positioning(const PerTool& t, const Level& l);
  // The tool's level moves that cut: not at a feed far above its cutting feed, not above its
  // first plunge's start. Sets `positioning` to how many were left out.
  static Extent cutting_levels_of(const PerTool& t, std::size_t& positioning,
                                  bool below_z0 = false);
  std::map<int, PerTool> tools_;
  std::vector<double> levels_;
};

// The stock a machinist would take when nothing states it, from the cuts of one setup
// (docs/removal.md, "The guessed stock", gives the rules with an example each):
//  - top: Z0 when the cuts travel at or below it (posts put Z0 on the stock's top: an engraving
//    just under Z0 cuts a stock whose top is Z0, a face at Z-0.5 has material above it); a face
//    at Z0 itself has a facing allowance above it; a program that cuts above Z0 (Z0 on the
//    table) has its top at the highest level it cuts;
//  - bottom: the lowest cut;
//  - outline: the tool paths' extent; a face mill's passes, which run past the part, do not
//    widen it where other tools say where the part is;
//  - a later setup cuts what the first one left: its outline is no larger than the first
//    setup's, nor its height.
struct StockGuess {
  Box3 box;                       // program coordinates, mm
  std::vector<std::string> rules; // the rules that set it, in words, for the summary
};
// `first_setup`: the stock of the program's first setup, which bounds a later setup's (null for
// the first). std::nullopt when nothing cuts.
std::optional<StockGuess> guess_stock(const std::vector<ToolCuts>& cuts, bool program_inch,
                                      const Box3* first_setup = nullptr);

// Which way a program's Z runs, from where its rapids cross XY: on a standard mill (+Z away from
// the work) a program retracts to cross, so its rapids across XY run above its lowest cut. One
// whose every such rapid runs below every point of its cuts across XY (plunges and retracts in
// Z alone left out) was posted for a machine whose +Z points into the work (a post that scales
// Z by -1, as Estlcam allows).
class ZDirectionScan {
public:
  void add(const CanonCommand& command);
  // At least one rapid across XY and one cut, every such rapid below every cut.
  bool points_down() const;
  double highest_rapid_z() const { return highest_rapid_; } // mm
  double lowest_cut_z() const { return lowest_cut_; }       // mm

private:
  double highest_rapid_ = -std::numeric_limits<double>::infinity();
  double lowest_cut_ = std::numeric_limits<double>::infinity();
  bool rapid_ = false, cut_ = false;
};

// The command as removal sees it on a machine whose +Z points into the work: Z negated (arcs in
// the XZ and YZ planes turn the other way).
CanonCommand mirrored_z(const CanonCommand& command);

struct Triangle {
  double v[3][3]; // three vertices, x y z
};
struct TriangleMesh {
  std::vector<Triangle> triangles;
  Box3 bounds() const;
  // How many triangles a vertical line through the mesh's XY bounds meets, on average: 2 for a
  // closed solid with no overhang, more for stacked or overlapping shells. Each meeting is a
  // crossing to sort while the stock is filled, so memory grows with it.
  double crossings_per_column() const;
};
// Binary or ASCII STL, in mm. On failure returns std::nullopt with an error in `diagnostics`
// (the file, and the line of an ASCII STL).
std::optional<TriangleMesh> parse_stl(std::string_view bytes, const std::string& path,
                                      std::vector<Diagnostic>& diagnostics);
std::optional<TriangleMesh> read_stl(const std::string& path, std::vector<Diagnostic>& diagnostics);

// The XY grid of columns shared by both engines: column (i, j) has its centre at
// (x0 + (i + 0.5) * dx, y0 + (j + 0.5) * dy). The grid covers the stock's XY bounds exactly.
struct GridFrame {
  double x0 = 0, y0 = 0;
  double dx = 1, dy = 1;
  int nx = 0, ny = 0;
  double z0 = 0, z1 = 0; // Z extent of the stock (the voxel engine's layers)
  // Voxel engine: Z values its layer boundaries are placed on (besides z0 and z1), so that the
  // flat floors a program cuts fall between layers instead of through them. Empty: uniform.
  std::vector<double> z_levels;
  std::size_t columns() const { return std::size_t(nx) * std::size_t(ny); }
  double column_x(int i) const { return x0 + (i + 0.5) * dx; }
  double column_y(int j) const { return y0 + (j + 0.5) * dy; }
};
// A grid over `bounds` whose cells are at most `spacing_mm` wide and tile the bounds exactly.
GridFrame make_grid(const Box3& bounds, double spacing_mm);

struct ZInterval {
  double lo = 0, hi = 0;
};

// A solid the engines can be filled from.
class StockShape {
public:
  virtual ~StockShape() = default;
  virtual Box3 bounds() const = 0;
  virtual std::string description() const = 0;
  // Material along the vertical line through every column centre, as sorted, disjoint
  // intervals: column c (= j * nx + i) holds intervals[first[c] .. first[c + 1]).
  virtual void fill_columns(const GridFrame& grid, std::vector<std::uint32_t>& first,
                            std::vector<ZInterval>& intervals) const = 0;
};
std::unique_ptr<StockShape> make_box_stock(const Box3& box, std::string description);
// Columns are ray-cast vertically against the triangles; a column with an odd number of
// crossings (an open mesh) drops its last crossing and is counted in *open_columns.
std::unique_ptr<StockShape> make_mesh_stock(TriangleMesh mesh, std::string description,
                                            std::size_t* open_columns = nullptr);

// ---------------------------------------------------------------------------------------------
// Engines
// ---------------------------------------------------------------------------------------------

// Dexel: the default, exact in Z. Voxel: the reference in the manner of the Anziani thesis, a
// 3-D grid of one byte per voxel where, for every step, each voxel in the bounding box of the
// tool's swept volume has its centre tested against the tool; slow on purpose, and simple
// enough to trust.
enum class EngineKind : std::uint8_t { Dexel, Voxel };
std::string_view engine_name(EngineKind kind); // "dexel", "voxel"

// A point of the tool tip in the program's frame (mm).
using Point3 = Eigen::Vector3d;

// Work counters, for benchmarks.
struct EngineStats {
  std::uint64_t steps = 0;
  std::uint64_t columns_visited = 0; // columns inside the tool's footprint, summed over steps
                                     // (dexel: in tiles with material above the tool)
  std::uint64_t cells_tested = 0;    // dexel: columns whose envelope was computed;
                                     // voxel: voxels whose centre was tested
};

// One straight step of a tool, for removal in batches.
struct RemovalStep {
  const Tool* tool = nullptr;
  Point3 from = Point3::Zero(), to = Point3::Zero();
};

class RemovalEngine {
public:
  virtual ~RemovalEngine() = default;
  virtual EngineKind kind() const = 0;
  // Removes everything the tool sweeps moving in a straight line with its tip from `from` to
  // `to`, and returns the volume removed (mm^3). Deterministic: the same calls in the same
  // order give the same result bit for bit, whatever the number of threads.
  virtual double remove_step(const Tool& tool, const Point3& from, const Point3& to) = 0;
  // Removes the steps in order; volumes[k] is step k's volume. The same result, bit for bit, as
  // remove_step on each in turn, for any number of threads. The dexel engine splits the batch
  // over tiles of its grid, each tile applying the steps that touch it in order, in parallel.
  // With `cut_tops`, cut_tops[k] is the highest top of material step k cut into (mm, the
  // steps' Z): with the tool's lowest point, the depth of the cut. NaN where an engine does not
  // say; -inf where the step cut nothing.
  virtual void remove_steps(const std::vector<RemovalStep>& steps, std::vector<double>& volumes,
                            std::vector<double>* cut_tops = nullptr);
  virtual double material_volume_mm3() const = 0; // what is left
  // Whether there is material at the point (in the column under it, at its height).
  virtual bool material_at(const Point3& point) const = 0;
  // Whether any material lies above `z_floor` in a column whose cell comes within `radius` (in
  // X and Y) of the segment from `from` to `to`: a conservative test of whether the space a move
  // sweeps, inflated by a clearance, is clear (optimize.hpp). Columns are taken whole: a cell
  // that only touches the inflated footprint counts. std::nullopt where the engine cannot say
  // (the voxel engine: optimize uses the dexel engine).
  virtual std::optional<bool> material_above(const Point3& from, const Point3& to, double radius,
                                             double z_floor) const;
  virtual std::size_t memory_bytes() const = 0;
  virtual const GridFrame& grid() const = 0;
  virtual const EngineStats& stats() const = 0;
};

// `grid` is the XY grid. The voxel engine also cuts [grid.z0, grid.z1] into layers of at most
// min(dx, dy), with boundaries on grid.z_levels (see voxel_layer_bounds).
std::unique_ptr<RemovalEngine> make_removal_engine(EngineKind kind, const StockShape& stock,
                                                   const GridFrame& grid);

// The voxel engine's layer boundaries, from grid.z0 to grid.z1: every Z of grid.z_levels inside
// the stock is a boundary (up to as many levels as there are uniform layers; beyond that the
// levels are ignored), and each gap between boundaries is split evenly into layers no thicker
// than min(dx, dy).
std::vector<double> voxel_layer_bounds(const GridFrame& grid);

// ---------------------------------------------------------------------------------------------
// Running a program
// ---------------------------------------------------------------------------------------------

struct RemovalOptions {
  EngineKind engine = EngineKind::Dexel;
  double grid_mm = 0; // 0: automatic (automatic_grid_spacing, then budgets)
  // The automatic grid is coarsened (with a note) beyond 4M columns (about 128 MiB of stock
  // model), beyond max_voxels, or beyond the memory budget: caps, not what chooses the grid.
  std::size_t max_columns = 4'000'000;
  std::size_t max_voxels = 2'000'000'000;
  // Memory the stock model may take; 0: kDefaultRemovalMemoryBudget. A grid given with grid_mm
  // that needs more is refused (an error names the budget); the automatic one is coarsened.
  std::size_t memory_budget_bytes = 0;
  // The automatic grid keeps the removal work within about this many column visits (see
  // automatic_grid_spacing).
  double work_columns = 1.5e8;
  std::string source_path; // file name used in diagnostics
  // The program's +Z points into the work (ZDirection::Down): removal negates Z, of the moves
  // and of a given stock (box or STL, in program coordinates). The extent that sizes the default
  // stock must then be of the mirrored commands (mirrored_z).
  bool mirror_z = false;
  bool program_inch = false; // the program's units (G20): for what a stock's units are said to be
  // The stock of the program's first setup, in program coordinates (mm), when this is a later
  // setup: a guessed stock is no larger than what the first setup left.
  std::optional<Box3> first_setup_stock;
};
inline constexpr std::size_t kDefaultRemovalMemoryBudget = std::size_t(1) << 30; // 1 GiB

// The finest grid spacing the automatic grid uses: the smallest diameter / 120 (60 cells across
// a radius), kept within [0.01, 1] mm: 0.05 mm for a 6 mm end mill. Removed volumes stay within
// about 0.05% of the exact ones at this spacing on the closed-form cases (docs/removal.md gives
// the error against the grid spacing).
double default_grid_spacing(const std::map<int, Tool>& tools);
// The grid the figures need: the spacing at which the volume removed gains or loses about 0.1%
// along the cuts' edges (an edge error of about 0.06 x spacing / diameter per cut,
// docs/removal.md), each tool weighted by the area it sweeps (its cutting length below the
// stock's top `top_z` times its diameter). Never finer than default_grid_spacing, nor coarser
// than a twentieth of the largest tool (at most 2 mm). It follows the job alone: not the memory
// of the machine it runs on.
double accuracy_grid_spacing(const StockExtent& extent, const std::map<int, Tool>& tools,
                             double top_z = std::numeric_limits<double>::infinity());
// The grid removal uses when none is given: accuracy_grid_spacing, coarsened (up to a twentieth
// of the largest tool diameter, 2 mm at most) while the work (steps times the columns each
// covers, estimated from the cutting length of each tool) would exceed `work_columns`; the
// simulator then caps it by RemovalOptions::max_columns and the memory budget, with a note. A
// small job (given `stock_area_mm2`, the stock's XY area: at most 1M columns at
// default_grid_spacing, and a quarter of the work) keeps default_grid_spacing. `top_z`: the
// stock's top, for accuracy_grid_spacing.
double automatic_grid_spacing(const StockExtent& extent, const std::map<int, Tool>& tools,
                              double work_columns = 1.5e8, double stock_area_mm2 = 0,
                              double top_z = std::numeric_limits<double>::infinity());
// The max_sample_step_mm to ask the planner for: steps as long as the grid spacing, or a quarter
// of the smallest tool radius if that is longer, at most 1 mm. A step's sweep is exact along
// it, so the step length sets only how finely MRR is resolved along a move (and the chords of
// arcs).
double recommended_sample_step(const std::map<int, Tool>& tools, double grid_mm);
// The memory (bytes) a removal engine would take over `grid` for the stock: what the budget is
// checked against before anything is allocated. A mesh stock's crossings
// (TriangleMesh::crossings_per_column) are counted too: they are held while it is filled.
std::size_t estimated_removal_memory(EngineKind engine, const GridFrame& grid,
                                     StockSpec::Kind stock_kind, double crossings_per_column = 2);
// The widest stock ncjoule takes, in mm: more than any machine's travel, so that a stock in the
// wrong units or at absurd coordinates is said to be so, before any grid is tried on it.
inline constexpr double kMaxStockWidthMm = 100'000;

// Removal results for one timed command (parallel to Timeline::commands).
struct CommandRemoval {
  // Volume removed between sample i and i+1 of the command (size samples.size() - 1, or 0).
  std::vector<double> step_volume_mm3;
  // Depth of cut of each step (mm): from the highest material it cut into down to the tool's
  // lowest point; empty where the engine does not say (the voxel engine), 0 where it cut nothing.
  std::vector<float> step_depth_mm;
  double removed_mm3 = 0;
  double mrr_mean_mm3_s = 0; // removed_mm3 / duration
  double mrr_peak_mm3_s = 0; // highest step volume / step time
  bool collision = false;    // a rapid that removed material
};

struct RemovalResult {
  std::vector<CommandRemoval> commands; // parallel to Timeline::commands
  double removed_mm3 = 0;
  std::string stock_description; // which stock was used, e.g. "box ... (from cutting moves)"
  StockSource stock_source = StockSource::None;
  std::string stock_from = "none"; // StockSpec::from; "guess" for a box of the cuts
  std::string stock_origin;        // StockSpec::origin, where that stock is written
  Box3 stock_box;               // its bounds in program coordinates (mm), as the program writes Z
  std::size_t memory_bytes = 0; // memory held by the stock model
  std::vector<Diagnostic> diagnostics; // collisions, unknown tools, ...
  EngineKind engine = EngineKind::Dexel;
  GridFrame grid;              // the grid used (dx, dy: cell size in mm)
  double stock_volume_mm3 = 0; // material before the program, as the engine holds it
  bool z_mirrored = false;     // the program's Z was read mirrored (RemovalOptions::mirror_z)
  EngineStats stats;
};

// A move and its timing, as removal and energy take them one at a time.
struct TimedMove {
  std::size_t index = 0; // position in the timeline
  const CanonCommand* command = nullptr;
  const TimedCommand* timed = nullptr;
};

// Removal one move at a time, in program order: simulate_removal for a pipeline that keeps no
// program-sized lists. The stock and the grid are set up once; moves are removed in batches
// through RemovalEngine::remove_steps (tiles of the grid in parallel, each applying the batch's
// steps in order), so results are the same bit for bit as step by step, for any thread count.
class RemovalSimulator {
public:
  // Sets up the stock (`spec`; the default box from `extent`) and the grid for `tools` (the
  // tools moves cut with, by the number they carry). When there is nothing to cut (no stock, a
  // grid over the memory budget), ready() is false and the diagnostics say why.
  RemovalSimulator(const StockSpec& spec, const StockExtent& extent,
                   const std::map<int, Tool>& tools, const RemovalOptions& options);
  ~RemovalSimulator();
  RemovalSimulator(const RemovalSimulator&) = delete;
  RemovalSimulator& operator=(const RemovalSimulator&) = delete;

  bool ready() const { return engine_ != nullptr; }
  // Where the stock came from (StockSource::None when there is none to cut).
  StockSource stock_source() const { return engine_ ? totals_.stock_source : StockSource::None; }
  const GridFrame& grid() const { return grid_; }
  // The sample step the planner should use for this grid and these tools.
  double sample_step_mm() const { return sample_step_; }
  // Removes a batch of moves, in order: out[k] is moves[k]'s removal. Moves of a tool not in
  // `tools`, and commands that are not moves, remove nothing. Rapids that cut a given stock are
  // flagged as collisions with a warning; rapids that enter a guessed stock show where the guess
  // is too large: what they pass through is air (no volume), and summary() notes them. What
  // `out` held is replaced; the memory of its step vectors is reused.
  void remove(const std::vector<TimedMove>& moves, std::vector<CommandRemoval>& out);
  // Everything but the per-command list: stock, grid, volumes, memory, work counters, and the
  // diagnostics so far.
  RemovalResult summary() const;

private:
  std::map<int, Tool> tools_;
  RemovalOptions options_;
  std::unique_ptr<StockShape> stock_;
  std::unique_ptr<RemovalEngine> engine_;
  GridFrame grid_;
  double crossings_ = 2; // of a mesh stock: TriangleMesh::crossings_per_column
  double sample_step_ = 0;
  RemovalResult totals_; // commands left empty
  bool warned_no_samples_ = false;
  bool first_move_checked_ = false; // the program's first move was checked for starting inside
  bool warned_rotary_ = false;      // a move of A/B/C was said to make removal approximate
  // Rapids that entered a guessed stock (taken as air, see remove()): count, volume, first lines.
  std::size_t air_rapids_ = 0;
  double air_rapid_mm3_ = 0;
  std::vector<int> air_rapid_lines_;
  std::vector<RemovalStep> steps_; // scratch
  std::vector<double> volumes_;
  std::vector<double> cut_tops_;
};

// Plays the timeline on the stock. Moves (Traverse, Feed, Arc, Probe) remove material step by
// step between consecutive samples; a Traverse that removes material is flagged as a collision
// with a warning. Moves whose tool is not in `tools` remove nothing (assign_tools says which and
// why). A stock that cannot be read is an error and nothing is removed.
RemovalResult simulate_removal(const std::vector<CanonCommand>& commands, const Timeline& timeline,
                               const std::map<int, Tool>& tools, const StockSpec& stock,
                               const RemovalOptions& options = {});

} // namespace ncjoule
