// [setup]: where the work sits in the machine, for programs that move in machine coordinates.
#include <cctype>

#include "sections.hpp"

namespace ncjoule {

namespace {
constexpr const char* kWorkOffsetNames[] = {"G54", "G55",   "G56",   "G57",  "G58",
                                            "G59", "G59.1", "G59.2", "G59.3"};
} // namespace

int work_offset_index(std::string_view name) {
  std::string upper;
  for (char c : name)
    if (c != ' ') upper += char(std::toupper(static_cast<unsigned char>(c)));
  for (int k = 0; k < 9; ++k)
    if (upper == kWorkOffsetNames[k]) return k + 1;
  // The additional offsets: "G54.1 P7" (Fanuc), "G154 P7" (Haas), "G110".."G129" (Haas P1-P20).
  int p = 0;
  for (std::string_view prefix : {"G54.1P", "G154P"}) {
    if (upper.rfind(prefix, 0) != 0) continue;
    const std::string digits = upper.substr(prefix.size());
    if (digits.empty() || digits.size() > 3 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      return 0;
    p = std::stoi(digits);
  }
  if (upper.size() == 4 && upper[0] == 'G' &&
      upper.find_first_not_of("0123456789", 1) == std::string::npos) {
    const int g = std::stoi(upper.substr(1));
    if (g >= 110 && g <= 129) p = g - 109;
  }
  return p >= 1 && p <= kAdditionalWorkOffsets ? 9 + p : 0;
}

std::string work_offset_name(int index) {
  if (index > 9 && index <= 9 + kAdditionalWorkOffsets)
    return "G54.1 P" + std::to_string(index - 9);
  return index >= 1 && index <= 9 ? kWorkOffsetNames[index - 1] : "G54";
}

} // namespace ncjoule

namespace ncjoule::profile_detail {
namespace {

// An array of `count` finite numbers, or the reason it is not.
std::optional<std::vector<double>> numbers(const toml::node* node, std::size_t count) {
  const toml::array* list = node ? node->as_array() : nullptr;
  if (!list || list->size() != count) return std::nullopt;
  std::vector<double> out;
  for (const toml::node& item : *list) {
    const std::optional<double> v = item.value<double>();
    // A coordinate beyond 100 m is no machine's (a slip of units or of typing).
    if (!v || !std::isfinite(*v) || std::abs(*v) > 1e5) return std::nullopt;
    out.push_back(*v);
  }
  return out;
}

} // namespace

std::map<int, Pose> read_work_offsets(const toml::table& table, const TableReader& owner,
                                      std::string_view key) {
  std::map<int, Pose> offsets;
  for (const auto& [name, value] : table) {
    const int index = work_offset_index(name.str());
    const std::string where = std::string(key) + "." + std::string(name.str());
    if (index == 0)
      owner.fail(where, "names no work offset: G54 to G59, G59.1 to G59.3, \"G54.1 P1\" to "
                        "\"G54.1 P300\" (Haas \"G154 P1\", G110 to G129)");
    const auto xyz = numbers(&value, 3);
    if (!xyz) owner.fail(where, "must be [X, Y, Z], the origin's machine coordinates in mm");
    if (offsets.count(index))
      owner.fail(where, "is " + work_offset_name(index) +
                            ", given twice (G110 to G129 are "
                            "G154 P1 to P20)");
    offsets[index] = Pose{(*xyz)[0], (*xyz)[1], (*xyz)[2], 0, 0, 0};
  }
  return offsets;
}

WorkSetup read_setup(TableReader t, std::vector<std::string>& sources) {
  WorkSetup setup;
  if (const auto source = t.optional_string("source")) sources.push_back("setup: " + *source);
  if (const auto above =
          t.optional_quantity("z_home_above_work", Dimension::Length, Range::NonNegative))
    setup.z_home_above_work_mm = *above;
  if (const auto units = t.optional_string("power_on_units")) {
    if (*units == "inch" || *units == "in")
      setup.power_on_inch = true;
    else if (*units == "mm")
      setup.power_on_inch = false;
    else
      t.fail("power_on_units", "must be \"mm\" or \"inch\" (the units a program that sets "
                               "neither G20 nor G21 runs in)");
  }
  if (const auto mode = t.optional_string("cutter_compensation")) {
    if (*mode == "control")
      setup.cutter_compensation = CutterCompMode::Control;
    else if (*mode == "wear")
      setup.cutter_compensation = CutterCompMode::Wear;
    else
      t.fail("cutter_compensation",
             "must be \"control\" (G41/G42 offset the part contour by the tool radius) or "
             "\"wear\" (the path is already the tool centre; G41/G42 add only a wear value)");
  }
  // The control's peck distances (Fanuc parameters 5114/5115, Haas setting 22, ...).
  if (const auto d = t.optional_quantity("peck_clearance", Dimension::Length, Range::NonNegative))
    setup.peck_clearance_mm = *d;
  if (const auto d =
          t.optional_quantity("chip_break_retract", Dimension::Length, Range::NonNegative))
    setup.chip_break_retract_mm = *d;
  if (const toml::node* node = t.raw("work_offsets_mm")) {
    const toml::table* table = node->as_table();
    if (!table) t.fail("work_offsets_mm", "must be a table: G54 = [X, Y, Z], ...");
    setup.work_offsets = read_work_offsets(*table, t, "work_offsets_mm");
  }
  if (const toml::node* node = t.raw("macro_dirs")) {
    const toml::array* list = node->as_array();
    if (!list) t.fail("macro_dirs", "must be a list of folders: [\"macros\", ...]");
    for (const toml::node& item : *list) {
      const std::optional<std::string> dir = item.value<std::string>();
      if (!dir || dir->empty()) t.fail("macro_dirs", "must be a list of folder names (strings)");
      setup.macro_dirs.push_back(*dir);
    }
  }
  if (const toml::node* node = t.raw("xy_home_in_work_mm")) {
    const auto xy = numbers(node, 2);
    if (!xy)
      t.fail("xy_home_in_work_mm",
             "must be [X, Y]: where machine X/Y home is in the program's work coordinates (mm)");
    setup.xy_home_in_work_mm = std::pair{(*xy)[0], (*xy)[1]};
  }
  if (const toml::node* node = t.raw("travel_mm")) {
    const toml::table* table = node->as_table();
    if (!table) t.fail("travel_mm", "must be a table: x = [MIN, MAX], y = ..., z = ...");
    std::array<std::pair<double, double>, 3> travel{};
    constexpr const char* axes[] = {"x", "y", "z"};
    for (std::size_t i = 0; i < 3; ++i) {
      const auto range = numbers(table->get(axes[i]), 2);
      const std::string where = std::string("travel_mm.") + axes[i];
      if (!range || !((*range)[0] < (*range)[1]))
        t.fail(where, "must be [MIN, MAX] in machine coordinates (mm), MIN below MAX");
      travel[i] = {(*range)[0], (*range)[1]};
    }
    if (table->size() != 3) t.fail("travel_mm", "takes x, y and z, nothing else");
    setup.travel = travel;
  }
  t.finish();
  return setup;
}

} // namespace ncjoule::profile_detail
