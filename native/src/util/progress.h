#pragma once
// Progress of a long computation, shared between workers, the caller and Python:
// atomic counters, a status line and a cancel flag that workers poll.
#include <atomic>
#include <mutex>
#include <stdexcept>
#include <string>

namespace fenestra {

class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("computation cancelled") {}
};

class Progress {
 public:
  // A new step: its status line and count. While a stage holds the line (StageStatus), the traces
  // it runs only restart the count, so their work reads as the stage's.
  void start(const std::string& status, uint64_t total) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!held_) status_ = status;
    }
    done_ = 0;
    total_ = total;
  }
  // Sets the line whether held or not and holds it; returns whether it was held before.
  bool hold(const std::string& status) {
    std::lock_guard<std::mutex> lock(mutex_);
    status_ = status;
    done_ = 0;
    total_ = 1;
    const bool was = held_;
    held_ = true;
    return was;
  }
  void release(bool was_held) {
    std::lock_guard<std::mutex> lock(mutex_);
    held_ = was_held;
  }
  void advance(uint64_t n = 1) { done_ += n; }
  double fraction() const {
    const uint64_t total = total_;
    return total == 0 ? 0.0 : static_cast<double>(done_.load()) / static_cast<double>(total);
  }
  std::string status() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return status_;
  }
  void cancel() { cancelled_ = true; }
  bool cancelled() const { return cancelled_; }
  void throw_if_cancelled() const {
    if (cancelled_) throw Cancelled();
  }

 private:
  std::atomic<uint64_t> done_{0};
  std::atomic<uint64_t> total_{0};
  std::atomic<bool> cancelled_{false};
  mutable std::mutex mutex_;
  std::string status_;
  bool held_ = false;  // under mutex_
};

// A solver stage's name on the status line for as long as it runs, over the traces it runs (the
// edge search in a thick wall, the check with real cutters), which would name themselves.
class StageStatus {
 public:
  StageStatus(Progress* progress, const std::string& status)
      : progress_(progress), was_held_(progress ? progress->hold(status) : false) {}
  ~StageStatus() {
    if (progress_) progress_->release(was_held_);
  }
  StageStatus(const StageStatus&) = delete;
  StageStatus& operator=(const StageStatus&) = delete;

 private:
  Progress* progress_;
  bool was_held_;
};

}  // namespace fenestra
