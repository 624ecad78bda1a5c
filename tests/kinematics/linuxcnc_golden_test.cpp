// The "linuxcnc-2.9" junction rule against LinuxCNC 2.9's own planner: per-line times measured
// with LinuxCNC run headless (tests/kinematics/linuxcnc/*.lcnc.csv, made by the lcnc-time tool
// that bench/linuxcnc_time.sh uses) on programs written to exercise its rules
// (make_programs.py). The targets are those of docs/timing-vs-linuxcnc.md: the total within 1%,
// the 95th percentile of the per-line error (lines over 0.1 s) within 3%.
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "ncjoule/kinematics.hpp"

namespace fs = std::filesystem;
using namespace ncjoule;

namespace {

const fs::path kFolder = fs::path(NCJOULE_SOURCE_DIR) / "tests" / "kinematics" / "linuxcnc";

// The machine lcnc-time simulates: trivkins XYZ, 100 mm/s and 1000 mm/s^2 per axis.
MachineProfile linuxcnc_sim() {
  MachineProfile m;
  m.name = "LinuxCNC 2.9 simulation";
  for (AxisLimits& a : m.kinematics.axes) {
    a.rapid_mm_s = a.max_feed_mm_s = 100;
    a.accel_mm_s2 = 1000;
  }
  m.kinematics.junction_rule = JunctionRule::LinuxCnc29;
  m.kinematics.path_tolerance_mm = 0;
  return m;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// line (1-based) -> seconds, from the "line,seconds,..." CSV lcnc-time writes.
std::map<int, double> linuxcnc_lines(const fs::path& csv) {
  std::map<int, double> out;
  std::istringstream in(read(csv));
  std::string row;
  std::getline(in, row); // header
  while (std::getline(in, row)) {
    std::istringstream fields(row);
    std::string line, seconds;
    std::getline(fields, line, ',');
    std::getline(fields, seconds, ',');
    if (!line.empty()) out[std::stoi(line)] += std::stod(seconds);
  }
  return out;
}

struct Comparison {
  double linuxcnc_s = 0, ncjoule_s = 0, p95 = 0, worst = 0;
  int lines = 0; // compared lines (over 0.1 s in LinuxCNC)
};

// As bench/linuxcnc_time.py: ncjoule's time on lines LinuxCNC does not list goes to the next
// line it lists.
Comparison compare(const std::string& name) {
  const std::map<int, double> lcnc = linuxcnc_lines(kFolder / (name + ".lcnc.csv"));
  REQUIRE(!lcnc.empty());
  const Toolpath path = interpret(make_source(name, read(kFolder / (name + ".ngc"))));
  const Timeline t = plan(path.commands, linuxcnc_sim());
  std::map<int, double> ours;
  for (const TimedCommand& c : t.commands)
    ours[c.line + 1] += c.duration_s;
  std::map<int, double> folded;
  for (const auto& [line, s] : ours) {
    auto it = lcnc.lower_bound(line);
    if (it == lcnc.end()) it = std::prev(lcnc.end());
    folded[it->first] += s;
  }
  Comparison c;
  std::vector<double> errors;
  for (const auto& [line, s] : lcnc) {
    c.linuxcnc_s += s;
    if (s > 0.1) errors.push_back(std::abs(folded[line] - s) / s);
  }
  c.ncjoule_s = t.total_s;
  std::sort(errors.begin(), errors.end());
  if (!errors.empty()) {
    const double k = 0.95 * (errors.size() - 1);
    const std::size_t lo = static_cast<std::size_t>(k), hi = std::min(lo + 1, errors.size() - 1);
    c.p95 = errors[lo] + (errors[hi] - errors[lo]) * (k - lo);
    c.worst = errors.back();
  }
  c.lines = static_cast<int>(errors.size());
  return c;
}

void check(const std::string& name, double p95_target = 0.03) {
  CAPTURE(name);
  const Comparison c = compare(name);
  CAPTURE(c.linuxcnc_s);
  CAPTURE(c.ncjoule_s);
  CAPTURE(c.worst);
  CHECK(c.lines > 0);
  CHECK(std::abs(c.ncjoule_s - c.linuxcnc_s) / c.linuxcnc_s < 0.01);
  CHECK(c.p95 < p95_target);
}

} // namespace

TEST_CASE("linuxcnc-2.9 rule against LinuxCNC: corners under G64, G64 P, G61, G61.1") {
  check("corners");
}
TEST_CASE("linuxcnc-2.9 rule against LinuxCNC: 3D surfacing with 0.4 mm segments") {
  check("surface");
}
TEST_CASE("linuxcnc-2.9 rule against LinuxCNC: engraving with plunges, spindle, coolant") {
  check("engrave");
}
TEST_CASE("linuxcnc-2.9 rule against LinuxCNC: line-arc and arc-arc joins, helices") {
  check("arcs");
}
TEST_CASE("linuxcnc-2.9 rule against LinuxCNC: naive-CAM merging under G64 P Q") {
  check("naivecam");
}
TEST_CASE("linuxcnc-2.9 rule against LinuxCNC: corner arcs split between two naive-CAM moves") {
  // The total as LinuxCNC's. Per line, LinuxCNC lists an arc's second half on the last line of
  // the move it ends up in; ncjoule keeps it on the arc: lines differ by up to 8% where the
  // corner radius changes, so the per-line target is wider here.
  check("splitarcs", 0.08);
}
TEST_CASE("linuxcnc-2.9 rule against LinuxCNC: codes that stop the path and codes that do not") {
  check("stops");
}
TEST_CASE("linuxcnc-2.9 rule against LinuxCNC: moves of a few servo cycles") {
  check("short");
}
