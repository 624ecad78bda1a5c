// Job files: the stocks, work offsets and tool table of a job, in TOML (see JobFile in
// estimate.hpp). Every error names the file, the line and column, and the key.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <toml++/toml.h>

#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"
#include "ncjoule/text.hpp"
#include "ncjoule/text_file.hpp"
#include "ncjoule/tool.hpp"

namespace ncjoule {
namespace {

struct JobReader {
  const std::string& path;
  std::vector<Diagnostic>& diagnostics;
  bool failed = false;

  void say(Severity severity, const toml::node* node, const std::string& key,
           const std::string& what) {
    int line = 0, column = 0;
    if (node) line = int(node->source().begin.line), column = int(node->source().begin.column);
    diagnostics.push_back({severity, path, line, column, key + ": " + what});
    if (severity == Severity::Error) failed = true;
  }
  void error(const toml::node* node, const std::string& key, const std::string& what) {
    say(Severity::Error, node, key, what);
  }
  // Diagnostics a reader of one value made, already placed.
  void add(const std::vector<Diagnostic>& made) {
    for (const Diagnostic& d : made) {
      diagnostics.push_back(d);
      if (d.severity == Severity::Error) failed = true;
    }
  }

  // A path from the job file, relative to the job file's folder.
  std::string resolve(const std::string& relative) const {
    const std::filesystem::path p(relative);
    if (p.is_absolute()) return relative;
    return (std::filesystem::path(path).parent_path() / p).lexically_normal().string();
  }

  // A number within [lowest, highest] (what the thing it stands for can physically be).
  std::optional<double> number(const toml::table& table, std::string_view key,
                               const std::string& where, double lowest, double highest) {
    const toml::node* node = table.get(key);
    if (!node) return std::nullopt;
    const std::string name = where + std::string(key);
    if (!node->is_number()) {
      error(node, name, "must be a number");
      return std::nullopt;
    }
    const double value = *node->value<double>();
    if (!(value >= lowest && value <= highest)) {
      error(node, name,
            "must be a number from " + format_limit(lowest) + " to " + format_limit(highest));
      return std::nullopt;
    }
    return value;
  }
  static std::string format_limit(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
  }

  // `stock` (a box or STL spec) or `stock_stl` (a path) of `table`, keys named after `where`.
  std::optional<StockSpec> read_stock(const toml::table& table, const std::string& where,
                                      LengthUnit units) {
    const toml::node* stock = table.get("stock");
    const toml::node* stock_stl = table.get("stock_stl");
    if (stock && stock_stl) {
      error(stock_stl, where + "stock_stl", "give either stock or stock_stl, not both");
    } else if (stock) {
      if (!stock->is_string()) {
        error(stock, where + "stock", "must be a string such as \"box:0,0,-20,100,60,0\"");
        return std::nullopt;
      }
      // The value's first character is just after the opening quote.
      const TextOrigin origin{path, int(stock->source().begin.line),
                              int(stock->source().begin.column) + 1};
      std::vector<Diagnostic> problems;
      if (auto spec = parse_stock_spec(*stock->value<std::string>(), &problems, origin, units)) {
        if (spec->kind == StockSpec::Kind::Stl) spec->stl_path = resolve(spec->stl_path);
        spec->from = "job-file";
        return spec;
      }
      for (Diagnostic& d : problems)
        d.message = where + "stock: " + d.message;
      add(problems);
    } else if (stock_stl) {
      if (!stock_stl->is_string() || stock_stl->value<std::string>()->empty()) {
        error(stock_stl, where + "stock_stl", "must be the path of an STL file");
        return std::nullopt;
      }
      StockSpec spec;
      spec.kind = StockSpec::Kind::Stl;
      spec.stl_path = resolve(*stock_stl->value<std::string>());
      spec.stl_units = units;
      spec.origin = path;
      spec.from = "job-file";
      return spec;
    }
    return std::nullopt;
  }

  void read_tool(const toml::node& node, std::size_t index, JobFile& job) {
    const std::string where = "tool[" + std::to_string(index + 1) + "].";
    const toml::table* t = node.as_table();
    if (!t) return error(&node, "tool[" + std::to_string(index + 1) + "]", "must be a table");
    for (const auto& [key, value] : *t) {
      static const char* known[] = {"number",          "type",
                                    "diameter_mm",     "corner_radius_mm",
                                    "point_angle_deg", "tip_diameter_mm",
                                    "flute_length_mm", "shank_diameter_mm",
                                    "flutes",          "description"};
      if (std::find(std::begin(known), std::end(known), key.str()) == std::end(known))
        say(Severity::Warning, &value, where + std::string(key.str()), "unknown key, ignored");
    }
    ToolFields fields;
    const toml::node* number = t->get("number");
    // As --tool takes them: a number past the largest would wrap into another tool's.
    if (!number || !number->is_integer() || *number->value<std::int64_t>() < 0 ||
        *number->value<std::int64_t>() > kMaxToolNumber)
      return error(number ? number : &node, where + "number",
                   "must be a whole tool number from 0 to " + std::to_string(kMaxToolNumber) +
                       " (e.g. number = 1)");
    fields.number = int(*number->value<std::int64_t>());
    const std::string tool_name =
        "tool[" + std::to_string(index + 1) + "] (T" + std::to_string(fields.number) + ").";
    const toml::node* type = t->get("type");
    if (!type || !type->is_string() || !tool_shape_from_name(*type->value<std::string>()))
      return error(type ? type : &node, tool_name + "type",
                   "must be one of \"flat\", \"ball\", \"bullnose\", \"drill\", \"chamfer\"");
    fields.type = *type->value<std::string>();
    // Lengths from a micrometre to two metres, angles within (0, 180]: as --tool takes them.
    const std::optional<double> diameter = this->number(*t, "diameter_mm", tool_name, 0.001, 2000);
    if (!diameter) {
      if (!t->get("diameter_mm"))
        error(&node, tool_name + "diameter_mm", "must be given, in mm, from 0.001 to 2000");
      return;
    }
    fields.diameter_mm = *diameter;
    fields.corner_radius_mm = this->number(*t, "corner_radius_mm", tool_name, 0, 1000);
    fields.point_angle_deg = this->number(*t, "point_angle_deg", tool_name, 1, 180);
    fields.tip_diameter_mm = this->number(*t, "tip_diameter_mm", tool_name, 0, 2000);
    fields.flute_length_mm = this->number(*t, "flute_length_mm", tool_name, 0.001, 2000);
    fields.shank_diameter_mm = this->number(*t, "shank_diameter_mm", tool_name, 0.001, 2000);
    if (const toml::node* z = t->get("flutes")) {
      if (!z->is_integer() || z->value<std::int64_t>() < 1 || z->value<std::int64_t>() > 100)
        return error(z, tool_name + "flutes", "must be a whole number from 1 to 100");
      fields.flutes = int(*z->value<std::int64_t>());
    }
    if (const toml::node* d = t->get("description"); d && d->is_string())
      fields.description = *d->value<std::string>();
    else
      fields.description =
          std::string(tool_shape_name(*tool_shape_from_name(fields.type))) + " from " + path;
    std::string problem;
    const std::optional<Tool> made = make_tool(fields, &problem);
    if (!made) return error(&node, tool_name.substr(0, tool_name.size() - 1), problem);
    const Tool& tool = *made;
    if (job.tools.count(tool.number))
      return error(&node, tool_name.substr(0, tool_name.size() - 1),
                   "tool T" + std::to_string(tool.number) + " is defined twice");
    job.tools[tool.number] = tool;
  }
};

} // namespace

std::optional<JobFile> parse_job_file(std::string_view text, const std::string& path,
                                      std::vector<Diagnostic>& diagnostics) {
  toml::table document;
  try {
    document = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    diagnostics.push_back({Severity::Error, path, int(where.line), int(where.column),
                           "not valid TOML: " + std::string(e.description())});
    return std::nullopt;
  }
  JobReader reader{path, diagnostics};
  JobFile job;
  job.path = path;

  for (const auto& [key, value] : document)
    if (key.str() != "stock" && key.str() != "stock_stl" && key.str() != "tool" &&
        key.str() != "material" && key.str() != "units" && key.str() != "setup" &&
        key.str() != "work_offsets_mm" && key.str() != "cutter_compensation" &&
        key.str() != "machine")
      reader.say(Severity::Warning, &value, std::string(key.str()), "unknown key, ignored");

  // The unit of the stock's values written without one; none: the program's (G20/G21).
  LengthUnit units = LengthUnit::Program;
  if (const toml::node* u = document.get("units")) {
    const std::string name = u->is_string() ? to_lower(*u->value<std::string>()) : "";
    if (name == "mm")
      units = LengthUnit::Mm;
    else if (name == "in" || name == "inch")
      units = LengthUnit::Inch;
    else
      reader.error(u, "units", "must be \"mm\" or \"in\"");
  }

  if (const toml::node* setups = document.get("setup")) {
    const toml::array* list = setups->as_array();
    if (!list || !list->is_array_of_tables()) {
      reader.error(setups, "setup", "must be an array of tables ([[setup]] entries)");
    } else if (document.get("stock") || document.get("stock_stl")) {
      reader.error(setups, "setup",
                   "give the first setup's stock in its [[setup]] entry, not also as stock");
    } else {
      for (std::size_t k = 0; k < list->size(); ++k) {
        const toml::table& entry = *list->get(k)->as_table();
        const std::string where = "setup[" + std::to_string(k + 1) + "].";
        for (const auto& [key, value] : entry)
          if (key.str() != "stock" && key.str() != "stock_stl" && key.str() != "name")
            reader.say(Severity::Warning, &value, where + std::string(key.str()),
                       "unknown key, ignored");
        std::optional<StockSpec> stock = reader.read_stock(entry, where, units);
        if (k == 0)
          job.stock = std::move(stock);
        else
          job.setup_stocks.push_back(std::move(stock));
      }
    }
  } else {
    job.stock = reader.read_stock(document, "", units);
  }

  if (const toml::node* node = document.get("work_offsets_mm")) {
    const toml::table* table = node->as_table();
    if (!table) reader.error(node, "work_offsets_mm", "must be a table: G54 = [X, Y, Z], ...");
    static const toml::table kNone;
    for (const auto& [name, value] : table ? *table : kNone) {
      const std::string where = "work_offsets_mm." + std::string(name.str());
      const int index = work_offset_index(name.str());
      const toml::array* xyz = value.as_array();
      std::optional<double> v[3];
      for (std::size_t i = 0; xyz && xyz->size() == 3 && i < 3; ++i)
        if (auto n = xyz->get(i)->value<double>(); n && std::isfinite(*n) && std::abs(*n) <= 1e5)
          v[i] = n;
      if (index == 0)
        reader.error(&value, where, "names no work offset: G54 to G59, G59.1 to G59.3");
      else if (!v[0] || !v[1] || !v[2])
        reader.error(&value, where,
                     "must be [X, Y, Z], the origin's machine coordinates in mm (within 100 m)");
      else
        job.work_offsets[index] = Pose{*v[0], *v[1], *v[2], 0, 0, 0};
    }
  }

  if (const toml::node* mode = document.get("cutter_compensation")) {
    const std::string name = mode->is_string() ? to_lower(*mode->value<std::string>()) : "";
    if (name == "control")
      job.cutter_compensation = CutterCompMode::Control;
    else if (name == "wear")
      job.cutter_compensation = CutterCompMode::Wear;
    else
      reader.error(mode, "cutter_compensation",
                   "must be \"control\" (G41/G42 offset the part contour) or \"wear\" (the "
                   "path is the tool centre)");
  }
  if (const toml::node* machine = document.get("machine")) {
    const std::optional<std::string> name = machine->value<std::string>();
    if (!machine->is_string() || name->empty())
      reader.error(machine, "machine",
                   "must name a machine profile (a shipped one's name, or a .toml file)");
    else if (name->find_first_of("/\\") == std::string::npos &&
             !(name->size() > 5 && name->compare(name->size() - 5, 5, ".toml") == 0))
      job.machine = *name; // a shipped profile's name: no folder, no .toml
    else
      job.machine = reader.resolve(*name);
  }
  if (const toml::node* material = document.get("material")) {
    if (!material->is_string() || !find_material(*material->value<std::string>()))
      reader.error(material, "material",
                   "must name a material ncjoule knows (aluminium-alloy, mild-steel, ...: "
                   "docs/models.md)");
    else
      job.material = *material->value<std::string>();
  }
  if (const toml::node* tools = document.get("tool")) {
    if (const toml::array* list = tools->as_array()) {
      for (std::size_t k = 0; k < list->size(); ++k)
        reader.read_tool(*list->get(k), k, job);
    } else {
      reader.error(tools, "tool", "must be an array of tables ([[tool]] entries)");
    }
  }
  if (reader.failed) return std::nullopt;
  return job;
}

std::optional<JobFile> read_job_file(const std::string& path,
                                     std::vector<Diagnostic>& diagnostics) {
  const std::optional<std::string> text = read_text_file(path, "a job file", diagnostics);
  if (!text) return std::nullopt;
  return parse_job_file(*text, path, diagnostics);
}

} // namespace ncjoule
