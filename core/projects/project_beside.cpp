// The project file beside a program (projects.hpp says the order).
#include <algorithm>
#include <filesystem>

#include "ncjoule/projects.hpp"
#include "ncjoule/text.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule {
namespace {

namespace fs = std::filesystem;

// A folder with more files of a kind than this is not searched further: the projects of a
// program sit beside it, not among thousands.
constexpr std::size_t kMaxCandidates = 64;

bool has_extension(const fs::path& p, std::string_view ext) {
  return to_lower(p.extension().string()) == ext;
}

} // namespace

std::optional<ProjectFile> project_beside(const std::string& program,
                                          std::vector<Diagnostic>& diagnostics) {
  if (program.empty() || program == "-") return std::nullopt;
  const fs::path path(program);
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::vector<fs::path> camotics, freecad;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code type_error;
    if (!it->is_regular_file(type_error)) continue;
    const fs::path& p = it->path();
    if (has_extension(p, ".camotics") && camotics.size() < kMaxCandidates) camotics.push_back(p);
    if (has_extension(p, ".fcstd") && freecad.size() < kMaxCandidates) freecad.push_back(p);
  }
  if (camotics.empty() && freecad.empty()) return std::nullopt;
  std::sort(camotics.begin(), camotics.end());
  // The program's own document (same name) first, then the others in order.
  std::stable_sort(freecad.begin(), freecad.end(), [&](const fs::path& a, const fs::path& b) {
    return (a.stem() == path.stem()) > (b.stem() == path.stem());
  });
  std::vector<ProjectFile> found;
  for (const fs::path& p : camotics) {
    std::vector<Diagnostic> problems;
    const auto text = read_text_file(p.string(), "a CAMotics project", problems);
    if (!text) {
      for (Diagnostic& d : problems) {
        d.severity = Severity::Warning;
        d.message = "CAMotics project not read: " + d.message;
        diagnostics.push_back(std::move(d));
      }
      continue;
    }
    if (auto project = parse_camotics_project(*text, p.string(), program, diagnostics))
      found.push_back(std::move(*project));
  }
  for (const fs::path& p : freecad) {
    const bool own = p.stem() == path.stem();
    if (!own) {
      // Another document is this program's only if one of its Jobs names it as its output.
      std::vector<Diagnostic> quiet;
      auto project = read_freecad_document(p.string(), program, quiet, true);
      if (!project) continue;
      diagnostics.insert(diagnostics.end(), quiet.begin(), quiet.end());
      found.push_back(std::move(*project));
      continue;
    }
    if (!reads_freecad_documents()) {
      diagnostics.push_back({Severity::Warning, p.string(), 0, 0,
                             "FreeCAD document not read: this build of ncjoule has no zlib to "
                             "inflate it; give its stock with --stock"});
      continue;
    }
    if (auto project = read_freecad_document(p.string(), program, diagnostics))
      found.push_back(std::move(*project));
  }
  if (found.empty()) return std::nullopt;
  auto with_stock = std::find_if(found.begin(), found.end(),
                                 [](const ProjectFile& f) { return f.stock.has_value(); });
  if (with_stock == found.end()) {
    auto with_tools = std::find_if(found.begin(), found.end(),
                                   [](const ProjectFile& f) { return !f.tools.empty(); });
    return with_tools == found.end() ? std::nullopt : std::optional(*with_tools);
  }
  for (auto other = with_stock + 1; other != found.end(); ++other)
    if (other->stock)
      diagnostics.push_back(
          {Severity::Note, other->path, 0, 0,
           "also gives a stock for this program; the one of " + with_stock->path + " is used"});
  return *with_stock;
}

} // namespace ncjoule
