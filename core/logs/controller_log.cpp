// The controller log as one time-ordered list of observations, gathered from one or more files
// (SHDR or Streams documents, told apart by their content), and the parts the readers share.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <tuple>

#include "log_builder.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule {

bool parse_shdr_log(std::string_view text, const std::string& path, ControllerLog& log,
                    const LogReadOptions& options, std::vector<Diagnostic>& diagnostics);
bool parse_streams_log(std::string_view text, const std::string& path, ControllerLog& log,
                       const LogReadOptions& options, std::vector<Diagnostic>& diagnostics);

std::uint32_t ControllerLog::intern(std::string_view t) {
  // Texts are few (program names, execution words): a linear search keeps them in order.
  for (std::size_t i = 0; i < texts.size(); ++i)
    if (texts[i] == t) return static_cast<std::uint32_t>(i);
  texts.emplace_back(t);
  return static_cast<std::uint32_t>(texts.size() - 1);
}

std::uint16_t ControllerLog::device_index(std::string_view name) {
  for (std::size_t i = 0; i < devices.size(); ++i)
    if (devices[i] == name) return static_cast<std::uint16_t>(i);
  devices.emplace_back(name);
  items.resize(devices.size());
  return static_cast<std::uint16_t>(devices.size() - 1);
}

int ControllerLog::span_of(double t_s) const {
  for (std::size_t i = 0; i < coverage.size(); ++i)
    if (t_s >= coverage[i].first - 1e-6 && t_s <= coverage[i].second + 1e-6) return int(i);
  return -1;
}

namespace logs_detail {
namespace {

bool is_text_signal(LogSignal s) {
  return s == LogSignal::Program || s == LogSignal::Execution || s == LogSignal::Mode ||
         s == LogSignal::Block || s == LogSignal::Availability || s == LogSignal::EmergencyStop;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
    s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
    s.remove_suffix(1);
  return s;
}

std::optional<double> parse_number(std::string_view s, bool digits_inside) {
  s = trim(s);
  if (digits_inside) {
    // A TOOL_ID may be written "T12": its number is what the program's T word says.
    while (!s.empty() && !std::isdigit(static_cast<unsigned char>(s.front())) && s.front() != '-')
      s.remove_prefix(1);
  }
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || (end != s.data() + s.size() && !digits_inside) || !std::isfinite(value))
    return std::nullopt;
  return value;
}

} // namespace

void add_observation(ControllerLog& log, const ItemResolver& resolver, const ResolvedItem& item,
                     std::uint16_t file, std::uint16_t device, double t_s, std::string_view value,
                     std::uint32_t line, std::string_view key, ValueProblems& problems) {
  if (!item.signal) return;
  LogObservation o;
  o.t_s = t_s;
  o.signal = *item.signal;
  o.file = file;
  o.device = device;
  o.line = line;
  value = trim(value);
  if (value == "UNAVAILABLE") {
    o.unavailable = true;
    o.value = std::numeric_limits<double>::quiet_NaN();
  } else if (is_text_signal(o.signal)) {
    o.value = std::numeric_limits<double>::quiet_NaN();
    o.text = log.intern(o.signal == LogSignal::Execution ? resolver.execution_word(value)
                                                         : std::string(value));
  } else {
    const auto number = parse_number(value, o.signal == LogSignal::Tool);
    if (!number) {
      if (problems.not_numbers++ == 0) {
        problems.first_line = int(line);
        problems.first_item = std::string(key) + " = '" + std::string(value.substr(0, 40)) + "'";
      }
      return;
    }
    o.value = *number * item.scale;
  }
  log.observations.push_back(o);
  ++log.files[file].observations;
}

void report_value_problems(const ValueProblems& problems, const std::string& path,
                           std::vector<Diagnostic>& diagnostics) {
  if (problems.not_numbers == 0) return;
  diagnostics.push_back({Severity::Warning, path, problems.first_line, 0,
                         std::to_string(problems.not_numbers) + " value" +
                             (problems.not_numbers > 1 ? "s" : "") +
                             " of numeric items are not numbers and were skipped, the first: " +
                             problems.first_item});
}

} // namespace logs_detail

bool parse_controller_log(std::string_view text, const std::string& path, ControllerLog& log,
                          const LogReadOptions& options, std::vector<Diagnostic>& diagnostics) {
  if (const std::string encoding = non_text_encoding(text); !encoding.empty()) {
    diagnostics.push_back({Severity::Error, path, 0, 0,
                           "holds " + encoding + ", not an MTConnect log (SHDR or XML text)"});
    return false;
  }
  std::string_view body = text;
  if (body.substr(0, 3) == "\xEF\xBB\xBF") body.remove_prefix(3);
  while (!body.empty() && std::isspace(static_cast<unsigned char>(body.front())))
    body.remove_prefix(1);
  if (body.empty()) {
    diagnostics.push_back({Severity::Error, path, 0, 0, "the log is empty"});
    return false;
  }
  if (log.files.size() >= std::numeric_limits<std::uint16_t>::max()) {
    diagnostics.push_back({Severity::Error, path, 0, 0, "too many log files in one run"});
    return false;
  }
  if (body.front() == '<') return parse_streams_log(text, path, log, options, diagnostics);
  return parse_shdr_log(text, path, log, options, diagnostics);
}

bool read_controller_log(const std::string& path, ControllerLog& log, const LogReadOptions& options,
                         std::vector<Diagnostic>& diagnostics) {
  auto text = read_text_file(path, "an MTConnect log (SHDR or a Streams document)", diagnostics,
                             kDefaultMaxProgramBytes);
  if (!text) return false;
  return parse_controller_log(*text, path, log, options, diagnostics);
}

void finish_controller_log(ControllerLog& log, std::vector<Diagnostic>& diagnostics) {
  auto& obs = log.observations;
  std::stable_sort(obs.begin(), obs.end(),
                   [](const LogObservation& a, const LogObservation& b) { return a.t_s < b.t_s; });
  // The same value at the same time of the same item, from two files (a day's log and a piece
  // cut from it), is one observation.
  auto same = [&](const LogObservation& a, const LogObservation& b) {
    return a.t_s == b.t_s && a.signal == b.signal && a.device == b.device &&
           a.unavailable == b.unavailable && a.text == b.text &&
           (a.value == b.value || (std::isnan(a.value) && std::isnan(b.value)));
  };
  std::vector<LogObservation> kept;
  kept.reserve(obs.size());
  for (std::size_t i = 0; i < obs.size(); ++i) {
    bool duplicate = false;
    for (std::size_t j = kept.size(); j-- > 0 && kept[j].t_s == obs[i].t_s;)
      if (same(kept[j], obs[i]) && kept[j].file != obs[i].file) {
        duplicate = true;
        break;
      }
    if (!duplicate) kept.push_back(obs[i]);
  }
  obs.swap(kept);
  // The files' spans, merged where they overlap.
  std::vector<std::pair<double, double>> spans;
  for (const ControllerLog::File& f : log.files)
    if (f.observations > 0) spans.emplace_back(f.first_s, f.last_s);
  std::sort(spans.begin(), spans.end());
  log.coverage.clear();
  for (const auto& s : spans) {
    if (!log.coverage.empty() && s.first <= log.coverage.back().second + 1e-6)
      log.coverage.back().second = std::max(log.coverage.back().second, s.second);
    else
      log.coverage.push_back(s);
  }
  // The signals everything rests on.
  for (std::size_t d = 0; d < log.devices.size(); ++d) {
    if (d >= log.items.size()) break;
    bool any = false;
    for (const std::string& item : log.items[d])
      any = any || !item.empty();
    if (!any) continue;
    const std::string who = log.devices[d].empty() ? "the log" : "device " + log.devices[d];
    const std::string file = log.files.empty() ? "" : log.files.front().path;
    for (LogSignal s : {LogSignal::Execution, LogSignal::Line})
      if (log.items[d][static_cast<std::size_t>(s)].empty())
        diagnostics.push_back(
            {Severity::Warning, file, 0, 0,
             who + " has no " + (s == LogSignal::Line ? "LINE (the block running)" : "EXECUTION") +
                 " item: runs cannot be " +
                 (s == LogSignal::Line ? "aligned with programs" : "found") +
                 "; give the agent's device file (--devices) or a mapping file (--log-mapping)"});
  }
}

} // namespace ncjoule
