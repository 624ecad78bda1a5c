// Internal: the stage of the pipeline between the planner and the folding of results. Timed
// commands come in, in the order they run; they are gathered in batches and removed from the
// stock a batch at a time (the grid's tiles in parallel), and each removed batch goes on to the
// folding (result_fold.hpp). On a thread of its own, removal of one batch runs while the energy
// of the one before is integrated and folded.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "ncjoule/removal.hpp"
#include "setups.hpp"
#include "spare_bin.hpp"

namespace ncjoule::estimate_detail {

// Commands in the order they run, with what removal took under each.
struct RemovedBatch {
  std::size_t first_index = 0; // timeline index of the first command
  std::vector<CanonCommand> commands;
  std::vector<TimedCommand> timed;
  bool removal_known = false;          // some setup's stock could be made
  std::vector<CommandRemoval> removed; // one per command where removal_known
};

class BatchRemoval {
public:
  // `removals`: one simulator per setup (`setups` tells which command is in which), or none.
  // `spares`: batches the folding is done with, whose memory new batches reuse (spare_bin.hpp).
  BatchRemoval(std::vector<RemovalSimulator*> removals, SetupIndex setups,
               SpareBin<RemovedBatch>* spares = nullptr)
      : removals_(std::move(removals)), setups_(std::move(setups)), spares_(spares) {}

  // Adds a command; when that fills the batch, the batch removed.
  std::optional<RemovedBatch> take(const CanonCommand& command, TimedCommand&& timed);
  // The last batch removed, if it holds any command.
  std::optional<RemovedBatch> finish();

private:
  RemovedBatch remove_batch();
  // An empty batch to fill next: a spare one where there is one.
  RemovedBatch next_batch();

  std::vector<RemovalSimulator*> removals_;
  SetupIndex setups_;
  SpareBin<RemovedBatch>* spares_;
  RemovedBatch batch_; // being filled
  std::size_t batch_samples_ = 0;
  std::vector<TimedMove> moves_; // scratch
};

} // namespace ncjoule::estimate_detail
