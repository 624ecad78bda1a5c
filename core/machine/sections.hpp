// The two halves of a profile: what the machine can do, and what it draws.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ncjoule/machine.hpp"
#include "table_reader.hpp"

namespace ncjoule::profile_detail {

// [kinematics] with its [kinematics.x], [kinematics.y], [kinematics.z] and optional
// [kinematics.rotary] tables. Each table's `source` is appended to sources.
Kinematics read_kinematics(TableReader kinematics, std::vector<std::string>& sources);

// [power] with [power.pavanaskar] and/or [power.zhou], as its `model` needs them.
PowerConstants read_power(TableReader power, std::vector<std::string>& sources);

// [default_tool]: type = "flat" | "ball" | "bullnose" | "drill" | "chamfer", diameter_mm, and
// corner_radius_mm, point_angle_deg, tip_diameter_mm as the type needs them.
Tool read_default_tool(TableReader tool, std::vector<std::string>& sources);

// [setup]: z_home_above_work_mm, power_on_units, work_offsets_mm = { G54 = [X, Y, Z], ... },
// travel_mm = { x = [MIN, MAX], y = ..., z = ... }; every key optional.
WorkSetup read_setup(TableReader setup, std::vector<std::string>& sources);
// A table of work offsets (G54 = [X, Y, Z], ...) in machine coordinates, mm; errors are reported
// against `owner` under `key`.
std::map<int, Pose> read_work_offsets(const toml::table& table, const TableReader& owner,
                                      std::string_view key);

// Reads the table's `source` string and records it as "<table>: <source>".
void read_source(TableReader& table, std::string_view table_name,
                 std::vector<std::string>& sources);

} // namespace ncjoule::profile_detail
