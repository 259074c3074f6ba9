#include "apps/setup_progress.h"

#include <cstdio>
#include <utility>

namespace ipstep {

SetupProgress::SetupProgress(std::string program, double delay_seconds)
    : program_(std::move(program)), delay_(delay_seconds) {
  if (delay_ > 0.0) watcher_ = std::thread([this] { Watch(); });
}

SetupProgress::~SetupProgress() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (shown_) std::fprintf(stderr, "\n");
    stop_ = true;
  }
  changed_.notify_all();
  if (watcher_.joinable()) watcher_.join();
}

void SetupProgress::Begin(const std::string& what) {
  if (delay_ < 0.0) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (shown_) std::fprintf(stderr, "\n");
    phase_ = what;
    ++generation_;
    started_ = std::chrono::steady_clock::now();
    shown_ = false;
    if (delay_ == 0.0) Show();
  }
  changed_.notify_all();
}

void SetupProgress::End(const std::string& result) {
  if (delay_ < 0.0) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (shown_) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
      std::fprintf(stderr, " %s in %.1f s\n", result.c_str(), seconds);
    }
    phase_.clear();
    shown_ = false;
  }
  changed_.notify_all();
}

void SetupProgress::Show() {
  std::fprintf(stderr, "%s: %s ...", program_.c_str(), phase_.c_str());
  std::fflush(stderr);
  shown_ = true;
}

void SetupProgress::Watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    if (phase_.empty() || shown_) {
      changed_.wait(lock);
      continue;
    }
    const auto due = started_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                    std::chrono::duration<double>(delay_));
    const long generation = generation_;
    if (changed_.wait_until(lock, due) == std::cv_status::timeout && !stop_ &&
        generation_ == generation && !shown_ && !phase_.empty()) {
      Show();
    }
  }
}

std::string Thousands(long long value) {
  std::string digits = std::to_string(value < 0 ? -value : value);
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3) digits.insert(i, ",");
  return value < 0 ? "-" + digits : digits;
}

}  // namespace ipstep
