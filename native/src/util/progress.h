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
  void start(const std::string& status, uint64_t total) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      status_ = status;
    }
    done_ = 0;
    total_ = total;
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
};

}  // namespace fenestra
