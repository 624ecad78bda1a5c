// Work cut in pieces, made on all cores and taken in order: how the annotated program and the
// JSON's blocks are written. A few pieces are in flight at a time (TBB's parallel_pipeline), so
// memory holds those, not the whole output; what take() sees is the same, piece for piece, as
// making them one after another.
#pragma once

#include <cstddef>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

namespace ncjoule {

// Calls make(i) for each i in [0, count) on any core, and take(piece) with each result on one
// thread at a time, in the order of i. Piece must be movable (text, or a pointer to a result).
template <class Piece, class Make, class Take>
void make_in_order(std::size_t count, Make&& make, Take&& take) {
  std::size_t next = 0;
  const auto in_flight = 2 * std::size_t(tbb::this_task_arena::max_concurrency()) + 1;
  tbb::parallel_pipeline(
      in_flight,
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                          [&](tbb::flow_control& control) -> std::size_t {
                                            if (next == count) control.stop();
                                            return next++;
                                          }) &
          tbb::make_filter<std::size_t, Piece>(tbb::filter_mode::parallel,
                                               [&](std::size_t i) { return make(i); }) &
          tbb::make_filter<Piece, void>(tbb::filter_mode::serial_in_order,
                                        [&](Piece piece) { take(piece); }));
}

} // namespace ncjoule
