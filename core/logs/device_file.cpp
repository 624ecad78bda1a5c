// The agent's device file (MTConnectDevices, Devices.xml): every data item with its type,
// subType, category, units and the component and device it belongs to, so that SHDR item names
// (which say nothing of what they are) can be read by MTConnect type.
#include <algorithm>

#include "ncjoule/logs.hpp"
#include "ncjoule/text_file.hpp"
#include "xml_util.hpp"

namespace ncjoule {
namespace logs_detail {

int line_of_offset(std::string_view text, std::ptrdiff_t offset) {
  if (offset < 0) return 0;
  const std::size_t end = std::min(text.size(), static_cast<std::size_t>(offset));
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + std::ptrdiff_t(end), '\n'));
}

std::string xml_error(const pugi::xml_parse_result& result) {
  return std::string("not well-formed XML: ") + result.description();
}

} // namespace logs_detail

namespace {

using logs_detail::local_name;

struct DeviceWalker {
  DeviceFile& out;

  void walk(const pugi::xml_node& node, const std::string& device, const std::string& component,
            const std::string& component_name) {
    for (const pugi::xml_node& child : node.children()) {
      if (child.type() != pugi::node_element) continue;
      const std::string_view name = local_name(child);
      if (name == "DataItems") {
        for (const pugi::xml_node& item : child.children()) {
          if (item.type() != pugi::node_element || local_name(item) != "DataItem") continue;
          DataItemInfo info;
          info.id = item.attribute("id").value();
          info.name = item.attribute("name").value();
          info.type = item.attribute("type").value();
          info.sub_type = item.attribute("subType").value();
          info.category = item.attribute("category").value();
          info.units = item.attribute("units").value();
          info.representation = item.attribute("representation").value();
          info.component = component;
          info.component_name = component_name;
          info.device = device;
          out.items.push_back(std::move(info));
        }
      } else if (name == "Device" || name == "Agent") {
        walk(child, child.attribute("name").value(), std::string(name),
             child.attribute("name").value());
      } else if (name == "Components" || name == "Devices" || name == "MTConnectDevices") {
        walk(child, device, component, component_name);
      } else if (name == "Header" || name == "Description" || name == "Configuration" ||
                 name == "References" || name == "Compositions") {
        continue;
      } else {
        // A component (Axes, Rotary, Linear, Controller, Path, Spindle, Electric, ...).
        const char* cname = child.attribute("name").value();
        walk(child, device, std::string(name), *cname ? cname : std::string(name));
      }
    }
  }
};

} // namespace

const DataItemInfo* DeviceFile::find(std::string_view name_or_id, std::string_view device) const {
  const DataItemInfo* by_name = nullptr;
  for (const DataItemInfo& item : items) {
    if (!device.empty() && item.device != device) continue;
    if (item.id == name_or_id) return &item;
    if (!by_name && item.name == name_or_id) by_name = &item;
  }
  return by_name;
}

std::optional<DeviceFile> parse_device_file(std::string_view xml, const std::string& path,
                                            std::vector<Diagnostic>& diagnostics) {
  pugi::xml_document doc;
  const pugi::xml_parse_result result = doc.load_buffer(xml.data(), xml.size());
  if (!result) {
    diagnostics.push_back({Severity::Error, path, logs_detail::line_of_offset(xml, result.offset),
                           0, logs_detail::xml_error(result)});
    return std::nullopt;
  }
  const pugi::xml_node root = doc.document_element();
  if (local_name(root) != "MTConnectDevices") {
    diagnostics.push_back({Severity::Error, path, 0, 0,
                           "not an MTConnect device file: its document is <" +
                               std::string(root.name()) + ">, not <MTConnectDevices>"});
    return std::nullopt;
  }
  DeviceFile file;
  file.path = path;
  DeviceWalker{file}.walk(root, "", "", "");
  if (file.items.empty()) {
    diagnostics.push_back({Severity::Error, path, 0, 0, "the device file describes no data item"});
    return std::nullopt;
  }
  return file;
}

std::optional<DeviceFile> read_device_file(const std::string& path,
                                           std::vector<Diagnostic>& diagnostics) {
  auto text = read_text_file(path, "an MTConnect device file (Devices.xml)", diagnostics,
                             kMaxSettingsFileBytes);
  if (!text) return std::nullopt;
  return parse_device_file(*text, path, diagnostics);
}

} // namespace ncjoule
