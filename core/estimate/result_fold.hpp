// Internal: the end of the pipeline. Batches of timed commands come in from removal
// (batch_removal.hpp), in the order they run; their energy is integrated and everything is
// folded into the results that are kept: one summary per source line, the operations, the time
// split, the power series and the reduced toolpath. Nothing program-sized is kept but the
// per-line summaries.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "batch_removal.hpp"
#include "ncjoule/estimate.hpp"
#include "operations.hpp"
#include "series_reducer.hpp"
#include "setups.hpp"

namespace ncjoule::estimate_detail {

class ResultFolder {
public:
  // `removals`: one simulator per setup (`setups` tells which command is in which; `starts`
  // where and why each begins), or none (removal not simulated); `expected_commands` (from the
  // first pass) scales the progress reports. `power` and `options` must outlive the folder.
  ResultFolder(const SourceFile& source, const Dialect& dialect, const PowerConstants& power,
               const EstimateOptions& options, std::vector<RemovalSimulator*> removals,
               SetupIndex setups, const std::vector<SetupStart>& starts,
               std::size_t expected_commands, Estimate& out);

  // Integrates the energy of a batch's commands and folds them in; batches come in order.
  void take(const RemovedBatch& batch);
  // Fills the estimate's results; `total_s` is the program's time.
  void finish(double total_s);

private:
  void fold(const CanonCommand& command, const TimedCommand& timed, const CommandRemoval* removed,
            const CommandEnergy& energy, std::size_t operation, bool stock_guessed);
  // What a command under a guessed stock adds to the range of the guessed figures.
  void follow_guess(const TimedCommand& timed, const CommandRemoval* removed,
                    const CommandEnergy& energy, bool stock_guessed);
  // `powers`: the total power at the ends of each of `segments` (the integrator's).
  void follow_path(const CanonCommand& command, const TimedCommand& timed,
                   const std::vector<OperatingSegment>& segments,
                   const std::vector<SegmentPower>& powers);
  std::uint16_t note_index(const std::string& note);

  const SourceFile& source_;
  const Dialect& dialect_;
  const PowerConstants& power_constants_;
  const EstimateOptions& options_;
  // The setups' removal results as one: the program's.
  RemovalResult merged_removal() const;

  std::vector<RemovalSimulator*> removals_;
  SetupIndex setups_;
  std::vector<SetupSummary> setup_totals_;
  Estimate& out_;
  std::size_t expected_commands_;

  std::size_t last_progress_ = 0; // commands folded at the last progress report

  // What is kept.
  std::size_t line_count_;         // of the source
  std::vector<LineSummary> lines_; // one per source line while running, up to the last that ran
  EnergyIntegrator energy_;
  OperationTracker operations_;
  TimeSplit time_;
  SeriesReducer power_, mrr_;
  PathReducer path_;
  std::map<std::string, std::uint16_t> notes_;
  std::vector<bool> guessed_setups_; // whose stock is guessed, by setup
  StockGuessRange guess_;
  int last_overload_line_ = -1;
  // The peak, less the cutting of blocks over the rating under a guess.
  double plausible_peak_w_ = 0;
  // Blocks that ask the spindle for more than its rating (with a stock given or stated).
  std::size_t overloaded_ = 0;
  int first_overloaded_line_ = -1;
  double worst_load_ = 0;
  int worst_load_line_ = -1;

  // Scratch, reused command after command.
  std::vector<OperatingSegment> segments_;
  std::vector<SegmentPower> segment_powers_;
};

} // namespace ncjoule::estimate_detail
