// ncjoule stage 6: reports. The results of an estimate as JSON (docs/json.md).
#pragma once

#include <string>

#include "ncjoule/estimate.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule {

// The whole estimate as one JSON document; `indent` as nlohmann::json::dump (-1: one line).
std::string estimate_json(const Estimate& estimate, const MachineProfile& machine, int indent = 1);

} // namespace ncjoule
