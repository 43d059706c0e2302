#include "trace/parallel.h"

#include <algorithm>

#include "trace/ray_scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>
#include <pmmintrin.h>

namespace fenestra {

void parallel_tasks(size_t count, int threads, Progress* progress, const std::function<void(size_t)>& fn) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 1), [&](const tbb::blocked_range<size_t>& range) {
      // Embree recommends flush-to-zero / denormals-are-zero in every thread that traces rays.
      _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
      _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
      const uint64_t rays_before = thread_ray_count();
      for (size_t task = range.begin(); task != range.end(); ++task) {
        if (progress && progress->cancelled()) break;
        fn(task);
        if (progress) progress->advance();
      }
      add_rays_traced(thread_ray_count() - rays_before);
    });
  });
  if (progress) progress->throw_if_cancelled();
}

namespace {

// Tasks for the pass's i-th sensor, scene index sensor_at(i).
void path_tasks(size_t count, const std::function<size_t(size_t)>& sensor_at, int paths, int threads,
                Progress* progress, const std::function<void(const PathTask&)>& fn) {
  const size_t per_sensor = path_tasks_per_sensor(paths);
  parallel_tasks(count * per_sensor, threads, progress, [&](size_t task) {
    PathTask t;
    t.index = task;
    t.sensor = sensor_at(task / per_sensor);
    t.first = (task % per_sensor) * kPathsPerTask;
    t.last = std::min<size_t>(static_cast<size_t>(paths), t.first + kPathsPerTask);
    fn(t);
  });
}

}  // namespace

void parallel_path_tasks(SensorRange sensors, int paths, int threads, Progress* progress,
                         const std::function<void(const PathTask&)>& fn) {
  path_tasks(sensors.size(), [&](size_t i) { return sensors.begin + i; }, paths, threads, progress, fn);
}

void parallel_path_tasks(const std::vector<size_t>& sensors, int paths, int threads, Progress* progress,
                         const std::function<void(const PathTask&)>& fn) {
  path_tasks(sensors.size(), [&](size_t i) { return sensors[i]; }, paths, threads, progress, fn);
}

void for_each_sensor(size_t count, const Progress* progress, const std::function<void(size_t)>& fn) {
  tbb::parallel_for(size_t(0), count, [&](size_t sensor) { fn(sensor); });
  if (progress) progress->throw_if_cancelled();
}

}  // namespace fenestra
