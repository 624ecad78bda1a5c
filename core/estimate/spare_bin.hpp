// Internal: memory handed back up the stream. What a stage allocates for each command (a move's
// path samples in the planner, its step volumes in removal) is freed by the last stage, on
// another thread: with the C library's allocator that is a lock on the allocating thread's
// arena for every block, taken by both threads at once, and it cost about a tenth of a long
// program's stream. The folding gives the spent containers back through a bin instead, and the
// stage that made them takes them, a bin's worth at a time, to fill again: once the stream runs,
// nothing is allocated or freed per command. What a bin holds does not change a number.
#pragma once

#include <cstddef>
#include <mutex>
#include <utility>
#include <vector>

namespace ncjoule::estimate_detail {

template <class T> class SpareBin {
public:
  // At most `most` items wait; more are dropped (freed) by the giver.
  explicit SpareBin(std::size_t most) : most_(most) {}

  // Gives `item` for reuse (the stage after).
  void give(T&& item) {
    std::lock_guard lock(mutex_);
    if (items_.size() < most_) items_.push_back(std::move(item));
  }
  // Gives all of `items` that fit, under one lock; `items` is left empty.
  void give_all(std::vector<T>& items) {
    {
      std::lock_guard lock(mutex_);
      for (T& item : items) {
        if (items_.size() >= most_) break;
        items_.push_back(std::move(item));
      }
    }
    items.clear();
  }

  // One item in `item`, if any waits (the stage before).
  bool take(T& item) {
    std::lock_guard lock(mutex_);
    if (items_.empty()) return false;
    item = std::move(items_.back());
    items_.pop_back();
    return true;
  }
  // Every waiting item, appended to `into`, under one lock.
  void take_all(std::vector<T>& into) {
    std::lock_guard lock(mutex_);
    if (into.empty())
      into.swap(items_);
    else
      for (T& item : items_)
        into.push_back(std::move(item));
    items_.clear();
  }

private:
  const std::size_t most_;
  std::mutex mutex_;
  std::vector<T> items_;
};

} // namespace ncjoule::estimate_detail
