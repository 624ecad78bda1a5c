// The JSON of an estimate, as fast as it is made and the same whichever way it is made: the
// pipeline's stages run at once or one after the other give the same bytes; blocks formatted in
// pieces on all cores give the bytes of one writer; the compact form holds the same numbers as
// the full one.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "json_writer.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/report.hpp"
#include "ncjoule/text_file.hpp"

using namespace ncjoule;
using report_detail::JsonWriter;

namespace {

MachineProfile generic() {
  return load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/generic-3axis.toml");
}

SourceFile sample(const std::string& name) {
  std::vector<Diagnostic> diagnostics;
  const std::string path = std::string(NCJOULE_SOURCE_DIR) + "/samples/programs/" + name;
  auto text = read_text_file(path, "an NC program", diagnostics, std::size_t(1) << 30, "");
  REQUIRE(text);
  return make_source(name, std::move(*text));
}

// Pockets with two tools, arcs, a subprogram called twice and a loop: some thousands of
// commands, so that every stage hands many batches on.
SourceFile busy_program() {
  std::string s = "%\n(T1 D=6. CR=0. - FLAT END MILL)\n(T2 D=4. CR=2. - BALL END MILL)\n"
                  "G21 G90 G17 G64 P0.01\no100 sub\nG1 Z-1 F300\n";
  for (int i = 0; i < 300; ++i) {
    char line[96];
    std::snprintf(line, sizeof line, "G1 X%.3f Y%.3f F1200\n", 10 + (i * 37 % 800) / 10.0,
                  10 + (i * 53 % 400) / 10.0);
    s += line;
    if (i % 25 == 0) s += "G2 X" + std::to_string(20 + i % 40) + " Y20 R15\n";
  }
  s += "G0 Z5\no100 endsub\n"
       "T1 M6\nS9000 M3\nG0 X10 Y10 Z5\no100 call\n#1 = 0\no200 while [#1 LT 3]\n"
       "G1 X[20 + #1 * 10] Y30 Z-0.5 F800\nG1 X60 Y30\n#1 = [#1 + 1]\no200 endwhile\n"
       "M5\nT2 M6\nS12000 M3\nG0 X10 Y10 Z5\no100 call\nG4 P0.5\nM5\nM30\n%\n";
  return make_source("busy.ngc", std::move(s));
}

std::string json_of(const SourceFile& source, const MachineProfile& machine,
                    EstimateOptions options, bool compact = false) {
  const Estimate e = estimate_program(source, machine, options);
  std::ostringstream out;
  if (compact)
    write_estimate_json_compact(out, e, machine);
  else
    write_estimate_json(out, e, machine);
  return out.str();
}

} // namespace

TEST_CASE("the pipeline's stages run at once or one after the other give the same bytes") {
  const MachineProfile machine = generic();
  EstimateOptions options;
  options.stock = parse_stock_spec("box:0,0,-20,100,60,0");
  int compared = 0;
  for (const SourceFile& source : {sample("bracket-linuxcnc.ngc"),
                                   sample("pavanaskar-pocket-spiral-in.ngc"), busy_program()}) {
    for (const bool removal : {true, false}) {
      options.simulate_removal = removal;
      options.overlap_stages = true;
      const std::string overlapped = json_of(source, machine, options);
      options.overlap_stages = false;
      const std::string sequential = json_of(source, machine, options);
      CHECK(overlapped.size() > 2000);
      CHECK(overlapped == sequential);
      ++compared;
    }
  }
  CHECK(compared == 6);
}

TEST_CASE("a program with errors gives the same diagnostics and numbers either way") {
  const MachineProfile machine = generic();
  // An unknown word, an arc that cannot close and a G-code no control has, between good moves.
  const SourceFile source = make_source(
      "bad.ngc", "G21 G90\nT1 M6\nS5000 M3\nG1 X10 Y10 Z-1 F500\nG1 X20 Q@\nG2 X30 Y10 R1\n"
                 "G1 X40\nG987\nG1 X50 Y20\nM30\n");
  EstimateOptions options;
  options.overlap_stages = true;
  const std::string overlapped = json_of(source, machine, options);
  options.overlap_stages = false;
  CHECK(overlapped == json_of(source, machine, options));
  CHECK(overlapped.find("\"severity\":") != std::string::npos);
}

TEST_CASE("elements formatted in pieces on all cores are the bytes of one writer") {
  // More elements than several pieces, strings that need escapes, and the array's neighbours.
  auto element = [](JsonWriter& w, std::size_t i) {
    w.begin_object_on_one_line();
    w.field("i", i);
    w.field("x", double(i) / 7);
    w.field("f", float(i) * 0.1f);
    w.field("name", i % 97 == 0 ? std::string("quote \" and \\ and \x01") : "plain");
    w.end_object();
  };
  for (const int indent : {1, 0}) {
    for (const std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(5000)}) {
      std::ostringstream pieces, one;
      {
        JsonWriter w(pieces, indent);
        w.begin_object();
        w.field("before", 1);
        w.key("list");
        w.begin_array();
        w.elements(count, element);
        w.end_array();
        w.field("after", 2);
        w.end_object();
        w.end_document(indent > 0);
      }
      {
        JsonWriter w(one, indent);
        w.begin_object();
        w.field("before", 1);
        w.key("list");
        w.begin_array();
        for (std::size_t i = 0; i < count; ++i)
          element(w, i);
        w.end_array();
        w.field("after", 2);
        w.end_object();
        w.end_document(indent > 0);
      }
      CHECK(pieces.str() == one.str());
      CHECK(nlohmann::json::parse(pieces.str())["list"].size() == count);
    }
  }
}

TEST_CASE("numbers are written in the shortest form that reads back, zero and whole ones too") {
  std::ostringstream out;
  {
    JsonWriter w(out, 0);
    w.begin_array();
    for (const double v : {0.0, -0.0, 1.0, -325.0, 99999.0, 100000.0, 1e15, 0.1, 1.5e-7})
      w.value(v);
    for (const float v : {0.0f, -0.0f, 2.0f, 99999.0f, 100000.0f, 0.1f})
      w.value(v);
    w.end_array();
    w.end_document(true);
  }
  CHECK(out.str() == "[0,-0,1,-325,99999,1e+05,1e+15,0.1,1.5e-07,0,-0,2,99999,1e+05,0.1]\n");
}

TEST_CASE("a block's raw fields are the bytes of key() and value()") {
  // write_block writes its numbers with raw_field(): every kind of number, in a one-line object
  // of an indented array as the JSON's blocks are, must come out as field() writes it.
  std::mt19937_64 rng(21);
  auto pick = [&](int i) {
    switch (i % 6) {
    case 0:
      return double(rng() % 200000) - 100000.0; // whole, either side of 1e5
    case 1:
      return std::ldexp(double(rng() % 1000000), int(rng() % 80) - 60);
    case 2:
      return std::numeric_limits<double>::quiet_NaN();
    case 3:
      return -0.0;
    case 4:
      return -std::numeric_limits<double>::infinity();
    default:
      return std::bit_cast<double>(rng());
    }
  };
  int differ = 0, objects = 0;
  for (int object = 0; object < 3000; ++object, ++objects) {
    std::vector<double> values;
    for (int i = 0; i < 12; ++i)
      values.push_back(pick(i + object));
    const auto count = std::uint32_t(rng());
    std::ostringstream generic_out, raw_out;
    {
      JsonWriter generic(generic_out, 1), raw(raw_out, 1);
      for (JsonWriter* w : {&generic, &raw}) {
        w->begin_object();
        w->key("blocks");
        w->begin_array();
        w->begin_object_on_one_line();
        w->field("line", object);
      }
      for (std::size_t i = 0; i < values.size(); ++i) {
        const std::string name = "f" + std::to_string(i);
        if (i % 2 == 0) {
          generic.field(name, values[i]);
          raw.raw_field(",\"" + name + "\":", values[i]);
        } else {
          generic.field(name, float(values[i]));
          raw.raw_field(",\"" + name + "\":", float(values[i]));
        }
      }
      generic.field("commands", count);
      raw.raw_field(",\"commands\":", count);
      generic.key("inner");
      generic.begin_object();
      generic.field("a", values[1]);
      generic.end_object();
      raw.raw_field(",\"inner\":{\"a\":", values[1]);
      raw.raw_text("}");
      for (JsonWriter* w : {&generic, &raw}) {
        w->end_object();
        w->end_array();
        w->end_object();
        w->end_document(true);
      }
    }
    differ += generic_out.str() != raw_out.str();
    if (object == 0) CHECK(generic_out.str() == raw_out.str());
  }
  CHECK(differ == 0);
  CHECK(objects == 3000);
}

TEST_CASE("the document ends with its newline, never starts with it") {
  const MachineProfile machine = generic();
  const SourceFile source = make_source("small.ngc", "G21\nG1 X10 F100\nM30\n");
  const std::string full = json_of(source, machine, {});
  REQUIRE(full.size() > 2);
  CHECK(full.front() == '{');
  CHECK(full.substr(full.size() - 2) == "}\n");
  const std::string compact = json_of(source, machine, {}, true);
  CHECK(compact.front() == '{');
  CHECK(compact.substr(compact.size() - 2) == "}\n");
}

TEST_CASE("the compact document holds the full one's numbers, a block per row") {
  const MachineProfile machine = generic();
  EstimateOptions options;
  options.stock = parse_stock_spec("box:0,0,-20,100,60,0");
  const SourceFile source = busy_program();
  const std::string full_text = json_of(source, machine, options);
  const std::string compact_text = json_of(source, machine, options, true);
  CHECK(compact_text.size() * 2 < full_text.size());
  const auto full = nlohmann::json::parse(full_text);
  const auto compact = nlohmann::json::parse(compact_text);
  // Everything but the blocks is the same document.
  for (const auto& [key, value] : full.items())
    if (key != "blocks") CHECK_MESSAGE(compact.at(key) == value, key);
  CHECK(compact.size() == full.size());
  const auto& columns = compact["blocks"]["columns"];
  const auto& rows = compact["blocks"]["rows"];
  REQUIRE(rows.size() == full["blocks"].size());
  REQUIRE(rows.size() > 300);
  // Each row on a line of its own: the rows' text is the document's lines between the header
  // and the end.
  std::size_t lines = 0;
  for (const char c : compact_text)
    lines += c == '\n';
  CHECK(lines == rows.size() + 2);
  int operations = 0;
  [[maybe_unused]] int notes = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& block = full["blocks"][i];
    const auto& row = rows[i];
    REQUIRE(row.size() == columns.size());
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::string name = columns[c];
      if (name == "operation") {
        if (row[c].is_null()) {
          CHECK_FALSE(block.contains("operation"));
        } else {
          CHECK(full["operations"][row[c].get<std::size_t>()]["name"] == block["operation"]);
          ++operations;
        }
      } else if (name.rfind("components.", 0) == 0) {
        CHECK(row[c] == block["components"][name.substr(11)]);
      } else if (name == "notes") {
        if (row[c].is_null()) {
          CHECK_FALSE(block.contains("notes"));
        } else {
          CHECK(nlohmann::json::array({row[c]}) == block["notes"]);
          ++notes;
        }
      } else if (row[c].is_null()) {
        CHECK_FALSE(block.contains(name));
      } else {
        CHECK_MESSAGE(row[c] == block.at(name), name);
      }
    }
    // Every field of the full block has its column.
    CHECK(block.size() <= columns.size() - 7);
  }
  CHECK(operations > 300);
}
