// The work budgets (ncjoule/budget.hpp): a program that asks for more moves, path samples or
// removal work than allowed stops the run where the budget ran out, with an error that says which
// budget, the line, and how to raise it, and Estimate::budget_exceeded (not a program error).
// Each budget is set small here, so that the runs take milliseconds.
#include <doctest/doctest.h>

#include <string>

#include "estimate_checks.hpp"
#include "ncjoule/estimate.hpp"

using namespace ncjoule;
using namespace estimate_test;

namespace {

// A slot cut back and forth in a loop of `turns`, 6 mm tool, in a 100 x 20 stock.
SourceFile slot_loop(int turns) {
  return make_source("loop.ngc", "G21 G90 G17\n(T1 D=6. CR=0. - ZMIN=-1. - FLAT END MILL)\n"
                                 "T1 M6\nS8000 M3\nG0 X0 Y10 Z5\nG1 Z-1 F300\n"
                                 "o100 repeat [" +
                                     std::to_string(turns) +
                                     "]\nG1 X90 F1200\nG1 X0\no100 endrepeat\nG0 Z5\nM30\n");
}

EstimateOptions with_stock() {
  EstimateOptions options;
  options.stock = parse_stock_spec("box:-5,0,-5,95,20,0");
  return options;
}

// The one error of a stopped run.
const Diagnostic* stop_of(const Estimate& e) {
  for (const Diagnostic& d : e.diagnostics)
    if (d.severity == Severity::Error && d.message.find("budget") != std::string::npos) return &d;
  return nullptr;
}

} // namespace

TEST_CASE("within every budget the run is not stopped") {
  const Estimate e = estimate_program(slot_loop(3), generic(), with_stock());
  CHECK_FALSE(e.failed);
  CHECK_FALSE(e.budget_exceeded);
  CHECK(stop_of(e) == nullptr);
  CHECK(e.energy.removed_mm3 > 0);
}

TEST_CASE("the budget of moves stops a loop at the line that passed it") {
  EstimateOptions options = with_stock();
  options.limits.max_commands = 40; // the loop makes 2 moves a turn
  const Estimate e = estimate_program(slot_loop(1000000), generic(), options);
  CHECK(e.failed);
  CHECK(e.budget_exceeded);
  const Diagnostic* stop = stop_of(e);
  REQUIRE(stop != nullptr);
  CHECK(stop->file == "loop.ngc");
  CHECK((stop->line == 8 || stop->line == 9)); // a move of the loop's body
  CHECK(stop->message.find("more than 40 moves") != std::string::npos);
  CHECK(stop->message.find("--max-moves") != std::string::npos);
  CHECK(stop->message.find("max_moves") != std::string::npos);
}

TEST_CASE("the budget of path samples stops the stream") {
  EstimateOptions options = with_stock();
  const Estimate whole = estimate_program(slot_loop(20), generic(), options);
  REQUIRE_FALSE(whole.failed);
  options.max_path_samples = 500;
  const Estimate e = estimate_program(slot_loop(20), generic(), options);
  CHECK(e.failed);
  CHECK(e.budget_exceeded);
  const Diagnostic* stop = stop_of(e);
  REQUIRE(stop != nullptr);
  CHECK((stop->line == 8 || stop->line == 9));
  CHECK(stop->message.find("--max-path-samples") != std::string::npos);
  CHECK(stop->message.find("max_path_samples") != std::string::npos);
}

TEST_CASE("the budget of removal work stops removal before it cuts") {
  EstimateOptions options = with_stock();
  options.removal.grid_mm = 0.5;
  // 40 passes of 90 mm with a 6 mm tool on a 0.5 mm grid: about 40 x (90 + 6) x 6 / 0.25 =
  // 92,000 columns under the tool, and more with the steps' widths.
  options.max_removal_work = 20000;
  const Estimate e = estimate_program(slot_loop(20), generic(), options);
  CHECK(e.failed);
  CHECK(e.budget_exceeded);
  const Diagnostic* stop = stop_of(e);
  REQUIRE(stop != nullptr);
  CHECK((stop->line >= 6 && stop->line <= 9));
  CHECK(stop->message.find("--max-removal-work") != std::string::npos);
  CHECK(stop->message.find("max_removal_work") != std::string::npos);
  // Without removal there is no removal work to count.
  options.simulate_removal = false;
  const Estimate timed = estimate_program(slot_loop(20), generic(), options);
  CHECK_FALSE(timed.failed);
  CHECK_FALSE(timed.budget_exceeded);
}

TEST_CASE("a program error is not a budget") {
  // G81 L2.5 is one a control refuses: a failed estimate would still not be a stopped one.
  const Estimate e = estimate_program(
      make_source("l.ngc", "G21 G90\nG0 X0 Y0 Z5\nG91 G81 X10 Y0 Z-6 R-4 F100 L2.5\nG80\nM2\n"),
      generic(), [] {
        EstimateOptions o;
        o.simulate_removal = false;
        return o;
      }());
  CHECK_FALSE(e.budget_exceeded);
  CHECK(stop_of(e) == nullptr);
}
