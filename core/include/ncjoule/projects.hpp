// ncjoule projects: what a CAM or simulator project file beside a program says the program is cut
// from and with. Such a file holds the stock its author set in the CAM system (and, for CAMotics,
// the tools), so it comes before the user config's stock and the program's own comments
// (docs/stock.md gives the whole order).
//
// Read:
//  - a CAMotics project (.camotics, JSON) whose "files" name the program: its workpiece bounds
//    when "automatic" is false (CAMotics keeps them in mm whatever the project's "units"; an
//    automatic workpiece is CAMotics' own guess from the cuts and is not taken), and its tools
//    (cylindrical, ballnose, conical, snubnose; each in its own "units");
//  - a FreeCAD document (.FCStd, a zip holding Document.xml and the shapes as .brp files) whose
//    Path Job posts the program: the Job's Stock when it is a box (CreateBox: Length, Width,
//    Height at its Placement) or the model's bounding box with allowances (ExtendedBoundBox,
//    from the stock shape's vertices at its Placement). A cylinder stock or one taken from an
//    existing solid is named and not read: ncjoule models box and STL stocks.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncjoule/diagnostic.hpp"
#include "ncjoule/removal.hpp"
#include "ncjoule/tool.hpp"

namespace ncjoule {

struct ProjectFile {
  std::string path;
  std::optional<StockSpec> stock; // in mm (box_units Mm); `from` and `origin` say which file
  std::map<int, Tool> tools;      // described as the project describes them (CAMotics)
};

// The CAMotics project `text` read from `path`, for the program whose file is `program` (a path
// as given: the project's "files" are relative to the project's folder). std::nullopt, with a
// warning at the file, line and column, when the text is not a project ncjoule can read or
// does not name the program; a tool it cannot model is a warning and left out.
std::optional<ProjectFile> parse_camotics_project(std::string_view text, const std::string& path,
                                                  const std::string& program,
                                                  std::vector<Diagnostic>& diagnostics);

// The FreeCAD document at `path`, for `program`: the Job that posts it (the one whose
// PostProcessorOutputFile names the program's file, else the only Job unless `posting_only`),
// and its Stock. With `posting_only`, a document with no Job that names the program is
// std::nullopt without a word.
// std::nullopt, with a warning, when the file cannot be read or holds no such Job; a stock
// ncjoule cannot model gives a project without a stock, and a warning that says what it is.
std::optional<ProjectFile> read_freecad_document(const std::string& path,
                                                 const std::string& program,
                                                 std::vector<Diagnostic>& diagnostics,
                                                 bool posting_only = false);
// The same from the bytes of the document (read from `path`).
std::optional<ProjectFile> parse_freecad_document(std::string_view bytes, const std::string& path,
                                                  const std::string& program,
                                                  std::vector<Diagnostic>& diagnostics,
                                                  bool posting_only = false);

// Whether this build reads FreeCAD documents (it needs zlib to inflate them).
bool reads_freecad_documents();

// The project beside the program at `program`, in this order: a CAMotics project in its folder
// that names it, then its FreeCAD document (PROGRAM.FCStd), then another FreeCAD document in the
// folder whose Job posts it. The first that gives a stock is taken (a note names any other that
// gives one too); without a stock, the first that gives tools. std::nullopt when none is there.
// A project that cannot be read is a warning and the next is tried.
std::optional<ProjectFile> project_beside(const std::string& program,
                                          std::vector<Diagnostic>& diagnostics);

} // namespace ncjoule
