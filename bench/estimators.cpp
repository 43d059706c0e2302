#include "estimators.h"

#include <cstdio>

namespace bench {

namespace {

Scene with_sampler(const Scene& base, fenestra::RenderSettings::Sampler sampler) {
  Scene scene = base;
  scene.render.sampler = sampler;
  return scene;
}

}  // namespace

json estimator_comparison(const Scene& scene, int top, const Reference& ref, const std::vector<int>& columns,
                          const std::vector<Rung>& sobol_ladder, const RawThroughput& raw) {
  std::printf("[2b] The same ladder with independent random numbers (render.sampler \"independent\")\n");
  const Scene independent = with_sampler(scene, fenestra::RenderSettings::Sampler::kIndependent);
  const std::vector<Rung> ladder = one_pass_ladder(independent, top, ref, columns);
  const TimeToAccuracy before = time_to_accuracy(ladder), now = time_to_accuracy(sobol_ladder);
  print_time_to_accuracy(before, ladder);
  // Raw-Embree-equivalent rays: time to accuracy x this run's raw rays/s (a ratio of times).
  const double ray_ratio = before.seconds / now.seconds;
  const double path_ratio = before.paths / now.paths;
  const double memory_ratio = now.memory_bytes / before.memory_bytes;
  // The baseline of the memory target: the independent estimator with the records as they were laid out.
  const double baseline_memory_ratio = now.memory_bytes / before.previous_layout_bytes;
  std::printf("    to ||dE||_F <= %.0f%% and every all-open value within %.0f%%:\n"
              "      independent: %8.0f paths, %7.2f s = %6.1f M raw-Embree rays, %7.1f MiB of records%s\n"
              "      sobol:       %8.0f paths, %7.2f s = %6.1f M raw-Embree rays, %7.1f MiB of records%s\n"
              "      ratios: %.2f x fewer raw-Embree-equivalent rays (target >= 5), %.2f x fewer paths, "
              "records %.2f x\n"
              "      records against the independent estimator's in the layout before compaction (%.1f MiB): "
              "%.2f x (target <= 0.25)\n\n",
              100 * kFrobeniusTarget, 100 * kAllOpenTarget, before.paths, before.seconds,
              before.seconds * raw.all_threads * 1e-6, mib(before.memory_bytes), before.measured ? "" : " (extrapolated)",
              now.paths, now.seconds, now.seconds * raw.all_threads * 1e-6, mib(now.memory_bytes),
              now.measured ? "" : " (extrapolated)", ray_ratio, path_ratio, memory_ratio,
              mib(before.previous_layout_bytes), baseline_memory_ratio);
  json rungs = json::array();
  for (const Rung& r : ladder) rungs.push_back(rung_json(r));
  return {{"independent_ladder", rungs},
          {"independent_time_to_accuracy", time_to_accuracy_json(before, ladder)},
          {"sobol_time_to_accuracy", time_to_accuracy_json(now, sobol_ladder)},
          {"raw_embree_equivalent_ray_ratio", ray_ratio},
          {"path_ratio", path_ratio},
          {"record_memory_ratio", memory_ratio},
          {"record_memory_ratio_to_previous_layout", baseline_memory_ratio}};
}

}  // namespace bench
