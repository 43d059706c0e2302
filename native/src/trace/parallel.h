#pragma once
// Runs fn(task) for task in [0, count) on TBB with the requested thread count (0: all), with
// denormals flushed in every worker and cancellation polled between tasks.
#include <cstddef>
#include <functional>

#include "util/progress.h"

namespace fenestra {

void parallel_tasks(size_t count, int threads, Progress* progress, const std::function<void(size_t)>& fn);

// Paths per task: fixed, so that the split (and hence every sum) is the same for any thread count.
constexpr int kPathsPerTask = 128;

}  // namespace fenestra
