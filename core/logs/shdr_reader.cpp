// SHDR, an MTConnect adapter's lines as an agent receives them and shops save them:
//   2017-02-07T19:38:31.0625000Z|Block_Number|8|Feed_Rate|323.4
// a time stamp (optionally @duration), then item|value pairs; "device:item" names a device's
// item. A condition carries four more fields (native code, severity, qualifier, text), a message
// one. Lines of the agent protocol (* commands, @ASSET@) say nothing of the machine. A line that
// does not begin with a time stamp continues the one before it (a record broken across lines,
// as NIST's cleaning script broke values holding "2017").
#include <cmath>

#include "log_builder.hpp"

namespace ncjoule {
namespace {

using logs_detail::ItemResolver;
using logs_detail::ItemType;
using logs_detail::ResolvedItem;

std::vector<std::string_view> split_fields(std::string_view record) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t bar = record.find('|', start);
    fields.push_back(record.substr(start, bar == std::string_view::npos ? bar : bar - start));
    if (bar == std::string_view::npos) break;
    start = bar + 1;
  }
  return fields;
}

bool looks_like_stamp(std::string_view line) {
  return line.size() >= 19 && line[4] == '-' && line[7] == '-' &&
         (line[10] == 'T' || line[10] == ' ');
}

} // namespace

bool parse_shdr_log(std::string_view text, const std::string& path, ControllerLog& log,
                    const LogReadOptions& options, std::vector<Diagnostic>& diagnostics) {
  const std::uint16_t file = static_cast<std::uint16_t>(log.files.size());
  log.files.push_back({path, "SHDR", 0, 0, 0});
  ItemResolver resolver(log, options);
  logs_detail::ValueProblems value_problems;
  // The device of unprefixed items: the one asked for, else the device file's only one.
  std::string default_device = options.device;
  if (default_device.empty() && options.devices) {
    std::string only;
    bool one = true;
    for (const DataItemInfo& item : options.devices->items) {
      if (only.empty())
        only = item.device;
      else if (item.device != only)
        one = false;
    }
    if (one) default_device = only;
  }
  const std::uint16_t unprefixed = log.device_index(default_device);

  // Records: a physical line, with the lines after it that do not begin with a time stamp.
  struct Record {
    std::string text;
    std::uint32_t line;
  };
  std::vector<Record> records;
  std::size_t glued = 0, bad_stamps = 0, protocol = 0;
  int first_bad_line = 0;
  std::uint32_t line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty()) continue;
    if (line.front() == '*' || line.front() == '@') {
      ++protocol;
      continue;
    }
    if (looks_like_stamp(line) || records.empty()) {
      records.push_back({std::string(line), line_no});
    } else {
      records.back().text += line;
      ++glued;
    }
  }

  double last_t = -INFINITY;
  bool any = false;
  for (const Record& record : records) {
    const auto fields = split_fields(record.text);
    std::string_view stamp = fields[0];
    if (const std::size_t at = stamp.find('@'); at != std::string_view::npos)
      stamp = stamp.substr(0, at);
    const auto t = parse_log_time(stamp);
    if (!t) {
      if (bad_stamps++ == 0) first_bad_line = int(record.line);
      continue;
    }
    if (!any) log.files[file].first_s = *t;
    any = true;
    if (*t < last_t - 1.0) {
      // Written in order of arrival: a time going back is the clock's, not the machine's.
      diagnostics.push_back({Severity::Warning, path, int(record.line), 1,
                             "the clock jumps back " +
                                 std::to_string(int(std::lround(last_t - *t))) + " s (from " +
                                 format_log_time(last_t) + " to " + format_log_time(*t) +
                                 "): runs across it are not timed"});
      log.clock_jumps.push_back(*t);
    }
    last_t = std::max(last_t, *t);
    log.files[file].last_s = std::max(log.files[file].last_s, *t);
    for (std::size_t i = 1; i + 1 < fields.size();) {
      std::string_view key = fields[i];
      std::uint16_t device = unprefixed;
      if (const std::size_t colon = key.find(':'); colon != std::string_view::npos) {
        device = log.device_index(key.substr(0, colon));
        key = key.substr(colon + 1);
      }
      const ResolvedItem& item = resolver.resolve(device, key, {}, ItemType{});
      std::string_view value = fields[i + 1];
      int extra = item.extra_fields;
      // An item nothing describes whose value is a condition's level carries a condition's
      // fields: skip them rather than read them as items.
      if (!item.signal && extra == 0 &&
          (value == "NORMAL" || value == "WARNING" || value == "FAULT"))
        extra = 4;
      logs_detail::add_observation(log, resolver, item, file, device, *t, value, record.line, key,
                                   value_problems);
      i += 2 + std::size_t(extra);
    }
  }
  if (glued > 0)
    diagnostics.push_back({Severity::Note, path, 0, 0,
                           std::to_string(glued) + " line" + (glued > 1 ? "s" : "") +
                               " without a time stamp continue the line before (records broken "
                               "across lines) and were joined to it"});
  if (bad_stamps > 0)
    diagnostics.push_back({Severity::Warning, path, first_bad_line, 1,
                           std::to_string(bad_stamps) + " line" + (bad_stamps > 1 ? "s" : "") +
                               " without a readable time stamp were skipped"});
  logs_detail::report_value_problems(value_problems, path, diagnostics);
  if (!any) {
    diagnostics.push_back({Severity::Error, path, 0, 0,
                           "no SHDR line (time stamp|item|value) in the file" +
                               std::string(protocol ? ": only agent protocol lines" : "")});
    return false;
  }
  return true;
}

} // namespace ncjoule
