// Internal: hands items from one stage of the pipeline to the next on another thread, in order,
// a batch at a time: the interpreter, the planner and the folding of results (removal and
// energy) then run at once, each on its own core, and the numbers are the same as when one
// thread runs them one after the other, since every stage sees the same items in the same order.
//
// At most `max_batches` full batches wait: memory holds a window of the program, not the program.
// A stage that fails ends the exchange: the other side's push returns at once and its pop gives
// the failure (rethrown), so no thread waits for one that is gone.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace ncjoule::estimate_detail {

// Thrown by push() to the stage before when the stage after has stopped: it unwinds the stage
// before (the interpreter and the planner have no way to be told to stop) to run_overlapped().
struct StageAbandoned {};

template <class T> class StageQueue {
public:
  explicit StageQueue(std::size_t batch_size = 256, std::size_t max_batches = 16)
      : batch_size_(batch_size), max_batches_(max_batches) {
    filling_.reserve(batch_size_);
  }

  // Batches whose memory the stage before took anew (the others came back from the stage
  // after): a few more than max_batches however many items pass (for tests).
  std::size_t batches_made() const { return batches_made_; }

  // --- the stage before ----------------------------------------------------------------------
  // Adds an item; hands the batch over when it is full (waiting while max_batches wait). Throws
  // StageAbandoned when the stage after has stopped.
  void push(T&& item) {
    if (direct_) return direct_(item);
    filling_.push_back(std::move(item));
    if (filling_.size() >= batch_size_) hand_over();
  }
  // No more items: hands over the last batch.
  void finish() {
    if (direct_) return;
    if (!filling_.empty()) hand_over();
    std::lock_guard lock(mutex_);
    finished_ = true;
    ready_.notify_all();
  }
  // The stage failed: the next stage's pop rethrows `failure` once the batches before it are
  // taken.
  void fail(std::exception_ptr failure) {
    std::lock_guard lock(mutex_);
    failure_ = std::move(failure);
    finished_ = true;
    ready_.notify_all();
  }

  // --- the stage after -----------------------------------------------------------------------
  // The next batch in `batch` (its items to be moved from); false at the end. Rethrows the
  // stage before's failure.
  // `batch`'s memory (the batch popped before) goes back to the stage before, for a later
  // batch: no batch is allocated on one thread and freed on the other once the queue runs.
  bool pop(std::vector<T>& batch) {
    batch.clear();
    std::unique_lock lock(mutex_);
    if (batch.capacity() > 0) spare_.push_back(std::move(batch));
    ready_.wait(lock, [&] { return !waiting_.empty() || finished_; });
    if (waiting_.empty()) {
      if (failure_) std::rethrow_exception(failure_);
      return false;
    }
    batch = std::move(waiting_.front());
    waiting_.pop_front();
    room_.notify_one();
    return true;
  }
  // The stage after stops taking items (it failed): pushes from now on are dropped.
  void abandon() {
    std::lock_guard lock(mutex_);
    abandoned_ = true;
    waiting_.clear();
    room_.notify_all();
  }

  // A queue that hands each item to `consume` at once, on the pushing thread: the stages one
  // after the other, as run_overlapped runs them when told not to overlap.
  explicit StageQueue(std::function<void(T&)> consume) : batch_size_(0), max_batches_(0) {
    direct_ = std::move(consume);
  }

private:
  void hand_over() {
    std::unique_lock lock(mutex_);
    room_.wait(lock, [&] { return waiting_.size() < max_batches_ || abandoned_; });
    if (abandoned_) {
      filling_.clear();
      throw StageAbandoned{};
    }
    waiting_.push_back(std::move(filling_));
    ready_.notify_one();
    filling_ = {};
    if (!spare_.empty()) {
      filling_ = std::move(spare_.back());
      spare_.pop_back();
    }
    lock.unlock();
    if (filling_.capacity() == 0) ++batches_made_;
    filling_.reserve(batch_size_);
  }

  const std::size_t batch_size_, max_batches_;
  std::function<void(T&)> direct_; // set: no thread, no batches
  std::vector<T> filling_;         // the stage before's batch being filled (its thread only)
  std::mutex mutex_;
  std::condition_variable ready_, room_;
  std::deque<std::vector<T>> waiting_;
  std::vector<std::vector<T>> spare_; // batches the stage after is done with, emptied
  std::size_t batches_made_ = 1;      // the stage before's thread only
  bool finished_ = false, abandoned_ = false;
  std::exception_ptr failure_;
};

// Runs produce(queue), which pushes items of type T, on a thread of its own, and consume(item)
// for each item on this thread, in order, as they come. An exception in either ends both and is
// rethrown here. With `overlap` false, produce runs here and each item is consumed as it is
// pushed: the same calls in the same order, on one thread.
template <class T, class Produce, class Consume>
void run_overlapped(bool overlap, Produce&& produce, Consume&& consume,
                    std::size_t batch_size = 256, std::size_t max_batches = 16) {
  if (!overlap) {
    StageQueue<T> direct([&](T& item) { consume(item); });
    produce(direct);
    return;
  }
  StageQueue<T> queue(batch_size, max_batches);
  std::thread producer([&] {
    try {
      produce(queue);
      queue.finish();
    } catch (...) {
      queue.fail(std::current_exception());
    }
  });
  try {
    std::vector<T> batch;
    while (queue.pop(batch))
      for (T& item : batch)
        consume(item);
  } catch (...) {
    queue.abandon();
    producer.join();
    throw;
  }
  producer.join();
}

} // namespace ncjoule::estimate_detail
