// The budget of moves (InterpreterLimits::max_commands): every way a short program has to make
// millions of moves (a spline flattened into thousands of feeds, a canned cycle's L, in a loop)
// stops at the budget, with an error that says how to raise it; InterpretResult::commands is
// then over the budget (how callers tell the stop). The budgets here are small: the runs take
// milliseconds.
#include <doctest/doctest.h>

#include <string>

#include "ncjoule/gcode.hpp"

using namespace ncjoule;

namespace {

InterpretResult run(const std::string& text, std::size_t max_commands, std::size_t* emitted) {
  InterpreterOptions options;
  options.max_commands = max_commands;
  *emitted = 0;
  return interpret(make_source("budget.ngc", text), options,
                   [emitted](const CanonCommand&) { ++*emitted; });
}

const Diagnostic* budget_error(const InterpretResult& r) {
  for (const Diagnostic& d : r.diagnostics)
    if (d.severity == Severity::Error && d.message.find("--max-moves") != std::string::npos)
      return &d;
  return nullptr;
}

} // namespace

TEST_CASE("a spline with far control points in a loop stops at the budget of moves") {
  std::size_t emitted = 0;
  const InterpretResult r = run("G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z-1 F500\n"
                                "o100 repeat [1000000]\n"
                                "G5 X10 Y0 I5000 J5000 P5000 Q-5000\n"
                                "G5 X0 Y0 I-5000 J5000 P-5000 Q-5000\n"
                                "o100 endrepeat\nM2\n",
                                5000, &emitted);
  CHECK(r.commands > 5000);
  CHECK(emitted == 5000);
  const Diagnostic* d = budget_error(r);
  REQUIRE(d != nullptr);
  CHECK(d->line == 5); // the first spline already makes 10,000 feeds
  CHECK(d->message.find("more than 5000 moves") != std::string::npos);
  CHECK(d->message.find("max_moves") != std::string::npos);
}

TEST_CASE("a canned cycle's L in a loop stops at the budget of moves") {
  std::size_t emitted = 0;
  const InterpretResult r = run("G21 G90\nG0 X0 Y0 Z5\no100 repeat [1000000]\n"
                                "G91 G81 X1 Y0 Z-1 R1 F100 L100000\nG80 G90\no100 endrepeat\nM2\n",
                                2000, &emitted);
  CHECK(r.commands > 2000);
  CHECK(emitted == 2000);
  const Diagnostic* d = budget_error(r);
  REQUIRE(d != nullptr);
  CHECK(d->line == 4);
}

TEST_CASE("a program within the budget of moves runs whole") {
  std::size_t emitted = 0;
  const InterpretResult r =
      run("G21 G90\nG0 X0 Y0 Z5\no100 repeat [100]\nG1 X1 F100\nG1 X0\no100 endrepeat\nM2\n", 1000,
          &emitted);
  CHECK(r.commands <= 1000);
  CHECK(budget_error(r) == nullptr);
  CHECK(r.program_end);
  CHECK(emitted >= 200);
}
