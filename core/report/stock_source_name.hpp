// The word the JSON's `stock` fields and the CSV's stock column give a stock's source.
#pragma once

#include "ncjoule/removal.hpp"

namespace ncjoule::report_detail {

inline const char* stock_source_name(StockSource source) {
  switch (source) {
  case StockSource::Given:
    return "given";
  case StockSource::Program:
    return "program";
  case StockSource::Guessed:
    return "guessed";
  case StockSource::None:
    break;
  }
  return "none";
}

} // namespace ncjoule::report_detail
