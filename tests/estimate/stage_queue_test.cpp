// StageQueue hands items from one thread to the next in order, a batch at a time; the memory of
// the batches the stage after is done with goes back to the stage before, so that a long run
// makes only a few batches, whatever it passes.
#include <doctest/doctest.h>

#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "stage_queue.hpp"

using ncjoule::estimate_detail::run_overlapped;
using ncjoule::estimate_detail::StageQueue;

namespace {

// Long enough to live on the heap: an item moved wrong shows in its text.
std::string item(int i) {
  return "item number " + std::to_string(i) + " of the stream";
}

} // namespace

TEST_CASE("StageQueue passes every item in order and reuses its batches") {
  constexpr int kItems = 200000;
  StageQueue<std::string> queue(256, 4);
  std::thread producer([&] {
    for (int i = 0; i < kItems; ++i)
      queue.push(item(i));
    queue.finish();
  });
  std::vector<std::string> batch;
  int next = 0, wrong = 0;
  while (queue.pop(batch))
    for (std::string& s : batch)
      wrong += s != item(next++);
  producer.join();
  CHECK(next == kItems);
  CHECK(wrong == 0);
  // 782 batches passed; at most the 4 waiting, the one being filled, the one being read and
  // the one handed back were ever made.
  CHECK(queue.batches_made() <= 8);
}

TEST_CASE("run_overlapped: a failure of either stage ends both and comes back") {
  int consumed = 0;
  CHECK_THROWS_AS(run_overlapped<int>(
                      true,
                      [](StageQueue<int>& q) {
                        for (int i = 0; i < 10000; ++i)
                          q.push(int(i));
                        throw std::runtime_error("the stage before failed");
                      },
                      [&](int&) { ++consumed; }, 64, 2),
                  std::runtime_error);
  // The full batches before the failure were consumed (the one being filled is dropped: the run
  // fails anyway).
  CHECK(consumed >= 10000 - 64);
  CHECK(consumed <= 10000);
  CHECK_THROWS_AS(run_overlapped<int>(
                      true,
                      [](StageQueue<int>& q) {
                        for (int i = 0; i < 1000000; ++i)
                          q.push(int(i));
                      },
                      [](int& i) {
                        if (i == 500) throw std::logic_error("the stage after failed");
                      },
                      64, 2),
                  std::logic_error);
}
