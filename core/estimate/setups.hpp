// Internal: where a program's setups begin. A program that machines a part in two clampings
// (the top, then the part turned over) stops between them: M0 or M1, then the operator turns
// or moves the part, and the program goes on in another work offset, after a probing cycle, or
// after a comment that says so. Each setup cuts its own stock: one stock for both would leave
// the second setup nothing to remove (its cuts sit where the first one's stock is already gone,
// or above it), and call it all air cutting.
//
// A stop alone does not start a setup (posts write M1 between every operation); it starts one
// when, before the next cutting move, the program selects another work offset, probes, or has
// a comment naming a setup ("SETUP 2", "FLIP PART", "SECOND SIDE", ...).
//
// A rotary table or fourth axis turns the part without a stop: a positioning move that turns
// A, B or C after the part has been cut ("G0 A180", 3+1 indexing) presents another side, and
// starts a setup too. Removal is 3-axis, so each side's cuts are read in the table's frame: one
// stock for all sides would stack them into one tall block. A feed move that turns a rotary axis
// (simultaneous 4-axis cutting) starts none.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::estimate_detail {

struct SetupStart {
  std::size_t command = 0; // index of its first command in the program's stream
  int line = 0;            // 0-based source line of that command
  std::string reason;      // what told it ("M0 at line 41, then G55")
};

class SetupScan {
public:
  // Comments are read from `source` as `dialect` writes them (they make no commands).
  SetupScan(const SourceFile& source, const Dialect& dialect);
  // Commands in stream order; `index` counts every command the interpreter gives.
  void add(const CanonCommand& command, std::size_t index);
  // The setup the command at `index` belongs to (0-based), as far as the scan has seen.
  std::size_t current() const { return starts_.size() - 1; }
  const std::vector<SetupStart>& starts() const { return starts_; }

  // Whether a comment's text names a setup change.
  static bool names_setup(std::string_view text);

private:
  // The first comment naming a setup on lines after the last one looked at, up to `line`.
  std::string setup_comment_before(int line);

  const SourceFile& source_;
  Dialect dialect_;    // a copy: callers pass temporaries (find_dialect gives one)
  int looked_to_ = -1; // comments read up to this line
  std::vector<SetupStart> starts_;
  int work_offset_ = 1;
  bool cut_since_start_ = false; // a cutting move since the current setup began
  bool stopped_ = false;
  std::size_t stop_index_ = 0;
  int stop_line_ = 0;
  std::string stop_code_;
};

// Which setup each command index belongs to, from the starts a SetupScan found.
class SetupIndex {
public:
  explicit SetupIndex(std::vector<std::size_t> first_commands);
  std::size_t of(std::size_t command) const;
  std::size_t count() const { return first_.size(); }
  // The first command of setup `k` (the end of the stream for k == count()).
  std::size_t first(std::size_t k) const;

private:
  std::vector<std::size_t> first_;
};

} // namespace ncjoule::estimate_detail
