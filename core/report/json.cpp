// The results of an estimate as one JSON document (docs/json.md names every field), written as
// it is made.
#include <array>
#include <sstream>
#include <string>

#include "json_writer.hpp"
#include "ncjoule/report.hpp"
#include "stock_source_name.hpp"

namespace ncjoule {
namespace {

using report_detail::JsonWriter;
using report_detail::stock_source_name;

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

const char* origin_name(DialectOrigin origin) {
  switch (origin) {
  case DialectOrigin::Given:
    return "given";
  case DialectOrigin::Detected:
    return "detected";
  case DialectOrigin::Default:
    break;
  }
  return "default";
}

template <class Values> void write_components(JsonWriter& w, const Values& values) {
  w.key("components");
  w.begin_object();
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    w.field(component_name(PowerComponent(i)), values[i]);
  w.end_object();
}

void write_time_split(JsonWriter& w, const TimeSplit& t, bool removal_known) {
  w.key("time_split");
  w.begin_object();
  w.field("rapid_s", t.rapid_s);
  w.field("feed_s", t.feed_s);
  w.field("cutting_s", t.cutting_s());
  if (removal_known)
    w.field("air_cut_s", t.air_cut_s);
  else
    w.key("air_cut_s").null(); // not known without removal
  w.field("tool_change_s", t.tool_change_s);
  w.field("dwell_s", t.dwell_s);
  w.field("spindle_s", t.spindle_s);
  w.field("other_s", t.other_s);
  w.field("tool_changes", t.tool_changes);
  w.end_object();
}

// The keys of a block's components as written after its other fields: the first opens the
// object ("components":{"tare":), each with its comma.
const std::array<std::string, kPowerComponentCount>& block_component_keys() {
  static const auto keys = [] {
    std::array<std::string, kPowerComponentCount> k;
    for (std::size_t i = 0; i < kPowerComponentCount; ++i)
      k[i] = std::string(i == 0 ? ",\"components\":{\"" : ",\"") +
             std::string(component_name(PowerComponent(i))) + "\":";
    return k;
  }();
  return keys;
}

// One block, on a line. Its numbers go through raw_field(), the keys written as they are: the
// same bytes as field() (tests/report compares the two), a fifth of the JSON's work less.
void write_block(JsonWriter& w, const LineSummary& b, const Estimate& e) {
  w.begin_object_on_one_line();
  w.field("line", b.line + 1);
  w.field("kind", line_kind_name(b.kind));
  if (b.operation > 0 && b.operation <= e.operations.size())
    w.field("operation", e.operations[b.operation - 1].name);
  w.raw_field(",\"time_s\":", b.time_s);
  w.raw_field(",\"start_s\":", b.start_s);
  w.raw_field(",\"length_mm\":", b.length_mm);
  w.raw_field(",\"entry_speed_mm_s\":", b.entry_speed_mm_s);
  w.raw_field(",\"exit_speed_mm_s\":", b.exit_speed_mm_s);
  w.raw_field(",\"peak_speed_mm_s\":", b.peak_speed_mm_s);
  w.raw_field(",\"commands\":", b.commands);
  w.raw_field(",\"removed_mm3\":", b.removed_mm3);
  w.raw_field(",\"mrr_mm3_s\":", b.time_s > 0 ? b.removed_mm3 / b.time_s : 0.0);
  w.raw_field(",\"mrr_peak_mm3_s\":", b.mrr_peak_mm3_s);
  w.raw_field(",\"power_w\":", b.time_s > 0 ? b.energy_j / b.time_s : 0.0);
  w.raw_field(",\"power_peak_w\":", b.power_peak_w);
  w.raw_field(",\"energy_j\":", b.energy_j);
  if (b.spindle_load > 0) w.raw_field(",\"spindle_load\":", b.spindle_load);
  const auto& component_keys = block_component_keys();
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    w.raw_field(component_keys[i], b.components_j[i]);
  w.raw_text("}");
  if (b.note > 0 && b.note <= e.notes.size()) {
    w.key("notes");
    w.begin_array();
    w.value(e.notes[b.note - 1]);
    w.end_array();
  }
  w.end_object();
}

// The compact document's block columns: write_block's fields in its order, the components
// flattened, and for what write_block leaves out (no operation, no spindle load, no note) null.
constexpr const char* kBlockColumns[] = {"line",
                                         "kind",
                                         "operation",
                                         "time_s",
                                         "start_s",
                                         "length_mm",
                                         "entry_speed_mm_s",
                                         "exit_speed_mm_s",
                                         "peak_speed_mm_s",
                                         "commands",
                                         "removed_mm3",
                                         "mrr_mm3_s",
                                         "mrr_peak_mm3_s",
                                         "power_w",
                                         "power_peak_w",
                                         "energy_j",
                                         "spindle_load"};

void write_block_row(JsonWriter& w, const LineSummary& b, const Estimate& e) {
  w.begin_array();
  w.value(b.line + 1);
  w.value(line_kind_name(b.kind));
  if (b.operation > 0 && b.operation <= e.operations.size())
    w.value(int(b.operation) - 1); // index into "operations"
  else
    w.null();
  w.value(b.time_s);
  w.value(b.start_s);
  w.value(b.length_mm);
  w.value(b.entry_speed_mm_s);
  w.value(b.exit_speed_mm_s);
  w.value(b.peak_speed_mm_s);
  w.value(b.commands);
  w.value(b.removed_mm3);
  w.value(b.time_s > 0 ? b.removed_mm3 / b.time_s : 0.0);
  w.value(b.mrr_peak_mm3_s);
  w.value(b.time_s > 0 ? b.energy_j / b.time_s : 0.0);
  w.value(b.power_peak_w);
  w.value(b.energy_j);
  if (b.spindle_load > 0)
    w.value(b.spindle_load);
  else
    w.null();
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    w.value(b.components_j[i]);
  if (b.note > 0 && b.note <= e.notes.size())
    w.value(e.notes[b.note - 1]);
  else
    w.null();
  w.end_array();
}

void write_block_rows(JsonWriter& w, const Estimate& e) {
  w.begin_object();
  w.key("columns");
  w.begin_array();
  for (const char* name : kBlockColumns)
    w.value(name);
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    w.value("components." + std::string(component_name(PowerComponent(i))));
  w.value("notes");
  w.end_array();
  w.key("rows");
  w.begin_array_of_lines();
  w.elements(e.lines.size(),
             [&](JsonWriter& piece, std::size_t i) { write_block_row(piece, e.lines[i], e); });
  w.end_array();
  w.end_object();
}

void write_operation(JsonWriter& w, const OperationSummary& op, bool removal_known) {
  w.begin_object();
  w.field("name", op.name);
  w.field("tool", op.tool);
  w.field("line", op.line + 1); // 0 for what runs before the first operation
  w.field("start_s", op.start_s);
  w.field("time_s", op.time_s);
  w.field("removed_mm3", op.removed_mm3);
  w.field("energy_j", op.energy_j);
  w.field("sec_j_mm3", op.removed_mm3 > 0 ? op.energy_j / op.removed_mm3 : 0.0);
  w.field("co2_kg", op.co2_kg);
  w.field("cost", op.cost);
  write_components(w, op.components_j);
  write_time_split(w, op.time, removal_known);
  w.end_object();
}

// The figures a guessed stock sets, each as [low, high]: from no cut in the guessed setups to
// the guess; null when every stock is known.
void write_stock_guess(JsonWriter& w, const Estimate& e) {
  w.key("stock_guess");
  const GuessedFigures g = guessed_figures(e);
  if (!g.guessed) {
    w.null();
    return;
  }
  w.begin_object();
  const std::pair<const char*, GuessedFigures::Range> ranges[] = {{"removed_mm3", g.removed_mm3},
                                                                  {"energy_j", g.energy_j},
                                                                  {"peak_power_w", g.peak_power_w},
                                                                  {"co2_kg", g.co2_kg},
                                                                  {"cost", g.cost}};
  for (const auto& [name, range] : ranges) {
    w.key(name);
    w.begin_array();
    w.value(range.low);
    w.value(range.high);
    w.end_array();
  }
  w.field("peak_power_with_overloads_w", g.peak_with_overloads_w);
  const StockGuessRange& r = e.stock_guess;
  w.key("overloads");
  w.begin_object();
  w.field("blocks", r.overload_blocks);
  w.field("first_line", r.first_overload_line + 1);
  w.field("worst_line", r.worst_overload_line + 1);
  w.field("worst_load", r.worst_load);
  w.end_object();
  w.end_object();
}

} // namespace

namespace {

// The document; `compact`: on one line but for a line per block, the blocks as rows of values
// under one list of column names (docs/json.md).
void write_document(std::ostream& out, const Estimate& e, const MachineProfile& machine, int indent,
                    bool compact) {
  if (compact) indent = 0;
  const RemovalResult* removal = e.removal ? &*e.removal : nullptr;
  const EnergyResult& energy = e.energy;
  JsonWriter w(out, indent);
  w.begin_object();
  w.field("file", e.file);
  w.key("machine");
  w.begin_object();
  w.field("name", machine.name);
  w.field("file", machine.source_path);
  w.field("power_model", energy.model_description);
  w.field("cutting_term", e.power.cutting_source);
  if (!e.power.material.empty()) w.field("material", e.power.material);
  w.end_object();
  w.field("dialect", e.dialect.name);
  w.field("dialect_origin", origin_name(e.dialect_origin));
  w.field("dialect_reason", e.dialect_reason);
  w.field("time_s", e.time_s);
  write_time_split(w, e.time, removal != nullptr);
  w.field("removed_mm3", energy.removed_mm3);
  w.field("stock", removal ? removal->stock_description : std::string("not simulated"));
  // Where the (first setup's) stock came from: docs/stock.md lists the kinds.
  w.field("stock_from", e.setups.empty() || e.setups.front().stock_from.empty()
                            ? std::string("none")
                            : e.setups.front().stock_from);
  if (removal) {
    w.key("removal");
    w.begin_object();
    w.field("engine", engine_name(removal->engine));
    w.field("grid_mm", removal->grid.dx);
    w.field("columns", removal->grid.columns());
    w.field("stock_volume_mm3", removal->stock_volume_mm3);
    w.field("memory_bytes", removal->memory_bytes);
    w.field("z_mirrored", removal->z_mirrored);
    w.end_object();
  }
  // The setups (one per clamping of the part), each with its stock and where that came from.
  w.key("setups");
  w.begin_array();
  for (const SetupSummary& setup : e.setups) {
    w.begin_object();
    w.field("first_line", setup.first_line + 1);
    w.field("reason", setup.reason);
    w.field("time_s", setup.time_s);
    w.field("energy_j", setup.energy_j);
    w.field("removed_mm3", setup.removed_mm3);
    w.field("stock", setup.stock.empty() ? std::string("not simulated") : setup.stock);
    w.field("stock_source", stock_source_name(setup.stock_source));
    w.field("stock_from", setup.stock_from.empty() ? std::string("none") : setup.stock_from);
    if (!setup.stock_origin.empty()) w.field("stock_origin", setup.stock_origin);
    if (setup.stock_box) {
      const Box3& b = *setup.stock_box;
      w.key("stock_box_mm");
      w.begin_array();
      for (double v : {b.xmin, b.ymin, b.zmin, b.xmax, b.ymax, b.zmax})
        w.value(v);
      w.end_array();
    }
    w.end_object();
  }
  w.end_array();
  w.key("tools");
  w.begin_array();
  for (const auto& [number, tool] : e.tools) {
    w.begin_object();
    w.field("number", number);
    w.field("shape", tool_shape_name(tool.shape));
    w.field("diameter_mm", tool.diameter_mm);
    w.field("corner_radius_mm", tool.corner_radius_mm);
    w.field("tip_angle_deg", tool.tip_angle_deg);
    w.field("description", tool.description);
    w.end_object();
  }
  w.end_array();
  w.key("unsimulated_tools");
  w.begin_array();
  for (int t : e.unsimulated_tools)
    w.value(t);
  w.end_array();
  w.field("energy_j", energy.energy_j);
  w.field("sec_j_mm3", energy.sec_j_mm3);
  w.field("mean_power_w", energy.mean_power_w);
  w.field("peak_power_w", energy.peak_power_w);
  w.field("co2_kg", energy.co2_kg);
  w.field("cost", energy.cost);
  w.field("electricity_cost", energy.electricity_cost);
  w.field("machine_cost", energy.machine_cost);
  w.field("machine_rate_per_hour", energy.machine_rate_per_hour);
  w.field("currency", energy.currency);
  write_components(w, energy.components_j);
  write_stock_guess(w, e);
  w.key("operations");
  w.begin_array();
  for (const OperationSummary& op : e.operations)
    write_operation(w, op, removal != nullptr);
  w.end_array();
  w.key("blocks");
  if (compact) {
    write_block_rows(w, e);
  } else {
    w.begin_array();
    w.elements(e.lines.size(),
               [&](JsonWriter& piece, std::size_t i) { write_block(piece, e.lines[i], e); });
    w.end_array();
  }
  w.key("warnings");
  w.begin_array();
  for (const Diagnostic& d : e.diagnostics) {
    w.begin_object();
    w.field("file", d.file);
    w.field("line", d.line);
    w.field("column", d.column);
    w.field("severity", severity_name(d.severity));
    w.field("message", d.message);
    w.end_object();
  }
  w.end_array();
  w.field("warnings_dropped", e.diagnostics_dropped);
  w.end_object();
  w.end_document(indent > 0 || compact);
}

} // namespace

void write_estimate_json(std::ostream& out, const Estimate& e, const MachineProfile& machine,
                         int indent) {
  write_document(out, e, machine, indent, false);
}

void write_estimate_json_compact(std::ostream& out, const Estimate& e,
                                 const MachineProfile& machine) {
  write_document(out, e, machine, 0, true);
}

std::string estimate_json(const Estimate& e, const MachineProfile& machine, int indent) {
  std::ostringstream out;
  write_estimate_json(out, e, machine, indent);
  return out.str();
}

} // namespace ncjoule
