// Programs of a few KB built to nest as deep as they can (brackets, signs, parameter references,
// functions, control flow, calls) are interpreted on a thread with a 256 KiB stack, half what a
// host program's threads may have (macOS gives 512 KiB): each ends with an error or runs, and the
// thread returns. Deep nesting once recursed per byte of input and overflowed such a stack.
#include <doctest/doctest.h>
#include <pthread.h>

#include <string>

#include "program_runner.hpp"

using namespace ncjoule;
using namespace ncjoule::test;

namespace {

constexpr std::size_t kStackBytes = 256 * 1024;

struct Job {
  std::string text;
  Toolpath result;
};

void* interpret_job(void* arg) {
  Job& job = *static_cast<Job*>(arg);
  job.result = run(job.text);
  return nullptr;
}

// Interprets `text` on a thread of its own with a kStackBytes stack (std::thread cannot set it).
Toolpath run_on_small_stack(const std::string& text) {
  Job job{text, {}};
  pthread_attr_t attr;
  REQUIRE(pthread_attr_init(&attr) == 0);
  REQUIRE(pthread_attr_setstacksize(&attr, kStackBytes) == 0);
  pthread_t thread;
  REQUIRE(pthread_create(&thread, &attr, interpret_job, &job) == 0);
  REQUIRE(pthread_join(thread, nullptr) == 0);
  pthread_attr_destroy(&attr);
  return std::move(job.result);
}

std::string repeated(const std::string& unit, std::size_t times) {
  std::string out;
  out.reserve(unit.size() * times);
  for (std::size_t i = 0; i < times; ++i)
    out += unit;
  return out;
}

// One line of G-code moving X to `value`, and the end of the program.
std::string move_to(const std::string& value) {
  return "G21 G90\nG0 X" + value + "\nM2\n";
}

} // namespace

TEST_CASE("expressions nested as deep as a few KB allow end in an error on a 256 KiB stack") {
  struct Case {
    std::string name;
    std::string text;
  };
  const std::size_t n = 3000;
  const Case cases[] = {
      {"brackets", move_to(repeated("[", n) + "1" + repeated("]", n))},
      {"functions", move_to(repeated("sin[", n) + "1" + repeated("]", n))},
      {"parameter references in brackets", move_to(repeated("#[", n) + "1" + repeated("]", n))},
      {"brackets after signs", move_to(repeated("-[", n) + "1" + repeated("]", n))},
      {"powers of brackets", move_to(repeated("[2**", n) + "1" + repeated("]", n))},
      {"atan of atan", move_to(repeated("atan[", n) + "1" + repeated("]/[1]", n))},
      {"an o-word condition",
       "G21\no1 if [" + repeated("[", n) + "1" + repeated("]", n) + "]\nG0 X1\no1 endif\nM2\n"},
      {"a call's argument", "o<s> sub\no<s> endsub\no<s> call [" + repeated("[", n) + "1" +
                                repeated("]", n) + "]\nM2\n"},
      {"an assignment", "#1=" + repeated("[", n) + "1" + repeated("]", n) + "\nM2\n"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const Toolpath p = run_on_small_stack(c.text);
    CHECK(errors(p) >= 1);
    bool said = false;
    for (const Diagnostic& d : p.result.diagnostics)
      said = said || d.message.find("nested more than") != std::string::npos;
    CHECK(said);
  }
  // Never closed: the lexer finds no value for the word (a warning), nothing is evaluated.
  const Toolpath p = run_on_small_stack(move_to(repeated("[", n) + "1"));
  CHECK(warnings(p) >= 1);
}

TEST_CASE("chains of signs and parameter references take no stack per link") {
  const std::size_t n = 200'000;
  // An even number of minus signs: +1. With blanks, as a program may write them.
  Toolpath p = run_on_small_stack(move_to(repeated("- ", n) + "1"));
  CHECK(errors(p) == 0);
  REQUIRE(move_commands(p).size() == 1);
  CHECK(move_commands(p)[0].end.x == 1.0);
  p = run_on_small_stack(move_to(repeated("-", n + 1) + "[2]"));
  REQUIRE(move_commands(p).size() == 1);
  CHECK(move_commands(p)[0].end.x == -2.0);
  // #1 holds 1, so ###...#1 is 1 however many times it is read.
  p = run_on_small_stack("#1=1\n" + move_to(repeated("#", n) + "1"));
  REQUIRE(move_commands(p).size() == 1);
  CHECK(move_commands(p)[0].end.x == 1.0);
  p = run_on_small_stack("#1=1\n" + move_to(repeated("-#", n) + "1"));
  CHECK(move_commands(p).size() + errors(p) >= 1); // -#-#...: #-1 is an error
  // A word the lexer has to measure before anything is evaluated.
  p = run_on_small_stack(move_to(repeated("+", n) + repeated("#", n) + "<x>"));
  CHECK(errors(p) == 1); // #<x> is read before it is set
}

TEST_CASE("control flow and calls nested as deep as a program asks stay on the heap") {
  const std::size_t n = 3000;
  std::string ifs, whiles, endifs, endwhiles;
  for (std::size_t i = 0; i < n; ++i) {
    ifs += "o" + std::to_string(i) + " if [1]\n";
    endifs = "o" + std::to_string(i) + " endif\n" + endifs;
    whiles += "o" + std::to_string(n + i) + " while [0]\n";
    endwhiles = "o" + std::to_string(n + i) + " endwhile\n" + endwhiles;
  }
  Toolpath p = run_on_small_stack("G21\n" + ifs + "G0 X1\n" + endifs + "M2\n");
  CHECK(errors(p) == 0);
  CHECK(move_commands(p).size() == 1);
  p = run_on_small_stack("G21\n" + whiles + "G0 X1\n" + endwhiles + "G0 X2\nM2\n");
  CHECK(errors(p) == 0);
  CHECK(move_commands(p).size() == 1);
  // A subroutine that calls itself: refused past the call depth, not run until the stack ends.
  p = run_on_small_stack("o<r> sub\nG0 X1\no<r> call\no<r> endsub\no<r> call\nM2\n");
  CHECK(errors(p) >= 1);
  // The same with Fanuc's M98.
  Toolpath f = run("O1000\nM98 P2000\nM30\nO2000\nG0 X1\nM98 P2000\nM99\n", "fanuc");
  CHECK(errors(f) >= 1);
}
