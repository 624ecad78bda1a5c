#include "progress.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "platform.hpp"

namespace ncjoule::cli {
namespace {

constexpr int kBarWidth = 24;
constexpr auto kRedraw = std::chrono::milliseconds(100);

} // namespace

ProgressBar::ProgressBar(std::string what, std::size_t total)
    : what_(std::move(what)), total_(total), start_(std::chrono::steady_clock::now()) {
  const char* setting = std::getenv("NCJOULE_PROGRESS");
  lines_ = setting && std::string(setting) == "lines";
  enabled_ = !lines_ && platform::stderr_is_terminal() && !(setting && std::string(setting) == "0");
  if (const char* delay = std::getenv("NCJOULE_PROGRESS_DELAY_MS"))
    delay_ = std::chrono::milliseconds(std::atol(delay));
  if (enabled_) thread_ = std::thread([this] { run(); });
}

ProgressBar::~ProgressBar() {
  finish();
}

void ProgressBar::begin(std::size_t index, std::string name) {
  std::lock_guard lock(mutex_);
  index_ = index;
  name_ = std::move(name);
  fraction_ = 0;
}

void ProgressBar::set_fraction(double fraction) {
  std::lock_guard lock(mutex_);
  fraction_ = std::min(1.0, std::max(0.0, fraction));
  if (!lines_) return;
  const int percent = int(100 * done());
  if (percent == last_percent_) return;
  last_percent_ = percent;
  std::fprintf(stderr, "PROGRESS %d\n", percent);
  std::fflush(stderr);
}

double ProgressBar::done() const {
  return total_ > 0 ? (double(index_) + fraction_) / double(total_) : 0.0;
}

void ProgressBar::finish() {
  {
    std::lock_guard lock(mutex_);
    if (done_) return;
    done_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

// "estimating [#########---------------]  37% 2/5 part.ngc  3.4 s, about 6 s left".
std::string ProgressBar::line(double elapsed_s) const {
  const double done_fraction = done();
  std::string bar(kBarWidth, '-');
  const std::size_t filled = std::size_t(kBarWidth * done_fraction);
  bar.replace(0, filled, filled, '#');
  char tail[96];
  if (done_fraction > 0.02) {
    const double left = elapsed_s * (1 - done_fraction) / done_fraction;
    std::snprintf(tail, sizeof tail, "  %.1f s, about %.0f s left", elapsed_s, left);
  } else {
    std::snprintf(tail, sizeof tail, "  %.1f s", elapsed_s);
  }
  char percent[16];
  std::snprintf(percent, sizeof percent, "%3d%% ", int(100 * done_fraction));
  std::string text = what_ + " [" + bar + "] " + percent;
  if (total_ > 1) text += std::to_string(index_ + 1) + "/" + std::to_string(total_) + " ";
  std::string name = name_;
  if (name.size() > 40) name = "..." + name.substr(name.size() - 37);
  return text + name + tail;
}

void ProgressBar::run() {
  std::unique_lock lock(mutex_);
  while (!done_) {
    const auto elapsed = std::chrono::steady_clock::now() - start_;
    if (elapsed >= delay_) {
      const std::string text = line(std::chrono::duration<double>(elapsed).count());
      std::fprintf(stderr, "\r\033[K%s", text.c_str()); // \033[K: erase the rest of the line
      std::fflush(stderr);
      drawn_ = true;
    }
    wake_.wait_for(lock, kRedraw, [this] { return done_; });
  }
  if (drawn_) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }
}

} // namespace ncjoule::cli
