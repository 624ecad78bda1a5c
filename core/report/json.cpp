// The results of an estimate as one JSON document (docs/json.md names every field).
#include <nlohmann/json.hpp>

#include "ncjoule/report.hpp"

namespace ncjoule {
namespace {

using Json = nlohmann::ordered_json;

const char* severity_name(Severity s) {
  switch (s) {
  case Severity::Note:
    return "note";
  case Severity::Warning:
    return "warning";
  case Severity::Error:
    return "error";
  }
  return "error";
}

Json components_json(const ComponentValues& values) {
  Json j = Json::object();
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    j[std::string(component_name(PowerComponent(i)))] = values[i];
  return j;
}

Json block_json(const LineSummary& b) {
  Json j;
  j["line"] = b.line + 1;
  j["kind"] = b.kind;
  j["time_s"] = b.time_s;
  j["start_s"] = b.start_s;
  j["length_mm"] = b.length_mm;
  j["entry_speed_mm_s"] = b.entry_speed_mm_s;
  j["exit_speed_mm_s"] = b.exit_speed_mm_s;
  j["peak_speed_mm_s"] = b.peak_speed_mm_s;
  j["commands"] = b.commands;
  j["removed_mm3"] = b.removed_mm3;
  j["mrr_mm3_s"] = b.time_s > 0 ? b.removed_mm3 / b.time_s : 0.0;
  j["mrr_peak_mm3_s"] = b.mrr_peak_mm3_s;
  j["power_w"] = b.time_s > 0 ? b.energy_j / b.time_s : 0.0;
  j["power_peak_w"] = b.power_peak_w;
  j["energy_j"] = b.energy_j;
  j["components"] = components_json(b.components_j);
  if (!b.notes.empty()) j["notes"] = b.notes;
  return j;
}

Json operation_json(const OperationSummary& op) {
  Json j;
  j["name"] = op.name;
  j["tool"] = op.tool;
  j["line"] = op.line + 1; // 0 for what runs before the first tool change
  j["start_s"] = op.start_s;
  j["time_s"] = op.time_s;
  j["removed_mm3"] = op.removed_mm3;
  j["energy_j"] = op.energy_j;
  j["sec_j_mm3"] = op.removed_mm3 > 0 ? op.energy_j / op.removed_mm3 : 0.0;
  j["co2_kg"] = op.co2_kg;
  j["cost"] = op.cost;
  j["components"] = components_json(op.components_j);
  return j;
}

Json diagnostic_json(const Diagnostic& d) {
  return Json{{"file", d.file},
              {"line", d.line},
              {"column", d.column},
              {"severity", severity_name(d.severity)},
              {"message", d.message}};
}

Json estimate_document(const Estimate& e, const MachineProfile& machine) {
  const RemovalResult* removal = e.removal ? &*e.removal : nullptr;
  const EnergyResult& energy = e.energy;
  const Timeline& timeline = e.timeline;
  const std::vector<LineSummary>& blocks = e.lines;
  const std::vector<Diagnostic>& diagnostics = e.diagnostics;
  Json j;
  j["file"] = e.file;
  j["machine"] = Json{{"name", machine.name},
                      {"file", machine.source_path},
                      {"power_model", energy.model_description}};
  j["dialect"] = e.dialect.name;
  j["dialect_origin"] = e.toolpath.result.dialect_origin == DialectOrigin::Given      ? "given"
                        : e.toolpath.result.dialect_origin == DialectOrigin::Detected ? "detected"
                                                                                      : "default";
  j["dialect_reason"] = e.toolpath.result.dialect_reason;
  Json tools = Json::array();
  for (const auto& [number, tool] : e.tools)
    tools.push_back(Json{{"number", number},
                         {"shape", std::string(tool_shape_name(tool.shape))},
                         {"diameter_mm", tool.diameter_mm},
                         {"corner_radius_mm", tool.corner_radius_mm},
                         {"tip_angle_deg", tool.tip_angle_deg},
                         {"description", tool.description}});
  j["tools"] = std::move(tools);
  j["unsimulated_tools"] = e.unsimulated_tools;
  j["time_s"] = timeline.total_s;
  j["removed_mm3"] = energy.removed_mm3;
  j["stock"] = removal ? removal->stock_description : std::string("not simulated");
  if (removal) {
    j["removal"] = Json{{"engine", std::string(engine_name(removal->engine))},
                        {"grid_mm", removal->grid.dx},
                        {"columns", removal->grid.columns()},
                        {"stock_volume_mm3", removal->stock_volume_mm3},
                        {"memory_bytes", removal->memory_bytes}};
  }
  j["energy_j"] = energy.energy_j;
  j["sec_j_mm3"] = energy.sec_j_mm3;
  j["co2_kg"] = energy.co2_kg;
  j["cost"] = energy.cost;
  j["currency"] = energy.currency;
  j["components"] = components_json(energy.components_j);
  Json list = Json::array();
  for (const LineSummary& b : blocks)
    list.push_back(block_json(b));
  j["blocks"] = std::move(list);
  Json warnings = Json::array();
  for (const Diagnostic& d : diagnostics)
    warnings.push_back(diagnostic_json(d));
  j["warnings"] = std::move(warnings);
  return j;
}

} // namespace

std::string estimate_json(const Estimate& e, const MachineProfile& machine, int indent) {
  return estimate_document(e, machine).dump(indent);
}

std::string estimate_json(const Estimate& e, const SourceFile& source,
                          const MachineProfile& machine, int indent) {
  Json j = estimate_document(e, machine);
  Json list = Json::array();
  for (const OperationSummary& op : operations(source, e))
    list.push_back(operation_json(op));
  // After the totals, before the long list of blocks.
  Json ordered;
  for (auto& [key, value] : j.items()) {
    if (key == "blocks") ordered["operations"] = list;
    ordered[key] = value;
  }
  return ordered.dump(indent);
}

} // namespace ncjoule
