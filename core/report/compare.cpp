// Ranking alternatives of the same part by energy, with their differences to the best, so a
// planner sees which costs less and, component by component, why.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "ncjoule/report.hpp"

namespace ncjoule {
namespace {

using Json = nlohmann::ordered_json;

double percent_of(double diff, double base) {
  return base != 0 ? 100 * diff / base : 0.0;
}

Json components_json(const ComponentValues& values) {
  Json j = Json::object();
  for (std::size_t i = 0; i < kPowerComponentCount; ++i)
    j[std::string(component_name(PowerComponent(i)))] = values[i];
  return j;
}

} // namespace

ProgramTotals program_totals(const Estimate& e) {
  ProgramTotals t;
  t.file = e.file;
  t.time_s = e.time_s;
  t.energy_j = e.energy.energy_j;
  t.removed_mm3 = e.energy.removed_mm3;
  t.sec_j_mm3 = e.energy.sec_j_mm3;
  t.co2_kg = e.energy.co2_kg;
  t.cost = e.energy.cost;
  t.machine_cost = e.energy.machine_cost;
  t.inch = e.inch;
  for (const OperationSummary& op : e.operations)
    t.operations.push_back({op.name, op.time_s, op.energy_j, op.cost, op.time});
  t.currency = e.energy.currency;
  t.components_j = e.energy.components_j;
  t.air_cut_s = e.time.air_cut_s;
  t.setups = std::max<std::size_t>(e.setups.size(), 1);
  // No stock, or the box of a program's own cuts: each alternative cuts a stock of its own.
  t.stock_guessed =
      e.removal.has_value() &&
      std::any_of(e.setups.begin(), e.setups.end(), [](const SetupSummary& s) {
        return s.stock_source == StockSource::Guessed || s.stock_source == StockSource::None;
      });
  t.volumes_known = e.removal.has_value() && e.unsimulated_tools.empty();
  t.guess = guessed_figures(e);
  t.peak_power_w = e.energy.peak_power_w;
  t.time = e.time;
  t.removal = e.removal.has_value();
  return t;
}

std::vector<std::string> comparison_warnings(const std::vector<RankedProgram>& ranked) {
  std::vector<std::string> out;
  std::string unknown;
  double low = INFINITY, high = 0;
  for (const RankedProgram& r : ranked) {
    if (!r.totals.volumes_known) {
      unknown +=
          (unknown.empty() ? "" : ", ") + std::filesystem::path(r.totals.file).filename().string();
      continue;
    }
    low = std::min(low, r.totals.removed_mm3);
    high = std::max(high, r.totals.removed_mm3);
  }
  if (!unknown.empty())
    out.push_back("the volume " + unknown +
                  " removes is not known (material removal off, or a tool nothing describes): "
                  "the ranking leaves its cutting energy out");
  // Stocks guessed from each program's own cuts differ with the toolpaths: the same part from
  // the same stock needs the stock given.
  std::string guessed;
  for (const RankedProgram& r : ranked)
    if (r.totals.stock_guessed)
      guessed +=
          (guessed.empty() ? "" : ", ") + std::filesystem::path(r.totals.file).filename().string();
  if (!guessed.empty() && ranked.size() > 1)
    out.push_back("the stock of " + guessed +
                  " is guessed from its own cutting moves: give the job's stock (--stock or a job "
                  "file) so that every alternative cuts the same one");
  // Each guessed program's figures marked '*' in the table: the range they can span.
  for (const RankedProgram& r : ranked) {
    const GuessedFigures& g = r.totals.guess;
    if (!g.guessed) continue;
    const double unit = r.totals.inch ? kMm3PerIn3 : 1.0;
    char text[400];
    std::snprintf(text, sizeof text,
                  "%s*: on a guessed stock its energy can be %.2f to %.2f kJ, its volume %.*f to "
                  "%.*f %s and its peak %.0f to %.0f W (from no cut to the guess)",
                  std::filesystem::path(r.totals.file).filename().string().c_str(),
                  g.energy_j.low / 1000, g.energy_j.high / 1000, r.totals.inch ? 3 : 0,
                  g.removed_mm3.low / unit, r.totals.inch ? 3 : 0, g.removed_mm3.high / unit,
                  r.totals.inch ? "in^3" : "mm^3", g.peak_power_w.low, g.peak_power_w.high);
    out.push_back(text);
  }
  std::string setup_counts;
  for (const RankedProgram& r : ranked)
    if (r.totals.setups != ranked.front().totals.setups) setup_counts = "differ";
  if (!setup_counts.empty()) {
    std::string list;
    for (const RankedProgram& r : ranked)
      list += (list.empty() ? "" : ", ") +
              std::filesystem::path(r.totals.file).filename().string() + " " +
              std::to_string(r.totals.setups);
    out.push_back("the alternatives machine the part in different numbers of setups (" + list +
                  "): the extra clampings' handling time is not in the estimate");
  }
  // 1% (and 1 mm^3) apart: grids and tool approximations differ by less on the same part.
  if (high > 0 && high - low > std::max(1.0, 0.01 * high)) {
    std::string list;
    for (const RankedProgram& r : ranked) {
      if (!r.totals.volumes_known) continue;
      char text[64];
      std::snprintf(text, sizeof text, " %.0f mm^3", r.totals.removed_mm3);
      list += (list.empty() ? "" : ", ") +
              std::filesystem::path(r.totals.file).filename().string() + text;
    }
    out.push_back("the alternatives remove different volumes (" + list +
                  "): they do not make the same part from the same stock, so their energies "
                  "are not alternatives of one job");
  }
  return out;
}

std::optional<RankBy> parse_rank_by(std::string_view text) {
  if (text == "energy") return RankBy::Energy;
  if (text == "time") return RankBy::Time;
  if (text == "cost") return RankBy::Cost;
  return std::nullopt;
}

std::string_view rank_by_name(RankBy by) {
  switch (by) {
  case RankBy::Time:
    return "time";
  case RankBy::Cost:
    return "cost";
  case RankBy::Energy:
    break;
  }
  return "energy";
}

std::vector<RankedProgram> rank_programs(std::vector<ProgramTotals> programs, RankBy by) {
  std::stable_sort(programs.begin(), programs.end(),
                   [by](const ProgramTotals& a, const ProgramTotals& b) {
                     if (by == RankBy::Cost && a.cost != b.cost) return a.cost < b.cost;
                     if (by == RankBy::Time && a.time_s != b.time_s) return a.time_s < b.time_s;
                     if (a.energy_j != b.energy_j) return a.energy_j < b.energy_j;
                     if (a.time_s != b.time_s) return a.time_s < b.time_s;
                     return a.file < b.file;
                   });
  std::vector<RankedProgram> ranked;
  for (std::size_t i = 0; i < programs.size(); ++i) {
    RankedProgram r;
    r.rank = static_cast<int>(i) + 1;
    r.totals = programs[i];
    const ProgramTotals& best = programs.front();
    r.time_diff_s = r.totals.time_s - best.time_s;
    r.time_diff_pct = percent_of(r.time_diff_s, best.time_s);
    r.energy_diff_j = r.totals.energy_j - best.energy_j;
    r.energy_diff_pct = percent_of(r.energy_diff_j, best.energy_j);
    r.cost_diff = r.totals.cost - best.cost;
    r.co2_diff_kg = r.totals.co2_kg - best.co2_kg;
    for (std::size_t c = 0; c < kPowerComponentCount; ++c)
      r.component_diff_j[c] = r.totals.components_j[c] - best.components_j[c];
    ranked.push_back(std::move(r));
  }
  return ranked;
}

std::string explain_difference(const RankedProgram& r, std::size_t max_components) {
  if (r.rank == 1) return {};
  std::vector<std::size_t> order;
  for (std::size_t c = 0; c < kPowerComponentCount; ++c)
    if (std::abs(r.component_diff_j[c]) > 0.05) order.push_back(c); // under 0.05 J is noise
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::abs(r.component_diff_j[a]) > std::abs(r.component_diff_j[b]);
  });
  if (order.size() > max_components) order.resize(max_components);
  std::string text;
  for (std::size_t c : order) {
    char value[64];
    std::snprintf(value, sizeof value, "%+.1f kJ", r.component_diff_j[c] / 1000);
    text +=
        (text.empty() ? "" : ", ") + std::string(component_name(PowerComponent(c))) + " " + value;
  }
  return text;
}

std::string explain_time_difference(const TimeSplit& here, const TimeSplit& best, bool removal,
                                    std::size_t max_parts) {
  // Words a programmer reads a cycle time in.
  std::vector<std::pair<const char*, double>> parts;
  if (removal) {
    parts.emplace_back("cutting", here.cutting_s() - best.cutting_s());
    parts.emplace_back("air cutting", here.air_cut_s - best.air_cut_s);
  } else {
    parts.emplace_back("feed moves", here.feed_s - best.feed_s);
  }
  parts.emplace_back("rapids", here.rapid_s - best.rapid_s);
  parts.emplace_back("tool changes", here.tool_change_s - best.tool_change_s);
  parts.emplace_back("dwells", here.dwell_s - best.dwell_s);
  parts.emplace_back("spindle speed changes", here.spindle_s - best.spindle_s);
  parts.emplace_back("other", here.other_s - best.other_s);
  std::erase_if(parts, [](const auto& p) { return std::abs(p.second) < 0.05; });
  std::stable_sort(parts.begin(), parts.end(), [](const auto& a, const auto& b) {
    return std::abs(a.second) > std::abs(b.second);
  });
  if (parts.size() > max_parts) parts.resize(max_parts);
  std::string text;
  for (const auto& [what, diff] : parts) {
    char value[64];
    std::snprintf(value, sizeof value, "%+.1f s", diff);
    text += (text.empty() ? "" : ", ") + std::string(what) + " " + value;
  }
  return text;
}

std::string explain_by_operation(const RankedProgram& r, const RankedProgram& best, RankBy by,
                                 std::size_t max_operations) {
  if (r.rank == 1) return {};
  auto measure = [by](const OperationTotals& op) {
    return by == RankBy::Time ? op.time_s : by == RankBy::Cost ? op.cost : op.energy_j / 1000;
  };
  // Operations of one name are summed (a post may split one into several runs); their time
  // split too, for the cause in time.
  struct Diff {
    std::string name;
    double value = 0; // this minus best
    TimeSplit here, best;
  };
  std::vector<Diff> diffs;
  auto add = [&diffs](const OperationTotals& op, double value, bool mine) {
    auto it =
        std::find_if(diffs.begin(), diffs.end(), [&](const Diff& d) { return d.name == op.name; });
    if (it == diffs.end()) it = diffs.insert(diffs.end(), Diff{op.name});
    it->value += value;
    TimeSplit& t = mine ? it->here : it->best;
    t.rapid_s += op.time.rapid_s;
    t.feed_s += op.time.feed_s;
    t.air_cut_s += op.time.air_cut_s;
    t.tool_change_s += op.time.tool_change_s;
    t.dwell_s += op.time.dwell_s;
    t.spindle_s += op.time.spindle_s;
    t.other_s += op.time.other_s;
  };
  for (const OperationTotals& op : r.totals.operations)
    add(op, measure(op), true);
  for (const OperationTotals& op : best.totals.operations)
    add(op, -measure(op), false);
  auto here = [](const ProgramTotals& t, const std::string& name) {
    return std::any_of(t.operations.begin(), t.operations.end(),
                       [&](const OperationTotals& op) { return op.name == name; });
  };
  const double noise = by == RankBy::Time ? 0.05 : by == RankBy::Cost ? 5e-5 : 0.05e-3;
  std::erase_if(diffs, [noise](const Diff& d) { return std::abs(d.value) <= noise; });
  std::stable_sort(diffs.begin(), diffs.end(), [](const Diff& a, const Diff& b) {
    return std::abs(a.value) > std::abs(b.value);
  });
  if (diffs.size() > max_operations) diffs.resize(max_operations);
  const bool removal = r.totals.removal && best.totals.removal;
  std::string text;
  for (const Diff& d : diffs) {
    const std::string& name = d.name;
    const double diff = d.value;
    char value[64];
    if (by == RankBy::Time)
      std::snprintf(value, sizeof value, "%+.1f s", diff);
    else if (by == RankBy::Cost)
      std::snprintf(value, sizeof value, "%+.4f %s", diff, r.totals.currency.c_str());
    else
      std::snprintf(value, sizeof value, "%+.1f kJ", diff);
    const char* where = !here(best.totals, name) ? " (only here)"
                        : !here(r.totals, name)  ? " (only in the best)"
                                                 : "";
    // The cause in time; for a time ranking only when it is more than the total said already.
    std::string cause = explain_time_difference(d.here, d.best, removal, 2);
    if (by == RankBy::Time && cause.find(',') == std::string::npos) cause.clear(); // said already
    text += (text.empty() ? "" : ", ") + name + where + " " + value +
            (cause.empty() ? "" : " (" + cause + ")");
  }
  return text;
}

std::string comparison_json(const std::vector<RankedProgram>& ranked, const MachineProfile& machine,
                            int indent, RankBy by) {
  Json j;
  j["machine"] = Json{{"name", machine.name}, {"file", machine.source_path}};
  j["ranked_by"] = by == RankBy::Time ? "time_s" : by == RankBy::Cost ? "cost" : "energy_j";
  Json list = Json::array();
  for (const RankedProgram& r : ranked) {
    const ProgramTotals& t = r.totals;
    Json p;
    p["rank"] = r.rank;
    p["file"] = t.file;
    p["time_s"] = t.time_s;
    p["energy_j"] = t.energy_j;
    p["removed_mm3"] = t.removed_mm3;
    p["air_cut_s"] = t.air_cut_s;
    p["sec_j_mm3"] = t.sec_j_mm3;
    p["co2_kg"] = t.co2_kg;
    p["cost"] = t.cost;
    p["machine_cost"] = t.machine_cost;
    p["currency"] = t.currency;
    p["components"] = components_json(t.components_j);
    p["peak_power_w"] = t.peak_power_w;
    p["time_split"] = Json{{"cutting_s", t.removal ? Json(t.time.cutting_s()) : Json(nullptr)},
                           {"air_cut_s", t.removal ? Json(t.time.air_cut_s) : Json(nullptr)},
                           {"feed_s", t.time.feed_s},
                           {"rapid_s", t.time.rapid_s},
                           {"tool_change_s", t.time.tool_change_s},
                           {"dwell_s", t.time.dwell_s},
                           {"spindle_s", t.time.spindle_s},
                           {"other_s", t.time.other_s}};
    if (t.guess.guessed) {
      auto range = [](const GuessedFigures::Range& x) { return Json::array({x.low, x.high}); };
      p["stock_guess"] = Json{{"removed_mm3", range(t.guess.removed_mm3)},
                              {"energy_j", range(t.guess.energy_j)},
                              {"peak_power_w", range(t.guess.peak_power_w)},
                              {"co2_kg", range(t.guess.co2_kg)},
                              {"cost", range(t.guess.cost)}};
    } else {
      p["stock_guess"] = nullptr;
    }
    p["why"] = explain_difference(r);
    p["why_in_time"] = r.rank == 1
                           ? std::string()
                           : explain_time_difference(t.time, ranked.front().totals.time,
                                                     t.removal && ranked.front().totals.removal);
    p["why_by_operation"] = explain_by_operation(r, ranked.front(), by);
    p["vs_best"] = Json{{"time_s", r.time_diff_s},
                        {"time_pct", r.time_diff_pct},
                        {"energy_j", r.energy_diff_j},
                        {"energy_pct", r.energy_diff_pct},
                        {"cost", r.cost_diff},
                        {"co2_kg", r.co2_diff_kg},
                        {"components", components_json(r.component_diff_j)}};
    list.push_back(std::move(p));
  }
  j["programs"] = std::move(list);
  j["warnings"] = comparison_warnings(ranked);
  return j.dump(indent);
}

} // namespace ncjoule
