// Internal: small helpers for reading MTConnect's XML with pugixml.
#pragma once

#include <pugixml.hpp>
#include <string>
#include <string_view>

namespace ncjoule::logs_detail {

// An element's name without its namespace prefix ("m:DataItem" -> "DataItem").
inline std::string_view local_name(const pugi::xml_node& node) {
  std::string_view name = node.name();
  const std::size_t colon = name.find(':');
  return colon == std::string_view::npos ? name : name.substr(colon + 1);
}

// 1-based line of a byte offset in `text` (for diagnostics).
int line_of_offset(std::string_view text, std::ptrdiff_t offset);

// Why pugixml could not read a document, as a sentence.
std::string xml_error(const pugi::xml_parse_result& result);

} // namespace ncjoule::logs_detail
