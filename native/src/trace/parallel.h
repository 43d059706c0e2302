#pragma once
// The two ways the core spreads work over threads: tasks that trace rays (parallel_tasks), and a
// pass over the sensors' path records (for_each_sensor). Either way each task's work is its own
// and writes only its own results, so every figure is the same for any thread count.
#include <cstddef>
#include <functional>

#include "util/progress.h"

namespace fenestra {

// Runs fn(task) for task in [0, count) on TBB with the requested thread count (0: all), with
// denormals flushed in every worker (as Embree asks) and cancellation polled between tasks.
void parallel_tasks(size_t count, int threads, Progress* progress, const std::function<void(size_t)>& fn);

// Paths per task: fixed, so that the split (and hence every sum) is the same for any thread count.
constexpr int kPathsPerTask = 128;

// Runs fn(sensor) for sensor in [0, count) on TBB's threads, for passes over the path records
// that trace nothing. fn polls cancellation with cancelled_at (a sensor's record may hold
// millions of paths); once every sensor has returned, a cancelled `progress` throws Cancelled.
void for_each_sensor(size_t count, const Progress* progress, const std::function<void(size_t)>& fn);

// Paths between two polls of cancellation in loops over path records (well under a millisecond).
constexpr size_t kPollPaths = 4096;

// Whether a loop over a record's paths should stop at path p: polled every kPollPaths paths.
inline bool cancelled_at(const Progress* progress, size_t path) {
  return progress && path % kPollPaths == 0 && progress->cancelled();
}

}  // namespace fenestra
