// Internal: which signal each logged item is, decided once per item and shared by the SHDR and
// Streams readers. An item is known by the mapping file (by name or id), else by the device
// file's type for it, else by the type its Streams element carries, else (an SHDR log with
// neither file) by its name read as a type ("execution", "PathFeedrate"). One item per signal
// and device: the first claims it, the others are listed as unused.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "ncjoule/logs.hpp"

namespace ncjoule::logs_detail {

struct ResolvedItem {
  std::optional<LogSignal> signal;
  double scale = 1;     // the log's value times this is ncjoule's unit
  int extra_fields = 0; // SHDR fields after the value (a condition has 4, a message 1)
};

// What a Streams element (or the device file) says of an item.
struct ItemType {
  std::string_view type, sub_type, component, component_name, units, category, representation;
};

class ItemResolver {
public:
  ItemResolver(ControllerLog& log, const LogReadOptions& options) : log_(log), options_(options) {}

  // The item `key` (a name or an id; `id` too when the log gives both) of a device; `known`:
  // what the log itself says of its type (Streams), empty for SHDR.
  const ResolvedItem& resolve(std::uint16_t device, std::string_view key, std::string_view id,
                              const ItemType& known);
  // The execution word in MTConnect's words (the mapping's [execution], else upper case).
  std::string execution_word(std::string_view word) const;

private:
  ResolvedItem decide(std::uint16_t device, std::string_view key, std::string_view id,
                      const ItemType& known, std::string& described);

  ControllerLog& log_;
  const LogReadOptions& options_;
  std::map<std::pair<std::uint16_t, std::string>, ResolvedItem> cache_;
};

} // namespace ncjoule::logs_detail
