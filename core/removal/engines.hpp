// Constructors of the two removal engines (see make_removal_engine).
#pragma once

#include <memory>

#include "ncjoule/removal.hpp"

namespace ncjoule::detail {

std::unique_ptr<RemovalEngine> make_dexel_engine(const StockShape& stock, const GridFrame& grid);
std::unique_ptr<RemovalEngine> make_voxel_engine(const StockShape& stock, const GridFrame& grid);

} // namespace ncjoule::detail
