// Which fields a block's comment holds (BlockFields in annotate.hpp): the compact style and the
// --fields list.
#include <cctype>

#include "ncjoule/annotate.hpp"

namespace ncjoule {

BlockFields compact_block_fields() {
  BlockFields f;
  f.power = false;      // E / T
  f.cumulative = false; // the running sum of T
  f.omit_zero = true;
  return f;
}

std::optional<BlockFields> parse_block_fields(std::string_view list,
                                              std::vector<Diagnostic>& diagnostics,
                                              const TextOrigin& origin) {
  BlockFields f;
  f.time = f.energy = f.power = f.mrr = f.cumulative = f.operation = false;
  bool any = false;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t end = std::min(list.find(',', begin), list.size());
    const std::size_t at = begin;
    std::string name;
    for (char c : list.substr(begin, end - begin))
      if (!std::isspace(static_cast<unsigned char>(c)))
        name += char(std::toupper(static_cast<unsigned char>(c)));
    begin = end + 1;
    if (name.empty()) continue;
    bool* field = name == "T"     ? &f.time
                  : name == "E"   ? &f.energy
                  : name == "P"   ? &f.power
                  : name == "MRR" ? &f.mrr
                  : name == "CUM" ? &f.cumulative
                  : name == "OP"  ? &f.operation
                                  : nullptr;
    if (!field) {
      diagnostics.push_back(
          origin.at(at, "'" + name + "' is not a field: give some of T, E, P, MRR, CUM, OP"));
      return std::nullopt;
    }
    *field = any = true;
  }
  if (!any) {
    diagnostics.push_back(origin.at(0, "no field given: give some of T, E, P, MRR, CUM, OP"));
    return std::nullopt;
  }
  return f;
}

} // namespace ncjoule
