// SlotQueue, the planner's queue of commands not timed yet: first in, first out; an element
// keeps its address while queued (the path builder holds pointers to queued commands), and
// popped slots are reused, so that a long run allocates only what the largest queue needs.
#include <doctest/doctest.h>

#include <deque>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include "slot_queue.hpp"

using ncjoule::kinematics_detail::SlotQueue;

TEST_CASE("SlotQueue keeps order and addresses, and reuses its slots") {
  SlotQueue<std::string> queue;
  std::deque<std::pair<std::string, const std::string*>> model; // what is queued, and where
  std::set<const std::string*> addresses;
  std::mt19937 rng(3);
  std::size_t most = 0;
  int moved = 0, misordered = 0;
  for (int step = 0; step < 200000; ++step) {
    // Bursts of pushes (the queue grows through several sizes) and of pops.
    const bool growing = (step / 5000) % 2 == 0;
    const bool push = model.empty() || (growing ? rng() % 4 != 0 : rng() % 4 == 0);
    if (push) {
      // Long enough to live on the heap: a moved string would show in its address.
      std::string text = "command number " + std::to_string(step) + " of the program";
      const std::string& queued = queue.push_back(std::move(text));
      model.emplace_back(queued, &queued);
      addresses.insert(&queued);
    } else {
      misordered += queue.front() != model.front().first;
      queue.pop_front();
      model.pop_front();
    }
    REQUIRE(queue.size() == model.size());
    most = std::max(most, model.size());
    if (step % 997 == 0)
      for (std::size_t i = 0; i < model.size(); ++i)
        moved += &queue.at(i) != model[i].second || queue.at(i) != model[i].first;
  }
  CHECK(misordered == 0);
  CHECK(moved == 0);
  CHECK(most > 1000); // the queue grew many times over
  // Slots are reused: no more objects than twice the most held at once.
  CHECK(addresses.size() <= 2 * most);
  CHECK_THROWS_AS(queue.at(queue.size()), std::out_of_range);
  if (!queue.empty()) CHECK(&queue.back() == model.back().second);
}
