// A box of stock: every column inside the box holds one interval.
#include <cstdio>

#include "ncjoule/removal.hpp"

namespace ncjoule {
namespace {

class BoxStock final : public StockShape {
public:
  BoxStock(const Box3& box, std::string description)
      : box_(box), description_(std::move(description)) {}
  Box3 bounds() const override { return box_; }
  std::string description() const override { return description_; }

  void fill_columns(const GridFrame& grid, std::vector<std::uint32_t>& first,
                    std::vector<ZInterval>& intervals) const override {
    first.assign(grid.columns() + 1, 0);
    intervals.clear();
    intervals.reserve(grid.columns());
    for (int j = 0; j < grid.ny; ++j) {
      const double y = grid.column_y(j);
      for (int i = 0; i < grid.nx; ++i) {
        const std::size_t c = std::size_t(j) * grid.nx + i;
        const double x = grid.column_x(i);
        if (x >= box_.xmin && x < box_.xmax && y >= box_.ymin && y < box_.ymax)
          intervals.push_back({box_.zmin, box_.zmax});
        first[c + 1] = std::uint32_t(intervals.size());
      }
    }
  }

private:
  Box3 box_;
  std::string description_;
};

} // namespace

std::unique_ptr<StockShape> make_box_stock(const Box3& box, std::string description) {
  return std::make_unique<BoxStock>(box, std::move(description));
}

} // namespace ncjoule
