// A CAMotics project (projects.hpp). The format, as CAMotics writes it (src/camotics/project/):
//   {"units": "metric" | "imperial",            (how CAMotics shows lengths; not of the bounds)
//    "tools": {"1": {"units": "imperial", "shape": "ballnose", "length": 1, "diameter": 0.125,
//                    "snub_diameter": ..., "description": ""}, ...},
//    "workpiece": {"automatic": false, "margin": 5,
//                  "bounds": {"min": [x, y, z], "max": [x, y, z]}},   (mm)
//    "files": ["bear.nc", ...]}                   (relative to the project's folder)
// A tool's sizes are in its own "units". CAMotics sweeps a conical tool as a cone over its whole
// length (its tip angle follows from the diameter and the length), a snubnose one as a cone cut
// at its snub diameter, a spheroid as an ellipsoid of the diameter and the length.
#include <array>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "ncjoule/projects.hpp"
#include "ncjoule/text.hpp"

namespace ncjoule {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Line and column (1-based) of byte `offset` of `text`.
std::pair<int, int> line_column(std::string_view text, std::size_t offset) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n')
      ++line, column = 1;
    else
      ++column;
  }
  return {line, column};
}

// Whether `entry` of the project's "files" (relative to `folder`) is the file `program`.
bool names_program(const fs::path& folder, const std::string& entry, const std::string& program) {
  std::error_code ec1, ec2;
  const fs::path a = fs::weakly_canonical(folder / fs::path(entry), ec1);
  const fs::path b = fs::weakly_canonical(fs::path(program), ec2);
  if (!ec1 && !ec2) return a == b;
  return fs::path(entry).filename() == fs::path(program).filename();
}

std::optional<double> length(const json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_number()) return std::nullopt;
  const double v = it->get<double>();
  return std::isfinite(v) ? std::optional(v) : std::nullopt;
}

constexpr double kPi = 3.14159265358979323846;

std::optional<ProjectFile> read_project(const json& j, const std::string& path,
                                        const std::string& name, const std::string& program,
                                        std::vector<Diagnostic>& diagnostics);

// One tool of the project, or std::nullopt with `why`.
std::optional<Tool> tool_of(int number, const json& t, std::string& why) {
  if (!t.is_object()) return why = "is not an object", std::nullopt;
  const std::string units = t.value("units", std::string("metric"));
  double scale = 1;
  if (units == "imperial")
    scale = 25.4;
  else if (units != "metric")
    return why = "has units '" + units + "' (metric or imperial)", std::nullopt;
  const std::string shape = to_lower(t.value("shape", std::string("cylindrical")));
  const auto d = length(t, "diameter"), l = length(t, "length");
  if (!d || !(*d > 0)) return why = "has no diameter above 0", std::nullopt;
  Tool tool;
  tool.number = number;
  tool.diameter_mm = *d * scale;
  tool.description = t.value("description", std::string());
  if (shape == "cylindrical" || shape == "cylinder") {
    tool.shape = ToolShape::FlatEndMill;
  } else if (shape == "ballnose") {
    tool.shape = ToolShape::BallEndMill;
    tool.corner_radius_mm = tool.radius();
  } else if (shape == "conical" || shape == "cone" || shape == "snubnose") {
    if (!l || !(*l > 0)) return why = "is a cone without a length above 0", std::nullopt;
    const double snub = shape == "snubnose" ? length(t, "snub_diameter").value_or(0) * scale : 0;
    if (!(snub >= 0 && snub < tool.diameter_mm))
      return why = "has a snub diameter not below its diameter", std::nullopt;
    tool.shape = ToolShape::Chamfer;
    tool.tip_diameter_mm = snub;
    tool.tip_angle_deg = 2 * std::atan((tool.diameter_mm - snub) / 2 / (*l * scale)) * 180 / kPi;
  } else if (shape == "spheroid" || shape == "sphere") {
    // An ellipsoid as tall as its length: a ball end mill when that is its diameter.
    if (!l || std::abs(*l - *d) > 1e-9 * std::max(1.0, *d))
      return why = "is a spheroid whose length is not its diameter (an ellipsoid ncjoule does "
                   "not model)",
             std::nullopt;
    tool.shape = ToolShape::BallEndMill;
    tool.corner_radius_mm = tool.radius();
  } else {
    return why = "has shape '" + shape + "'", std::nullopt;
  }
  if (const std::string problem = tool_problem(tool); !problem.empty())
    return why = problem, std::nullopt;
  return tool;
}

} // namespace

std::optional<ProjectFile> parse_camotics_project(std::string_view text, const std::string& path,
                                                  const std::string& program,
                                                  std::vector<Diagnostic>& diagnostics) {
  const std::string name = fs::path(path).filename().string();
  auto warn = [&](std::string message, int line = 0, int column = 0) {
    diagnostics.push_back({Severity::Warning, path, line, column,
                           "CAMotics project not read: " + std::move(message)});
  };
  json j;
  try {
    j = json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    const auto [line, column] = line_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    if (const std::size_t at = what.find("syntax error"); at != std::string::npos)
      what = what.substr(at);
    warn("it is not JSON (" + what + ")", line, column);
    return std::nullopt;
  }
  if (!j.is_object()) {
    warn("it is not a JSON object");
    return std::nullopt;
  }
  try {
    return read_project(j, path, name, program, diagnostics);
  } catch (const json::exception& e) {
    // A value of another type than CAMotics writes ("automatic": "no", "units": 3).
    warn(std::string("a value is not of the type CAMotics writes (") + e.what() + ")");
    return std::nullopt;
  }
}

namespace {

std::optional<ProjectFile> read_project(const json& j, const std::string& path,
                                        const std::string& name, const std::string& program,
                                        std::vector<Diagnostic>& diagnostics) {
  // A part of the project left out; the rest is used.
  auto warn = [&](const std::string& message) {
    diagnostics.push_back(
        {Severity::Warning, path, 0, 0, "CAMotics project " + name + ": " + message});
  };
  // It is this program's project only when its "files" name the program.
  const auto files = j.find("files");
  if (files == j.end() || !files->is_array()) return std::nullopt;
  const fs::path folder = fs::path(path).parent_path();
  bool named = false;
  for (const json& f : *files)
    if (f.is_string() && names_program(folder, f.get<std::string>(), program)) named = true;
  if (!named) return std::nullopt;

  ProjectFile project;
  project.path = path;
  if (const auto tools = j.find("tools"); tools != j.end() && tools->is_object()) {
    for (const auto& [key, t] : tools->items()) {
      const auto number = parse_number(key);
      if (!number || *number < 0 || *number > 1e6 || std::floor(*number) != *number) {
        warn("tool '" + key + "' is not numbered; it is left out");
        continue;
      }
      std::string why;
      if (auto tool = tool_of(int(*number), t, why))
        project.tools[int(*number)] = *tool;
      else
        warn("tool " + key + " " + why + "; it is left out");
    }
  }
  const auto workpiece = j.find("workpiece");
  if (workpiece == j.end() || !workpiece->is_object()) return project;
  if (workpiece->value("automatic", true)) {
    diagnostics.push_back({Severity::Note, path, 0, 0,
                           "CAMotics project " + name +
                               ": its workpiece is automatic (CAMotics' own guess from the cuts), "
                               "not a stock its author set; it is not taken"});
    return project;
  }
  const auto bounds = workpiece->find("bounds");
  auto corner = [&](const char* key) -> std::optional<std::array<double, 3>> {
    if (bounds == workpiece->end() || !bounds->is_object()) return std::nullopt;
    const auto c = bounds->find(key);
    if (c == bounds->end() || !c->is_array() || c->size() != 3) return std::nullopt;
    std::array<double, 3> out{};
    for (std::size_t k = 0; k < 3; ++k) {
      if (!(*c)[k].is_number()) return std::nullopt;
      out[k] = (*c)[k].get<double>();
      if (!std::isfinite(out[k])) return std::nullopt;
    }
    return out;
  };
  const auto low = corner("min"), high = corner("max");
  if (!low || !high) {
    warn("its workpiece's bounds are not min and max of three numbers each; the next source of "
         "the stock is used");
    return project;
  }
  const Box3 box{(*low)[0], (*low)[1], (*low)[2], (*high)[0], (*high)[1], (*high)[2]};
  if (box.empty()) {
    warn("its workpiece's bounds have no volume (a max not above its min); the next source of "
         "the stock is used");
    return project;
  }
  StockSpec spec;
  spec.kind = StockSpec::Kind::Box;
  spec.box = box;
  spec.box_units.fill(LengthUnit::Mm); // CAMotics keeps the bounds in mm
  spec.from = "camotics";
  spec.origin = "CAMotics project " + name;
  project.stock = spec;
  return project;
}

} // namespace
} // namespace ncjoule
