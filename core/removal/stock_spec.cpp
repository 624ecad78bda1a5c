// What stock the user asked for, and the default: the bounding box of the cutting moves.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

#include "ncjoule/removal.hpp"
#include "ncjoule/text.hpp"

namespace ncjoule {

std::optional<std::pair<double, LengthUnit>> parse_length(std::string_view text) {
  const std::string_view t = trim(text);
  LengthUnit unit = LengthUnit::Program;
  std::string_view number = t;
  const std::string low = to_lower(t);
  for (const auto& [suffix, u] : {std::pair<std::string_view, LengthUnit>{"inch", LengthUnit::Inch},
                                  {"in", LengthUnit::Inch},
                                  {"\"", LengthUnit::Inch},
                                  {"mm", LengthUnit::Mm}}) {
    if (low.size() > suffix.size() &&
        low.compare(low.size() - suffix.size(), suffix.size(), suffix.data(), suffix.size()) == 0) {
      unit = u;
      number = trim(t.substr(0, t.size() - suffix.size()));
      break;
    }
  }
  const std::optional<double> value = parse_number(number);
  if (!value) return std::nullopt;
  return std::pair{*value, unit};
}

std::optional<StockSpec> parse_stock_spec(std::string_view text,
                                          std::vector<Diagnostic>* diagnostics,
                                          const TextOrigin& origin, LengthUnit units) {
  // A problem with the part of `text` at `where`, or with the whole text.
  auto fail = [&](std::string message, std::string_view where = {}) -> std::optional<StockSpec> {
    const std::size_t offset = where.data() ? std::size_t(where.data() - text.data()) : 0;
    if (diagnostics) diagnostics->push_back(origin.at(offset, std::move(message)));
    return std::nullopt;
  };
  StockSpec spec;
  spec.origin = origin.file;
  const std::string low = to_lower(text);
  if (low.empty() || low == "auto" || low == "default") return spec;
  if (low.rfind("box:", 0) == 0) {
    double v[6];
    std::string_view rest = text.substr(4);
    for (int k = 0; k < 6; ++k) {
      const std::size_t comma = rest.find(',');
      if ((k < 5) != (comma != std::string_view::npos))
        return fail("stock box needs six numbers: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (each may "
                    "carry a unit, mm or in; without one, the program's units)",
                    rest);
      const std::string_view field = rest.substr(0, comma);
      const auto length = parse_length(field);
      if (!length)
        return fail("stock box value '" + std::string(field) +
                        "' is not a number (with an optional unit: mm, in)",
                    field);
      v[k] = length->first;
      spec.box_units[std::size_t(k)] =
          length->second == LengthUnit::Program ? units : length->second;
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }
    spec.kind = StockSpec::Kind::Box;
    spec.box = Box3{v[0], v[1], v[2], v[3], v[4], v[5]};
    // Compared in one unit: a box written in two units ("0,0,-1in,100mm,...") is checked so.
    const StockSpec mm = spec.in_mm(false);
    if (mm.box.empty()) return fail("stock box has a maximum not above its minimum");
    return spec;
  }
  if (low.size() > 4 && low.compare(low.size() - 4, 4, ".stl") == 0) {
    spec.kind = StockSpec::Kind::Stl;
    spec.stl_path = std::string(text);
    spec.stl_units = units;
    return spec;
  }
  return fail("stock '" + std::string(text) +
              "' is neither box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX nor an .stl file");
}

StockSpec StockSpec::in_mm(bool program_inch) const {
  auto scale = [&](LengthUnit u) {
    const bool inch = u == LengthUnit::Inch || (u == LengthUnit::Program && program_inch);
    return inch ? 25.4 : 1.0;
  };
  StockSpec out = *this;
  double* values[6] = {&out.box.xmin, &out.box.ymin, &out.box.zmin,
                       &out.box.xmax, &out.box.ymax, &out.box.zmax};
  for (std::size_t k = 0; k < 6; ++k) {
    *values[k] *= scale(box_units[k]);
    out.box_units[k] = LengthUnit::Mm;
  }
  if (kind == Kind::Stl && scale(stl_units) != 1.0)
    out.stl_units = LengthUnit::Inch;
  else
    out.stl_units = LengthUnit::Mm;
  return out;
}

bool StockSpec::follows_program_units() const {
  if (kind == Kind::Stl) return stl_units == LengthUnit::Program;
  if (kind != Kind::Box) return false;
  // A 0 is 0 in any unit: "box:0,0,-1in,4in,3in,0" is all in inches.
  const double values[6] = {box.xmin, box.ymin, box.zmin, box.xmax, box.ymax, box.zmax};
  for (std::size_t k = 0; k < 6; ++k)
    if (box_units[k] == LengthUnit::Program && values[k] != 0) return true;
  return false;
}

Box3 place_sized_stock(const Box3& size, const std::optional<Box3>& cuts, std::string& how) {
  const double extent[3] = {size.xmax - size.xmin, size.ymax - size.ymin, size.zmax - size.zmin};
  // How much of [lo, hi] lies outside [a, b].
  const auto outside = [](double lo, double hi, double a, double b) {
    return std::max(0.0, a - lo) + std::max(0.0, hi - b);
  };
  double lo[3], hi[3];
  how.clear();
  static const char* const names[] = {"X", "Y"};
  for (int i = 0; i < 2; ++i) {
    const double w = extent[i];
    const double starts[3] = {0, -w / 2, -w};
    static const char* const placed[] = {" from 0", " centred", " up to 0"};
    int best = 0;
    if (cuts) {
      const double c_lo = i == 0 ? cuts->xmin : cuts->ymin, c_hi = i == 0 ? cuts->xmax : cuts->ymax;
      double least = outside(c_lo, c_hi, starts[0], starts[0] + w);
      for (int k = 1; k < 3; ++k)
        if (const double o = outside(c_lo, c_hi, starts[k], starts[k] + w); o < least - 1e-9)
          least = o, best = k;
    }
    lo[i] = starts[best], hi[i] = starts[best] + w;
    how += std::string(i ? ", " : "") + names[i] + placed[best];
  }
  const double h = extent[2];
  const bool above = cuts && cuts->zmin >= 0; // nothing cuts below Z0: Z0 is the stock's bottom
  lo[2] = above ? 0 : -h, hi[2] = above ? h : 0;
  how += above ? ", bottom at Z0" : ", top at Z0";
  return Box3{lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
}

std::string stock_mismatch(const Box3& stock, const Box3& cuts, const StockSpec& spec,
                           bool program_inch) {
  const double stock_size = std::max(stock.xmax - stock.xmin, stock.ymax - stock.ymin);
  const double cut_size = std::max(cuts.xmax - cuts.xmin, cuts.ymax - cuts.ymin);
  // Seen from above: a program that cuts above its stock only (air) is another matter.
  const bool overlaps = stock.xmin < cuts.xmax && cuts.xmin < stock.xmax &&
                        stock.ymin < cuts.ymax && cuts.ymin < stock.ymax;
  constexpr double kFactor = 20;
  const double ratio = cut_size > 0 ? stock_size / cut_size : 1;
  if (overlaps && ratio <= kFactor && ratio >= 1 / kFactor) return {};
  char what[200];
  if (ratio > kFactor || ratio < 1 / kFactor)
    std::snprintf(what, sizeof what,
                  "the stock is %.3g times %s than the program's cuts (%.1f mm across, the cuts "
                  "%.1f mm)",
                  ratio > 1 ? ratio : 1 / ratio, ratio > 1 ? "larger" : "smaller", stock_size,
                  cut_size);
  else
    std::snprintf(what, sizeof what,
                  "the stock (X%.1f..%.1f Y%.1f..%.1f mm) is beside the program's cuts "
                  "(X%.1f..%.1f Y%.1f..%.1f mm), not under them",
                  stock.xmin, stock.xmax, stock.ymin, stock.ymax, cuts.xmin, cuts.xmax, cuts.ymin,
                  cuts.ymax);
  std::string out = what;
  if (spec.follows_program_units())
    out += std::string(": a mix-up of units? Values written without a unit are read in the "
                       "program's units (") +
           (program_inch ? "inches, G20" : "mm") +
           "); write 'in' or 'mm' after a number (box:0,0,-1in,4in,3in,0)";
  else
    out += ": a mix-up of units, or a stock for another work offset?";
  return out;
}

} // namespace ncjoule
