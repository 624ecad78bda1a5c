#include "progress.hpp"

#include <cstdio>
#include <cstdlib>
#include <unistd.h>

namespace ncjoule::cli {
namespace {

constexpr int kBarWidth = 24;
constexpr auto kRedraw = std::chrono::milliseconds(100);

bool stderr_is_terminal() {
  if (!isatty(STDERR_FILENO)) return false;
  const char* term = std::getenv("TERM");
  return !(term && std::string(term) == "dumb");
}

} // namespace

ProgressBar::ProgressBar(std::string what, std::size_t total)
    : what_(std::move(what)), total_(total), start_(std::chrono::steady_clock::now()) {
  const char* setting = std::getenv("NCJOULE_PROGRESS");
  enabled_ = stderr_is_terminal() && !(setting && std::string(setting) == "0");
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

// "estimating [#########---------------] 2/5 part.ngc  3.4 s"; one item: a block that sweeps
// back and forth, since the pipeline does not say how far it has got inside a program.
std::string ProgressBar::line(double elapsed_s) const {
  std::string bar(kBarWidth, '-');
  if (total_ > 1) {
    const std::size_t filled = kBarWidth * index_ / total_;
    bar.replace(0, filled, filled, '#');
  } else {
    const int span = kBarWidth - 6;
    const int step = static_cast<int>(elapsed_s * 10) % (2 * span);
    const int at = step < span ? step : 2 * span - step;
    bar.replace(static_cast<std::size_t>(at), 6, 6, '#');
  }
  char tail[64];
  std::snprintf(tail, sizeof tail, "  %.1f s", elapsed_s);
  std::string text = what_ + " [" + bar + "] ";
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
