// A first-in, first-out queue whose elements keep their addresses while queued and whose memory
// is reused: a popped element's slot takes a later one by assignment. The planner queues every
// command it has not timed yet here; a std::deque of elements larger than its 512-byte node
// allocates and frees a node for each of them (a million of each on a 1M-block program).
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <vector>

namespace ncjoule::kinematics_detail {

template <class T> class SlotQueue {
public:
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  T& front() { return *slots_[head_]; }
  T& back() { return *slots_[slot(size_ - 1)]; }
  // The i-th element from the front; throws where there is none.
  T& at(std::size_t i) {
    if (i >= size_) throw std::out_of_range("SlotQueue::at: no such element");
    return *slots_[slot(i)];
  }

  // Appends `value`; the elements queued before keep their addresses.
  T& push_back(T&& value) {
    if (size_ == slots_.size()) grow();
    std::unique_ptr<T>& s = slots_[slot(size_)];
    if (s)
      *s = std::move(value);
    else
      s = std::make_unique<T>(std::move(value));
    ++size_;
    return *s;
  }
  // Drops the front element. Its object stays in its slot, with what it holds, until a later
  // push_back assigns over it.
  void pop_front() {
    head_ = slot(1);
    --size_;
  }

private:
  std::size_t slot(std::size_t i) const {
    const std::size_t s = head_ + i;
    return s >= slots_.size() ? s - slots_.size() : s;
  }
  // Twice the slots, the queued ones first, in order (the elements themselves do not move).
  void grow() {
    std::rotate(slots_.begin(), slots_.begin() + std::ptrdiff_t(head_), slots_.end());
    head_ = 0;
    slots_.resize(std::max<std::size_t>(16, 2 * slots_.size()));
  }

  std::vector<std::unique_ptr<T>> slots_;
  std::size_t head_ = 0, size_ = 0;
};

} // namespace ncjoule::kinematics_detail
