#include "item_resolver.hpp"

#include <algorithm>
#include <cctype>

namespace ncjoule::logs_detail {
namespace {

// "PathFeedrate", "path_feedrate", "pathFeedrate" -> "PATH_FEEDRATE".
std::string as_type_name(std::string_view name) {
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (std::isupper(c) && i > 0 && std::islower(static_cast<unsigned char>(name[i - 1])))
      out += '_';
    out += (c == '-' || c == ' ') ? '_' : char(std::toupper(c));
  }
  return out;
}

// Values in these units are converted; MTConnect's own units need nothing.
double unit_scale(std::string_view units) {
  if (units == "MILLIMETER/MINUTE") return 1.0 / 60;
  if (units == "INCH/MINUTE") return 25.4 / 60;
  if (units == "KILOWATT") return 1000;
  return 1;
}

} // namespace

std::string ItemResolver::execution_word(std::string_view word) const {
  if (options_.mapping) {
    const auto it = options_.mapping->execution.find(std::string(word));
    if (it != options_.mapping->execution.end()) return it->second;
  }
  std::string out(word);
  for (char& c : out)
    c = char(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

ResolvedItem ItemResolver::decide(std::uint16_t device, std::string_view key, std::string_view id,
                                  const ItemType& known, std::string& described) {
  ResolvedItem r;
  // 1. The mapping file names it.
  if (options_.mapping) {
    for (const auto& [signal, item] : options_.mapping->items)
      if (item == key || (!id.empty() && item == id)) {
        r.signal = signal;
        described = std::string(key) + " (mapping file)";
        const auto s = options_.mapping->scale.find(signal);
        if (s != options_.mapping->scale.end()) r.scale = s->second;
        return r;
      }
  }
  // 2. The device file describes it; 3. the log itself says its type; 4. its name as a type.
  ItemType t = known;
  std::string guessed;
  const DataItemInfo* info = nullptr;
  if (options_.devices) {
    const std::string& device_name = log_.devices[device];
    info = options_.devices->find(!id.empty() ? id : key, device_name);
    if (!info && !id.empty()) info = options_.devices->find(key, device_name);
  }
  if (info) {
    t = {info->type,  info->sub_type, info->component,     info->component_name,
         info->units, info->category, info->representation};
  } else if (t.type.empty()) {
    guessed = as_type_name(key);
    t.type = guessed;
  }
  if (t.category == "CONDITION")
    r.extra_fields = 4;
  else if (t.type == "MESSAGE")
    r.extra_fields = 1;
  else if (t.representation == "TIME_SERIES")
    r.extra_fields = 2;
  r.signal = signal_of(t.type, t.sub_type, t.component, t.component_name);
  described = std::string(key) + " (" + std::string(t.type) +
              (t.sub_type.empty() ? "" : " " + std::string(t.sub_type)) +
              (info || !guessed.empty() ? "" : ", from the log") +
              (!guessed.empty() ? ", from its name" : "") + ")";
  if (r.signal) {
    r.scale = unit_scale(t.units);
    if (options_.mapping) {
      const auto s = options_.mapping->scale.find(*r.signal);
      if (s != options_.mapping->scale.end()) r.scale = s->second;
      // The mapping gives this signal to another item: this one is not it.
      if (options_.mapping->items.count(*r.signal)) r.signal.reset();
    }
  }
  return r;
}

const ResolvedItem& ItemResolver::resolve(std::uint16_t device, std::string_view key,
                                          std::string_view id, const ItemType& known) {
  const auto cache_key = std::make_pair(device, std::string(!id.empty() ? id : key));
  if (auto it = cache_.find(cache_key); it != cache_.end()) return it->second;
  std::string described;
  ResolvedItem r = decide(device, key, id, known, described);
  if (log_.items.size() <= device) log_.items.resize(device + 1);
  if (r.signal) {
    std::string& owner = log_.items[device][static_cast<std::size_t>(*r.signal)];
    if (owner.empty()) {
      owner = described;
    } else if (owner != described) { // the same item read again from another file is no rival
      log_.unused_items.push_back(described + ": also a " +
                                  std::string(log_signal_name(*r.signal)) + ", " + owner +
                                  " is used");
      r.signal.reset();
    }
  } else if (std::find(log_.unused_items.begin(), log_.unused_items.end(), described) ==
             log_.unused_items.end()) {
    log_.unused_items.push_back(described);
  }
  return cache_.emplace(cache_key, r).first->second;
}

} // namespace ncjoule::logs_detail
