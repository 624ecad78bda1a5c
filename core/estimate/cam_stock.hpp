// Internal: the stock a CAM system states in the program's header comments. Such a stock is
// the one the toolpaths were computed for, so it comes before any guess from the cutting moves.
//
// Read: Carbide Create's "(stockMin:-150.00mm, -100.00mm, -8.00mm)" and
// "(stockMax:150.00mm, 100.00mm, 0.00mm)", and the same words spelt "STOCK MIN" / "STOCK MAX"
// with ':' or '='; the APT-style "(STOCK/BLOCK,300.00, 200.00, 8.00,150.00, 100.00, 8.00)"
// (size, then the work origin from the stock's low corner); and a size alone ("(STOCK 4.125 x
// 3.625 x 1.000)", "(STOCK SIZE: 100 X 60 X 20)"), which says not where the stock sits: it is
// placed where the cutting moves fit it (place_sized_stock in removal.hpp), and says so.
#pragma once

#include <optional>
#include <string_view>

#include "ncjoule/gcode.hpp"
#include "ncjoule/removal.hpp"

namespace ncjoule::estimate_detail {

// The stock the first `max_lines` lines' comments state, values without a unit in the
// program's units; nullopt when they state none (or only one corner).
std::optional<StockSpec> stock_from_cam_comments(const SourceFile& source, const Dialect& dialect,
                                                 std::size_t max_lines = 200);

// One comment's corner: which (min or max) and its three lengths (exposed for tests).
struct StockCorner {
  bool is_max = false;
  std::pair<double, LengthUnit> xyz[3];
};
std::optional<StockCorner> stock_corner_of_comment(std::string_view comment);
// One comment's whole stock: STOCK/BLOCK or a size alone (exposed for tests).
std::optional<StockSpec> stock_box_of_comment(std::string_view comment);

} // namespace ncjoule::estimate_detail
