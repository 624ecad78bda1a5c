// Internal: the stock a CAM system states in the program's header. Such a stock is the one the
// toolpaths were computed for, so it comes before any guess from the cutting moves (and after
// every stock a user or a project file gives: docs/stock.md).
//
// Read, anywhere in the header (the first `max_lines` lines), in this order of preference:
//  - Carbide Create's "(stockMin:-150.00mm, -100.00mm, -8.00mm)" and "(stockMax:150.00mm,
//    100.00mm, 0.00mm)", and the same words spelt "STOCK MIN" / "STOCK MAX" with ':' or '='
//    (kind "stock-comment");
//  - Sinumerik's blank, WORKPIECE(,"",,"BOX",112,0,-50,-80,0,0,100,100): BOX (two corners) and
//    RECTANGLE (centred) blanks (kind "sinumerik-workpiece");
//  - the APT-style "(STOCK/BLOCK,300.00, 200.00, 8.00,150.00, 100.00, 8.00)" (size, then the
//    work origin from the stock's low corner; kind "stock-comment");
//  - Vectric's Material Size block, "( Material Size)" then "( X= 300.000, Y= 200.000, Z=
//    18.000)" on the next line, or "( Material Size: X= 300, Y= 200, Z= 18)" on one, placed by
//    its "( Z Origin for Material = Material Surface)" and "( XY Origin for Material = Bottom
//    Left Corner)" lines (kind "vectric");
//  - a size alone ("(STOCK 4.125 x 3.625 x 1.000)", "(STOCK SIZE: 100 X 60 X 20)"; kind
//    "stock-comment").
// A size without a stated place is placed where the cutting moves fit it (place_sized_stock in
// removal.hpp), and says so. Values without a unit are in the program's units.
#pragma once

#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include "ncjoule/gcode.hpp"
#include "ncjoule/removal.hpp"

namespace ncjoule::estimate_detail {

// The stock the first `max_lines` lines' comments state, values without a unit in the
// program's units; nullopt when they state none (or only one corner).
// A header's stock that cannot be used (a WORKPIECE blank of another shape, one that does not
// read) is a warning in `problems`, at its line and column, and the next is looked for.
std::optional<StockSpec> stock_from_cam_comments(const SourceFile& source, const Dialect& dialect,
                                                 std::size_t max_lines = 1000,
                                                 std::vector<Diagnostic>* problems = nullptr);

// One comment's corner: which (min or max) and its three lengths (exposed for tests).
struct StockCorner {
  bool is_max = false;
  std::pair<double, LengthUnit> xyz[3];
};
std::optional<StockCorner> stock_corner_of_comment(std::string_view comment);
// One comment's whole stock: STOCK/BLOCK or a size alone (exposed for tests).
std::optional<StockSpec> stock_box_of_comment(std::string_view comment);

// Three sizes keyed X, Y and Z ("X= 300.000, Y= 200.000, Z= 18.000", "X=12 x Y=8 x Z=1in"),
// each above 0 (exposed for tests).
std::optional<std::array<std::pair<double, LengthUnit>, 3>> xyz_sizes(std::string_view text);
// One of Vectric's origin lines: where Z0 is on the material, or which corner (or the centre)
// X0 Y0 is.
struct VectricOrigin {
  enum class Z { Top, Bottom, Centre };
  enum class Side { Low, Centre, High };
  bool is_z = false;
  Z z = Z::Top;
  Side x = Side::Low, y = Side::Low;
};
std::optional<VectricOrigin> vectric_origin(std::string_view comment);
// The material's box from its size and origins (a size only, placed later, without both).
std::optional<StockSpec>
vectric_material_box(const std::array<std::pair<double, LengthUnit>, 3>& size,
                     const std::optional<VectricOrigin>& xy, const std::optional<VectricOrigin>& z);
// The blank a line's code defines with WORKPIECE(...); std::nullopt without one, or with
// `problem` (and its column, 0-based) when it is one that cannot be used.
std::optional<StockSpec> sinumerik_workpiece(std::string_view code, std::string& problem,
                                             std::size_t& problem_column);

} // namespace ncjoule::estimate_detail
