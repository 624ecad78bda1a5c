// An agent's Streams document (MTConnectStreams, the answer to /sample or /current saved to a
// file), MTConnect 1.2 to 2.x: DeviceStream > ComponentStream > Samples | Events | Condition,
// one element per observation, named by its type (<PathFeedrateOverride subType="RAPID">,
// <Line>, <LineNumber>). The document lists observations by component and type, not by time:
// they are put back in the agent's order (sequence) to find clock jumps, then in time order.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "log_builder.hpp"
#include "xml_util.hpp"

namespace ncjoule {
namespace {

using logs_detail::ItemResolver;
using logs_detail::ItemType;
using logs_detail::local_name;

// "PathFeedrateOverride" -> "PATH_FEEDRATE_OVERRIDE"; the representation's suffix goes to
// `representation` ("PositionTimeSeries" -> POSITION, TIME_SERIES).
std::string type_of_element(std::string_view name, std::string& representation) {
  for (std::string_view suffix : {"TimeSeries", "DataSet", "Table"}) {
    if (name.size() > suffix.size() && name.substr(name.size() - suffix.size()) == suffix) {
      representation = suffix == "TimeSeries" ? "TIME_SERIES"
                       : suffix == "DataSet"  ? "DATA_SET"
                                              : "TABLE";
      name.remove_suffix(suffix.size());
      break;
    }
  }
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (std::isupper(c) && i > 0) out += '_';
    out += char(std::toupper(c));
  }
  return out;
}

struct Pending {
  double t_s;
  unsigned long long sequence;
  std::size_t index; // into the log's observations
};

} // namespace

bool parse_streams_log(std::string_view text, const std::string& path, ControllerLog& log,
                       const LogReadOptions& options, std::vector<Diagnostic>& diagnostics) {
  pugi::xml_document doc;
  const pugi::xml_parse_result result = doc.load_buffer(text.data(), text.size());
  if (!result) {
    diagnostics.push_back({Severity::Error, path, logs_detail::line_of_offset(text, result.offset),
                           0, logs_detail::xml_error(result)});
    return false;
  }
  const pugi::xml_node root = doc.document_element();
  const std::string_view kind = local_name(root);
  if (kind == "MTConnectDevices") {
    diagnostics.push_back({Severity::Error, path, 0, 0,
                           "this is the agent's device file, not a log: give it with --devices"});
    return false;
  }
  if (kind == "MTConnectError") {
    std::string why;
    const pugi::xpath_node error = root.select_node("//*[local-name()='Error']");
    if (error)
      why = std::string(error.node().attribute("errorCode").value()) + ": " +
            error.node().child_value();
    diagnostics.push_back({Severity::Error, path, 0, 0,
                           "the agent answered with an error, not a log" +
                               (why.empty() ? std::string() : " (" + why + ")")});
    return false;
  }
  if (kind != "MTConnectStreams") {
    diagnostics.push_back({Severity::Error, path, 0, 0,
                           "not an MTConnect log: an XML document <" + std::string(root.name()) +
                               ">, where a Streams document (<MTConnectStreams>) or SHDR lines "
                               "were expected"});
    return false;
  }
  std::string format = "MTConnectStreams";
  if (const pugi::xml_node header = root.child("Header"); header) {
    if (const char* v = header.attribute("version").value(); *v) format += std::string(" ") + v;
  }
  const std::uint16_t file = static_cast<std::uint16_t>(log.files.size());
  log.files.push_back({path, format, 0, 0, 0});
  ItemResolver resolver(log, options);
  logs_detail::ValueProblems value_problems;
  std::vector<Pending> order;
  std::size_t bad_stamps = 0;
  int first_bad_line = 0;
  const std::size_t before = log.observations.size();

  const pugi::xpath_node_set devices = root.select_nodes("//*[local-name()='DeviceStream']");
  for (const pugi::xpath_node& dn : devices) {
    const pugi::xml_node device_node = dn.node();
    const std::string device_name = device_node.attribute("name").value();
    if (!options.device.empty() && device_name != options.device) continue;
    const std::uint16_t device = log.device_index(device_name);
    for (const pugi::xml_node& component : device_node.children()) {
      if (local_name(component) != "ComponentStream") continue;
      const std::string component_type = component.attribute("component").value();
      const std::string component_name = component.attribute("name").value();
      for (const pugi::xml_node& section : component.children()) {
        const std::string_view section_name = local_name(section);
        // Conditions say whether the control is in alarm, nothing a time is read from.
        if (section_name != "Samples" && section_name != "Events") continue;
        for (const pugi::xml_node& e : section.children()) {
          if (e.type() != pugi::node_element) continue;
          std::string representation;
          const std::string element(local_name(e));
          const bool extension = std::string_view(e.name()).find(':') != std::string_view::npos;
          const std::string type =
              extension ? std::string(e.name()) : type_of_element(element, representation);
          const char* stamp = e.attribute("timestamp").value();
          const auto t = parse_log_time(stamp);
          const int line = logs_detail::line_of_offset(text, e.offset_debug());
          if (!t) {
            if (bad_stamps++ == 0) first_bad_line = line;
            continue;
          }
          const std::string_view name = e.attribute("name").value();
          const std::string_view id = e.attribute("dataItemId").value();
          const ItemType known{type,
                               e.attribute("subType").value(),
                               component_type,
                               component_name,
                               "",
                               section_name == "Samples" ? "SAMPLE" : "EVENT",
                               representation};
          const auto& item = resolver.resolve(device, name.empty() ? id : name, id, known);
          if (!representation.empty()) continue; // time series and data sets: not read
          const std::size_t n = log.observations.size();
          logs_detail::add_observation(log, resolver, item, file, device, *t, e.child_value(),
                                       static_cast<std::uint32_t>(line), name.empty() ? id : name,
                                       value_problems);
          if (log.observations.size() > n)
            order.push_back({*t, std::strtoull(e.attribute("sequence").value(), nullptr, 10), n});
        }
      }
    }
  }
  if (bad_stamps > 0)
    diagnostics.push_back({Severity::Warning, path, first_bad_line, 0,
                           std::to_string(bad_stamps) + " element" + (bad_stamps > 1 ? "s" : "") +
                               " without a readable timestamp were skipped"});
  logs_detail::report_value_problems(value_problems, path, diagnostics);
  if (log.observations.size() == before) {
    diagnostics.push_back({Severity::Warning, path, 0, 0,
                           devices.empty() ? "the Streams document holds no DeviceStream"
                                           : "the Streams document holds no observation ncjoule "
                                             "reads (see the items it names)"});
    return true;
  }
  // The agent's order: a time that goes back along it is a clock that jumped.
  std::sort(order.begin(), order.end(),
            [](const Pending& a, const Pending& b) { return a.sequence < b.sequence; });
  double last = -INFINITY;
  for (const Pending& p : order) {
    if (p.t_s < last - 1.0) {
      const LogObservation& o = log.observations[p.index];
      diagnostics.push_back({Severity::Warning, path, int(o.line), 0,
                             "the clock jumps back " +
                                 std::to_string(int(std::lround(last - p.t_s))) + " s (sequence " +
                                 std::to_string(p.sequence) + ", " + format_log_time(p.t_s) +
                                 "): runs across it are not timed"});
      log.clock_jumps.push_back(p.t_s);
    }
    last = std::max(last, p.t_s);
  }
  auto [lo, hi] = std::minmax_element(
      order.begin(), order.end(), [](const Pending& a, const Pending& b) { return a.t_s < b.t_s; });
  log.files[file].first_s = lo->t_s;
  log.files[file].last_s = hi->t_s;
  return true;
}

} // namespace ncjoule
