// Internal: the operations of a program, found as its commands run. An operation starts at a
// tool change, or at the comment a CAM post writes before each operation ("(2D CONTOUR2)",
// "(Begin operation: Pocket)") once the operation before it has cut; its name is that comment,
// or the comment a post writes by its tool change (above it, on it, or below it).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ncjoule/estimate.hpp"

namespace ncjoule::estimate_detail {

// The name a comment gives an operation: its text without the words some posts put before the
// name ("Begin operation:", "Operation:"); empty when the comment names no operation: a tool
// list entry ("T1 D=6. CR=0. - ..."), commented-out code ("G00 Z3"), or one of the notes posts
// write between operations ("Finish operation: ...", "Coolant on", "Machine units: mm").
std::string operation_name_in(std::string_view comment);
// The comment of a line that holds nothing else but a block number ("(Face1)", "N10 (Face1)").
std::optional<std::string_view> comment_of_line(std::string_view line, const Dialect& dialect);

class OperationTracker {
public:
  // `source` must outlive the tracker; its comment-only lines that may name an operation are
  // found here, once.
  OperationTracker(const SourceFile& source, const Dialect& dialect);

  // Called for each timed command in the order they run; returns the index of the operation it
  // belongs to (index 0: what runs before the first operation).
  std::size_t take(const CanonCommand& command, const TimedCommand& timed);
  // Adds a command's results to its operation.
  void add(std::size_t op, CanonKind kind, double duration_s, double energy_j,
           const ComponentValues& components_j, double removed_mm3, bool removal_known);

  // The operations in the order they first ran, named, with co2 and cost shares; the empty
  // leading one dropped. `cuts_on(line)` says whether a line cut (names are not looked for past
  // such lines). `index_map[i]` is where operation i went (0 when dropped; else 1-based).
  std::vector<OperationSummary> finish(const std::function<bool(int line)>& cuts_on,
                                       const EnergyResult& totals,
                                       std::vector<std::uint16_t>& index_map) const;

private:
  struct Op {
    OperationSummary summary;
    int comment_line = -1;     // the comment that started it (-1: a tool change did)
    bool cut = false;          // it has cut
    bool moved = false;        // it has moved an axis (a rapid, a feed)
    bool changed_tool = false; // started by its comment, a tool change followed: it is named
  };
  std::size_t start(int line, int comment_line, const CanonCommand& command, double start_s);
  // The operation comment an operation that has neither cut nor moved meets before it does: a
  // set-up note ("FLIP PART"), a fixture's or a tool controller's name (FreeCAD) named it, and
  // the operation is the one named last before its cuts.
  void rename(int comment_line);
  std::string name_of(const Op& op, const std::function<bool(int)>& stops) const;

  const SourceFile& source_;
  const Dialect& dialect_;
  // Sorted: comment-only lines that may start an operation, of the lines before
  // comments_read_. Read as the program runs (find_comments_before): a queue of a million
  // lines is a serial stretch before the first command is folded otherwise.
  std::vector<int> comment_lines_;
  std::size_t comments_read_ = 0;
  void find_comments_before(int line);
  std::vector<Op> ops_;
  std::map<int, std::size_t> by_line_; // an operation's start line (a loop runs it again)
  std::size_t current_ = 0;
  int last_line_ = -1;      // the block that ran last
  int last_call_line_ = -1; // its line in the main program (a subprogram's: the call's)
};

} // namespace ncjoule::estimate_detail
