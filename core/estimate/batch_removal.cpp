#include "batch_removal.hpp"

#include <algorithm>

namespace ncjoule::estimate_detail {
namespace {

// A batch goes to removal when it holds this many commands or path samples: big enough for the
// removal tiles to run in parallel, small enough to stay in cache.
constexpr std::size_t kBatchCommands = 2048;
constexpr std::size_t kBatchSamples = 16384;

} // namespace

std::optional<RemovedBatch> BatchRemoval::take(const CanonCommand& command, TimedCommand&& timed) {
  batch_.commands.push_back(command);
  batch_samples_ += timed.samples.size();
  batch_.timed.push_back(std::move(timed)); // its samples are not copied
  if (batch_.commands.size() >= kBatchCommands || batch_samples_ >= kBatchSamples)
    return remove_batch();
  return std::nullopt;
}

std::optional<RemovedBatch> BatchRemoval::finish() {
  if (batch_.commands.empty()) return std::nullopt;
  return remove_batch();
}

RemovedBatch BatchRemoval::remove_batch() {
  RemovedBatch batch = std::move(batch_);
  const std::size_t n = batch.commands.size();
  batch_ = next_batch();
  batch_.first_index = batch.first_index + n;
  batch_.commands.reserve(n);
  batch_.timed.reserve(n);
  batch_samples_ = 0;
  // A setup whose stock could not be made (no cuts to size it by) removes nothing.
  batch.removal_known = std::any_of(removals_.begin(), removals_.end(),
                                    [](const RemovalSimulator* r) { return r->ready(); });
  if (!batch.removal_known) {
    batch.removed.clear();
    return batch;
  }
  // A batch may straddle a setup's start: each part goes to its own stock. A batch in one setup
  // (nearly all) is removed into its own `removed`, whose results' memory a spare batch brought.
  for (std::size_t k = 0; k < n;) {
    const std::size_t setup = setups_.of(batch.first_index + k);
    const std::size_t end = std::min(n, setups_.first(setup + 1) - batch.first_index);
    moves_.clear();
    for (std::size_t m = k; m < end; ++m)
      moves_.push_back({batch.first_index + m, &batch.commands[m], &batch.timed[m]});
    RemovalSimulator& removal = *removals_[std::min(setup, removals_.size() - 1)];
    if (k == 0 && end == n) {
      removal.remove(moves_, batch.removed);
    } else {
      if (k == 0) batch.removed.clear();
      std::vector<CommandRemoval> part;
      removal.remove(moves_, part);
      for (CommandRemoval& r : part)
        batch.removed.push_back(std::move(r));
    }
    k = end;
  }
  return batch;
}

RemovedBatch BatchRemoval::next_batch() {
  RemovedBatch next;
  if (!spares_ || !spares_->take(next)) return next;
  // Its commands and timings go (the folding took their samples); its results stay, for
  // RemovalSimulator::remove to fill again.
  next.commands.clear();
  next.timed.clear();
  next.removal_known = false;
  return next;
}

} // namespace ncjoule::estimate_detail
