#include "header.hpp"

#include <algorithm>
#include <string_view>

#include "ncjoule/energy.hpp"
#include "ncjoule/text.hpp"
#include "number_format.hpp"

namespace ncjoule::annotation {
namespace {

struct Group {
  std::string label;
  std::vector<std::string> fields;
};

// A group with room for its fields: the header is built for every program, and each growth of
// the list moves every field.
Group make_group(std::string label) {
  Group g{std::move(label), {}};
  g.fields.reserve(16);
  return g;
}

std::string field(std::string_view key, std::string_view value) {
  std::string out;
  out.reserve(key.size() + 1 + value.size());
  out += key;
  out += '=';
  out += value;
  return out;
}

Group totals(const Estimate& estimate) {
  const EnergyResult& e = estimate.energy;
  Group g = make_group("TOTAL");
  g.fields.push_back(field("T", format_duration(estimate.time_s)));
  g.fields.push_back(field("E", format_si(e.energy_j, "J")));
  g.fields.push_back(field("E_KWH", format_significant(e.energy_j / 3.6e6, 4, 6)));
  g.fields.push_back(field("P_MEAN", format_si(e.mean_power_w, "W")));
  g.fields.push_back(field("P_PEAK", format_si(e.peak_power_w, "W")));
  g.fields.push_back(field("VOL_MM3", format_significant(e.removed_mm3, 4, 3)));
  g.fields.push_back(field("SEC_J_MM3", format_significant(e.sec_j_mm3, 3, 4)));
  g.fields.push_back(field("CO2_KG", format_significant(e.co2_kg, 3, 6)));
  const std::string currency = safe_token(e.currency, 8);
  g.fields.push_back(
      field("COST" + (currency.empty() ? "" : "_" + currency), format_significant(e.cost, 3, 4)));
  // Mean removal rate while cutting; an inch program also reads in inches.
  const double cutting_s = estimate.time.cutting_s();
  const double mrr = cutting_s > 0 ? e.removed_mm3 / cutting_s : 0;
  g.fields.push_back(field("MRR_MM3_S", format_significant(mrr, 4, 3)));
  // What the numbers rest on that nobody gave: the stock, tools, the machine.
  std::string guessed;
  if (estimate.removal && (estimate.removal->stock_source == StockSource::Guessed ||
                           estimate.removal->stock_source == StockSource::None))
    guessed += "STOCK";
  if (estimate.tools_guessed) guessed += guessed.empty() ? "TOOLS" : "-TOOLS";
  if (estimate.machine_guessed) guessed += guessed.empty() ? "MACHINE" : "-MACHINE";
  if (!guessed.empty()) g.fields.push_back(field("GUESSED", guessed));
  if (estimate.inch) {
    g.fields.push_back(field("VOL_IN3", format_significant(e.removed_mm3 / kMm3PerIn3, 4, 4)));
    g.fields.push_back(field("MRR_IN3_MIN", format_significant(mrr * 60 / kMm3PerIn3, 4, 4)));
  }
  return g;
}

// Where the time goes: rapids, cutting, air cutting (feed moves that remove nothing), tool
// changes, dwells and spindle ramps.
Group time_split(const Estimate& estimate) {
  const TimeSplit& t = estimate.time;
  Group g = make_group("TIME");
  g.fields.push_back(field("RAPID", format_duration(t.rapid_s)));
  g.fields.push_back(field("CUT", format_duration(t.cutting_s())));
  g.fields.push_back(field("AIR", estimate.removal ? format_duration(t.air_cut_s) : "unknown"));
  g.fields.push_back(field("TOOL_CHANGE", format_duration(t.tool_change_s)));
  g.fields.push_back(field("DWELL", format_duration(t.dwell_s)));
  g.fields.push_back(field("SPINDLE", format_duration(t.spindle_s)));
  if (t.other_s > 0) g.fields.push_back(field("OTHER", format_duration(t.other_s)));
  return g;
}

// One group per operation, in program order: its name, tool, time, air cutting, energy, volume
// and share of the energy. The first kMaxOperations; the text summary lists them all.
constexpr std::size_t kMaxOperations = 40;
std::vector<Group> operations(const Estimate& estimate) {
  std::vector<Group> out;
  out.reserve(std::min(estimate.operations.size(), kMaxOperations) + 1);
  const double total = estimate.energy.energy_j;
  for (std::size_t k = 0; k < estimate.operations.size() && k < kMaxOperations; ++k) {
    const OperationSummary& op = estimate.operations[k];
    Group g = make_group("OP");
    g.fields.push_back(field("N", std::to_string(k + 1)));
    g.fields.push_back(field("NAME", safe_token(op.name, 32)));
    g.fields.push_back(field("TOOL", op.tool > 0 ? "T" + std::to_string(op.tool) : "-"));
    g.fields.push_back(field("T", format_duration(op.time_s)));
    if (estimate.removal) g.fields.push_back(field("AIR", format_duration(op.time.air_cut_s)));
    g.fields.push_back(field("E", format_si(op.energy_j, "J")));
    g.fields.push_back(field("VOL_MM3", format_significant(op.removed_mm3, 4, 3)));
    if (estimate.inch)
      g.fields.push_back(field("VOL_IN3", format_significant(op.removed_mm3 / kMm3PerIn3, 4, 4)));
    // No '%': Fanuc-family controllers read it as the end of the tape, even in a comment.
    g.fields.push_back(
        field("SHARE_PCT", format_significant(total > 0 ? 100 * op.energy_j / total : 0, 3, 1)));
    out.push_back(std::move(g));
  }
  if (estimate.operations.size() > kMaxOperations)
    out.push_back({"OP",
                   {"and", std::to_string(estimate.operations.size() - kMaxOperations), "more", "-",
                    "ncjoule", "estimate", "lists", "them", "all"}});
  return out;
}

// A box as X0,Y0,Z0,X1,Y1,Z1 at `scale` (1 for mm, 1/25.4 for inches), 3 or 4 decimals.
std::string box_text(const Box3& b, double scale, int decimals) {
  std::string out;
  for (double v : {b.xmin, b.ymin, b.zmin, b.xmax, b.ymax, b.zmax}) {
    if (!out.empty()) out += ',';
    out += format_significant(v * scale, 12, decimals);
  }
  return out;
}

// The stock each setup cuts and where it comes from: a stock guessed from the cuts makes every
// volume and MRR a guess too, and says so before them.
std::vector<Group> stocks(const Estimate& estimate) {
  std::vector<Group> out;
  for (std::size_t k = 0; k < estimate.setups.size(); ++k) {
    const SetupSummary& setup = estimate.setups[k];
    if (!setup.stock_box) continue;
    Group g = make_group("STOCK");
    if (estimate.setups.size() > 1) g.fields.push_back(field("SETUP", std::to_string(k + 1)));
    g.fields.push_back(field("BOX_MM", box_text(*setup.stock_box, 1, 3)));
    if (estimate.inch) g.fields.push_back(field("BOX_IN", box_text(*setup.stock_box, 1 / 25.4, 4)));
    const char* source = setup.stock_source == StockSource::Guessed   ? "GUESSED FROM CUTS"
                         : setup.stock_source == StockSource::Program ? "FROM CAM COMMENTS"
                                                                      : "GIVEN";
    for (std::string_view rest = source; !rest.empty();) { // one field a word: lines wrap
      const std::size_t blank = std::min(rest.find(' '), rest.size());
      g.fields.emplace_back(rest.substr(0, blank));
      rest.remove_prefix(std::min(blank + 1, rest.size()));
    }
    if (!setup.stock_from.empty())
      g.fields.push_back(field("FROM", safe_token(setup.stock_from, 24)));
    out.push_back(std::move(g));
  }
  return out;
}

// The setups of a program with more than one: where each starts, why, and its totals.
std::vector<Group> setups(const Estimate& estimate) {
  std::vector<Group> out;
  if (estimate.setups.size() < 2) return out;
  for (std::size_t k = 0; k < estimate.setups.size(); ++k) {
    const SetupSummary& setup = estimate.setups[k];
    Group g = make_group("SETUP");
    g.fields.push_back(field("N", std::to_string(k + 1)));
    g.fields.push_back(field("LINE", std::to_string(setup.first_line + 1)));
    g.fields.push_back(field("T", format_duration(setup.time_s)));
    g.fields.push_back(field("E", format_si(setup.energy_j, "J")));
    g.fields.push_back(field("VOL_MM3", format_significant(setup.removed_mm3, 4, 3)));
    g.fields.push_back(field("FROM", safe_token(setup.reason, 48)));
    out.push_back(std::move(g));
  }
  return out;
}

// The range of the figures a guessed stock sets: from no cut to the guess.
std::vector<Group> guess_range(const Estimate& estimate) {
  const GuessedFigures g = guessed_figures(estimate);
  if (!g.guessed) return {};
  Group r = make_group("GUESSED STOCK RANGE");
  auto span = [](const std::string& low, const std::string& high) { return low + ".." + high; };
  r.fields.push_back(
      field("E", span(format_si(g.energy_j.low, "J"), format_si(g.energy_j.high, "J"))));
  r.fields.push_back(field(
      "P_PEAK", span(format_si(g.peak_power_w.low, "W"), format_si(g.peak_power_w.high, "W"))));
  if (estimate.inch)
    r.fields.push_back(
        field("VOL_IN3", span(format_significant(g.removed_mm3.low / kMm3PerIn3, 4, 4),
                              format_significant(g.removed_mm3.high / kMm3PerIn3, 4, 4))));
  else
    r.fields.push_back(field("VOL_MM3", span(format_significant(g.removed_mm3.low, 4, 3),
                                             format_significant(g.removed_mm3.high, 4, 3))));
  return {r};
}

Group components(const Estimate& estimate) {
  Group g = make_group("ENERGY");
  for (std::size_t i = 0; i < kPowerComponentCount; ++i) {
    std::string key(component_name(PowerComponent(i)));
    key = to_upper(key);
    g.fields.push_back(field(key, format_si(estimate.energy.components_j[i], "J")));
  }
  return g;
}

Group machine_used(const Estimate& estimate, const MachineProfile& machine) {
  Group g = make_group("MACHINE");
  g.fields.push_back(field("NAME", safe_token(machine.name, 60)));
  const std::string& path = machine.source_path;
  const std::size_t slash = path.find_last_of("/\\");
  const std::string file = slash == std::string::npos ? path : path.substr(slash + 1);
  if (!file.empty()) g.fields.push_back(field("PROFILE", safe_token(file, 60)));
  g.fields.push_back(field("MODEL", std::string(model_name(estimate.power.model))));
  g.fields.push_back(field("DIALECT", safe_token(estimate.dialect.name, 20)));
  g.fields.push_back(field("DIALECT_FROM", estimate.dialect_origin == DialectOrigin::Given ? "given"
                                           : estimate.dialect_origin == DialectOrigin::Detected
                                               ? "detected"
                                               : "default"));
  g.fields.push_back(field("REMOVAL", estimate.removal ? "simulated" : "off"));
  return g;
}

// The constants of the model in use, named by their profile keys (the Pavanaskar ones without
// their "pavanaskar." prefix): the per-axis KA/KB terms next to Zhou's MRR term.
Group constants(const PowerConstants& power) {
  Group g = make_group("CONST");
  std::vector<PowerParameter> used = model_parameters(power.model);
  if (std::find(used.begin(), used.end(), PowerParameter::ToolChange) == used.end())
    used.push_back(PowerParameter::ToolChange);
  for (PowerParameter p : used) {
    std::string_view key = parameter_info(p).key;
    constexpr std::string_view kPrefix = "pavanaskar.";
    if (key.substr(0, kPrefix.size()) == kPrefix) key.remove_prefix(kPrefix.size());
    g.fields.push_back(field(key, format_significant(get_parameter(power, p), 4, 12)));
  }
  // Where the cutting term's constants come from: the machine's fit or the material table.
  if (!power.cutting_source.empty()) {
    const bool material = power.cutting_term == CuttingTerm::Material;
    g.fields.push_back(field("CUT_FROM", material ? "material_" + safe_token(power.material, 24)
                                                  : std::string("fit")));
  }
  return g;
}

// Notation a person reads as words where a comment cannot carry its marks: a model's formula by
// what it is, a unit's ratio as "per" ("c3*n^c4*MRR" would read "c3 nc4 MRR", "mm^3/s" "mm3-s").
std::string in_words(std::string_view text) {
  static const std::pair<std::string_view, std::string_view> kWords[] = {
      {"cutting term c3*n^c4*MRR", "cutting term"},
      {"c3*n^c4*MRR", "cutting term"},
      {"line c1 + c2*n", "line"},
      {"c1 + c2*n", "idle line"},
      {"J/mm^3", "J per mm3"},
      {"J/in^3", "J per in3"},
      {"mm^3/s", "mm3 per s"},
      {"in^3/min", "in3 per min"},
      {"mm/min", "mm per min"},
      {"in/min", "in per min"},
      {"mm^3", "mm3"},
      {"in^3", "in3"},
      {"W/rpm", "W per rpm"},
      {"kW/rpm", "kW per rpm"}};
  std::string out(text);
  for (const auto& [mark, words] : kWords)
    for (std::size_t at = out.find(mark); at != std::string::npos;
         at = out.find(mark, at + words.size()))
      out.replace(at, mark.size(), words);
  return out;
}

// A message as words a controller reads safely inside a comment: letters, digits, space and
// . , = _ - only. Formulas and units are put in words first (in_words), a clause mark (: ;)
// becomes a comma, brackets and quotes go.
std::string safe_words(std::string_view message) {
  const std::string worded = in_words(message);
  const std::string_view text = worded;
  std::string out;
  out.reserve(text.size());
  auto put = [&](char c) {
    if (c == ' ' && (out.empty() || out.back() == ' ')) return;
    if (c == ',' && !out.empty() && out.back() == ' ') out.pop_back();
    out += c;
  };
  for (char c : text) {
    if (c == '^' || c == '(' || c == ')' || c == '[' || c == ']' || c == '"' || c == '\'' ||
        c == '`')
      continue;
    if (c == '/')
      put('-');
    else if (c == ':' || c == ';')
      put(',');
    else
      put(is_safe_char(c) ? c : ' ');
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ',' || out.back() == '.'))
    out.pop_back();
  return out;
}

// The point of a message, as one whole sentence of at most `room` characters: all of it when it
// fits (details in brackets left out), else its first and last clauses (the clauses between
// ": ", "; " or " - "; most messages say what and where first, and what follows last), else
// its first clause, else as much of that as ends at a comma or a word; empty when not even a
// word fits.
std::string sentence(std::string_view message, std::size_t room) {
  std::string plain;
  int depth = 0;
  for (char c : message) {
    if (c == '(') ++depth;
    if (depth == 0) plain += c;
    if (c == ')' && depth > 0) --depth;
  }
  std::vector<std::string> clauses;
  std::string_view rest = plain;
  while (!rest.empty()) {
    std::size_t end = rest.size(), skip = 0;
    for (std::string_view mark : {": ", "; ", " - "})
      if (const std::size_t at = rest.find(mark); at < end) end = at, skip = mark.size();
    if (std::string c = safe_words(rest.substr(0, end)); !c.empty()) clauses.push_back(c);
    rest.remove_prefix(std::min(rest.size(), end + skip));
  }
  if (clauses.empty()) return {};
  std::string all;
  for (const std::string& c : clauses)
    all += (all.empty() ? "" : ", ") + c;
  if (all.size() + 1 <= room) return all + ".";
  if (clauses.size() > 2) {
    const std::string ends = clauses.front() + ", " + clauses.back();
    if (ends.size() + 1 <= room) return ends + ".";
  }
  const std::string& text = clauses.front();
  if (text.size() + 1 <= room) return text + ".";
  if (room < 2) return {};
  for (char boundary : {',', ' '}) {
    // The last boundary that leaves the text before it, and its full stop, within `room`.
    const std::size_t cut = text.rfind(boundary, room - 1);
    if (cut == std::string::npos || cut == 0) continue;
    std::string part = text.substr(0, cut);
    while (!part.empty() && (part.back() == ',' || part.back() == ' '))
      part.pop_back();
    if (!part.empty()) return part + ".";
  }
  return {};
}

} // namespace

// What the user should know before trusting the numbers: the tools that were not simulated, and
// the program's warnings and errors, one line each (the same message once, with its count), the
// first few of them.
std::vector<WarningText> header_warnings(const Estimate& estimate) {
  constexpr std::size_t kMaxLines = 8;
  std::vector<WarningText> texts;
  texts.reserve(kMaxLines + 1);
  if (!estimate.unsimulated_tools.empty()) {
    std::string tools;
    for (std::size_t k = 0; k < estimate.unsimulated_tools.size() && k < 6; ++k)
      tools += (k ? " T" : "T") + std::to_string(estimate.unsimulated_tools[k]);
    if (estimate.unsimulated_tools.size() > 6)
      tools += " and " + std::to_string(estimate.unsimulated_tools.size() - 6) + " more";
    texts.push_back({"", 0,
                     "tools " + tools +
                         " not simulated, their moves remove nothing, describe them "
                         "with --tool",
                     1});
  }
  std::vector<std::pair<const Diagnostic*, int>> distinct; // first of each message, count
  for (const Diagnostic& d : estimate.diagnostics) {
    if (d.severity == Severity::Note) continue;
    auto same = std::find_if(distinct.begin(), distinct.end(), [&](const auto& x) {
      return x.first->message == d.message && x.first->severity == d.severity;
    });
    if (same != distinct.end())
      ++same->second;
    else
      distinct.push_back({&d, 1});
  }
  std::size_t shown = 0;
  for (const auto& [d, count] : distinct) {
    if (texts.size() >= kMaxLines) break;
    texts.push_back({d->severity == Severity::Error ? "ERROR " : "", d->line, d->message, count});
    ++shown;
  }
  if (shown < distinct.size())
    texts.push_back({"", 0,
                     std::to_string(distinct.size() - shown) +
                         " more warnings, ncjoule estimate lists them all",
                     1});
  return texts;
}

namespace {

std::size_t comment_length(std::size_t content_length, const WriteStyle& style) {
  return style.comment.open.size() + content_length + style.comment.close.size();
}

// The lines `fields` make under `start` when each line holds at most `width` bytes.
std::vector<std::string> fill(const std::string& start, const std::vector<std::string>& fields,
                              std::size_t width, const WriteStyle& style) {
  std::vector<std::string> contents;
  std::string content = start;
  for (const std::string& f : fields) {
    if (content.size() > start.size() &&
        comment_length(content.size() + 1 + f.size(), style) > width) {
      contents.push_back(content);
      content = start;
    }
    content += ' ';
    content += f;
  }
  if (content.size() > start.size()) contents.push_back(content);
  return contents;
}

// A group on as few lines as it needs, each beginning with its label, the fields spread evenly
// over them: a line that does not fit is never left with a fragment of its group's end.
void wrap(const Group& group, const WriteStyle& style, std::vector<std::string>& lines) {
  const std::string start = "NCJ " + group.label;
  // A field too long for a line of its own is left out rather than cut.
  std::vector<std::string> fields;
  for (const std::string& f : group.fields)
    if (comment_length(start.size() + 1 + f.size(), style) <= style.max_line_length)
      fields.push_back(f);
  std::vector<std::string> best = fill(start, fields, style.max_line_length, style);
  // The narrowest width that needs no more lines.
  for (std::size_t width = style.max_line_length; width-- > start.size();) {
    std::vector<std::string> narrower = fill(start, fields, width, style);
    bool fits = narrower.size() == best.size();
    for (const std::string& c : narrower)
      fits = fits && comment_length(c.size(), style) <= width;
    if (!fits) break;
    best = std::move(narrower);
  }
  for (const std::string& c : best)
    lines.push_back(plain_comment(c, style.comment));
}

} // namespace

std::vector<std::string> summary_lines(const Estimate& estimate, const MachineProfile& machine,
                                       const WriteStyle& style) {
  std::vector<std::string> lines;
  lines.reserve(32);
  wrap(totals(estimate), style, lines);
  wrap(time_split(estimate), style, lines);
  for (const Group& g : stocks(estimate))
    wrap(g, style, lines);
  for (const Group& g : guess_range(estimate))
    wrap(g, style, lines);
  for (const Group& g : setups(estimate))
    wrap(g, style, lines);
  wrap(components(estimate), style, lines);
  for (const Group& g : operations(estimate))
    wrap(g, style, lines);
  wrap(machine_used(estimate, machine), style, lines);
  wrap(constants(estimate.power), style, lines);
  return lines;
}

std::vector<std::string> warning_lines(const std::vector<WarningText>& warnings,
                                       const WriteStyle& style,
                                       const std::function<int(int)>& line_in_output) {
  std::vector<std::string> lines;
  for (const WarningText& w : warnings) {
    std::string content = "NCJ WARN " + w.head;
    if (w.line > 0) content += "L" + std::to_string(line_in_output(w.line)) + " ";
    const std::size_t room = style.max_line_length -
                             std::min(style.max_line_length, comment_length(content.size(), style));
    const std::string times = w.count > 1 ? ", " + std::to_string(w.count) + " times" : "";
    std::string text = sentence(w.message, room > times.size() ? room - times.size() : 0);
    if (!text.empty() && !times.empty()) text.insert(text.size() - 1, times);
    if (text.empty()) text = sentence("a warning, ncjoule estimate gives it whole", room);
    lines.push_back(plain_comment(content + text, style.comment));
  }
  return lines;
}

std::vector<std::string> key_lines(const KeyUse& keys, const WriteStyle& style) {
  std::vector<std::string> parts;
  const BlockFields& f = keys.fields;
  if (f.time) parts.push_back("T=time of the block");
  if (f.energy) parts.push_back("E=its energy");
  if (f.power) parts.push_back("P=its mean power");
  if (f.mrr)
    parts.push_back(keys.inch ? "MRR=its mean removal rate in in3 per min"
                              : "MRR=its mean removal rate in mm3 per s");
  if (f.cumulative) parts.push_back("CUM=time at its end");
  if (keys.load) parts.push_back("LOAD_PCT=spindle power in percent of its rating");
  if (keys.operation) {
    parts.push_back("OP=operation starting here");
    parts.push_back("OPT=its time");
    parts.push_back("OPE=its energy");
  }
  // Whole sentences: as many definitions as fit a line, then a full stop.
  std::vector<std::string> lines;
  const std::string start = "NCJ KEYS ";
  std::string content;
  auto flush = [&] {
    if (!content.empty()) lines.push_back(plain_comment(start + content + ".", style.comment));
    content.clear();
  };
  auto fits = [&](std::size_t length) {
    return comment_length(start.size() + length + 1, style) <= style.max_line_length;
  };
  for (const std::string& p : parts) {
    if (!fits(p.size())) continue; // no line is that long: said in the documentation only
    if (!content.empty() && !fits(content.size() + 2 + p.size())) flush();
    content += (content.empty() ? "" : ", ") + p;
  }
  flush();
  for (std::string_view seal :
       {"SEAL lets ncjoule strip take out exactly these comments", "SEAL is for ncjoule strip"})
    if (fits(seal.size())) {
      lines.push_back(plain_comment(start + std::string(seal) + ".", style.comment));
      break;
    }
  return lines;
}

} // namespace ncjoule::annotation
