#pragma once
// The two ways the core spreads work over threads: tasks that trace rays (parallel_tasks), and a
// pass over the sensors' path records (for_each_sensor). Either way each task's work is its own
// and writes only its own results, so every figure is the same for any thread count.
#include <cstddef>
#include <functional>
#include <vector>

#include "trace/path_samples.h"
#include "trace/sensor_range.h"
#include "util/progress.h"
#include "util/rng.h"

namespace fenestra {

// Runs fn(task) for task in [0, count) on TBB with the requested thread count (0: all), with
// denormals flushed in every worker (as Embree asks) and cancellation polled between tasks.
void parallel_tasks(size_t count, int threads, Progress* progress, const std::function<void(size_t)>& fn);

// Paths per task: fixed, so that the split (and hence every sum) is the same for any thread count.
constexpr int kPathsPerTask = 128;

// The tasks a sensor's `paths` paths are traced in.
inline size_t path_tasks_per_sensor(int paths) { return (static_cast<size_t>(paths) + kPathsPerTask - 1) / kPathsPerTask; }

// One task of a pass over sensors' paths: paths [first, last) of `sensor` (the scene's index: it
// seeds the paths). `index`: task t of the i-th sensor of the pass is i * path_tasks_per_sensor + t.
struct PathTask {
  size_t index = 0, sensor = 0, first = 0, last = 0;

  // fn(path, rng, samples) for the task's paths in order: each with its random numbers from `seed`
  // and, under render.sampler "sobol", its stratified first decisions (else null; path_samples.h).
  template <typename Fn>
  void for_each_path(const RenderSettings& render, uint64_t seed, Fn fn) const {
    for (size_t p = first; p < last; ++p) {
      Rng rng = path_rng(seed, sensor, p);
      const std::optional<PathSamples> samples = path_samples(render, seed, sensor, p);
      fn(p, rng, samples ? &*samples : nullptr);
    }
  }
};

// Traces `paths` paths of every sensor of `sensors` in tasks of kPathsPerTask (parallel_tasks):
// fn(task) for the range.size() * path_tasks_per_sensor(paths) tasks.
void parallel_path_tasks(SensorRange sensors, int paths, int threads, Progress* progress,
                         const std::function<void(const PathTask&)>& fn);
// The same for the listed sensors (the scene's indices), the i-th of the list as the i-th sensor
// of the pass: each sensor's tasks are those of any pass over it.
void parallel_path_tasks(const std::vector<size_t>& sensors, int paths, int threads, Progress* progress,
                         const std::function<void(const PathTask&)>& fn);

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
