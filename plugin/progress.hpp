// A progress bar on standard error for runs that take a while: drawn only when stderr is a
// terminal (never into a log file or a pipe), only once the run has taken longer than a moment,
// and erased when done so the terminal keeps only the results. It shows the percentage done and
// an estimate of the time left. For other programs (the LinuxCNC filter), NCJOULE_PROGRESS=lines
// writes "PROGRESS <percent>" lines on stderr instead, one per whole percent, whatever stderr is.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace ncjoule::cli {

class ProgressBar {
public:
  // `total` items (programs) will be worked through under the heading `what` ("estimating").
  // NCJOULE_PROGRESS=0 turns the bar off, =lines gives progress lines; NCJOULE_PROGRESS_DELAY_MS
  // sets how long a run must take before the bar shows (default 300 ms).
  ProgressBar(std::string what, std::size_t total);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Item `index` (0-based) named `name` starts.
  void begin(std::size_t index, std::string name);
  // How far the current item has got (0 to 1). Safe to call from the worker thread.
  void set_fraction(double fraction);
  // A callback for EstimateOptions::progress that feeds this bar.
  std::function<void(double)> callback() {
    return [this](double f) { set_fraction(f); };
  }
  // All items are done: erases the bar.
  void finish();

  bool enabled() const { return enabled_; }

private:
  void run();
  std::string line(double elapsed_s) const;
  double done() const; // of all items, 0 to 1

  std::string what_;
  std::size_t total_;
  bool enabled_ = false;
  bool lines_ = false; // NCJOULE_PROGRESS=lines
  int last_percent_ = -1;
  double fraction_ = 0; // of the current item
  std::chrono::milliseconds delay_{300};
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  bool drawn_ = false;
  std::size_t index_ = 0;
  std::string name_;
  std::thread thread_;
};

} // namespace ncjoule::cli
