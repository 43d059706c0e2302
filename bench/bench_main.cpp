// fenestra_bench: on the paper-scale scene, in one run on this machine,
//  1. how many paths (and seconds) the one-pass contribution matrix E needs to reach the target
//     accuracy against a 16x longer reference,
//  2. its ray throughput against raw Embree on the same geometry,
//  3. its memory,
//  4. how long the paper's one-element-at-a-time approach would take for the same accuracy,
//  5. what a 0.3 m wall costs against the zero-thickness one: time to the same accuracy, memory.
// Wall-clock timings are noisy; the ratios are the numbers meant to be compared.
// Each benchmark has its file (raw_embree, accuracy_ladder, estimators, per_element, record_memory,
// thick_walls); this driver runs them in order and writes the one report.
#include <tbb/task_arena.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "accuracy_ladder.h"
#include "bench_common.h"
#include "estimators.h"
#include "per_element.h"
#include "raw_embree.h"
#include "record_memory.h"
#include "scene/scene.h"
#include "thick_walls.h"

namespace {

using namespace bench;

const char* const kScenePath = FENESTRA_EXAMPLES "/paper_scale/scene.json";

void print_header(const Scene& scene, double load) {
  std::printf("Fenestra benchmark: %s\n", scene.source.c_str());
  std::printf("  %zu sensors, %zu opening elements, %zu triangles, max %d bounces\n", scene.sensors.size(),
              scene.domain.element_count(), scene.mesh.triangle_count(), scene.render.max_bounces);
  std::printf("  hardware threads: %u (TBB uses %d); load average at start: %.2f\n",
              std::thread::hardware_concurrency(), tbb::this_task_arena::max_concurrency(), load);
  std::printf("  Timings are wall-clock seconds on this machine, in one run, and noisy (other load on the\n"
              "  machine shows up in them); the ratios are the meaningful numbers.\n\n");
}

// The estimator's targets: the criterion on this scene in at most 25 M raw-Embree-equivalent rays
// with at most 150 MB of path records; a 0.3 m wall at most 3x the thin wall's time to the same
// accuracy and 3x its record memory; standard errors that say the error (the forward check's
// target is printed by scripts/forward_check_bench.py).
constexpr double kTargetRays = 25e6, kTargetRecordBytes = 150e6, kTargetThickRatio = 3.0;

const char* met(bool ok) { return ok ? "met" : "NOT met"; }

void print_targets(const TimeToAccuracy& tta, const RawThroughput& raw, const Rung& top, const json& thick) {
  const double rays = tta.seconds * raw.all_threads;
  const double time_ratio = thick["time_to_accuracy_ratio"].get<double>();
  const double memory_ratio = thick["record_memory_ratio"].get<double>();
  const double honesty = top.own_stderr / top.frobenius;
  std::printf("Targets\n");
  std::printf("  criterion in <= %.0f M raw-Embree-equivalent rays: %.1f M, %s%s\n", kTargetRays * 1e-6, rays * 1e-6,
              met(rays <= kTargetRays), tta.measured ? "" : " (extrapolated)");
  std::printf("  path records at the criterion <= %.0f MB: %.0f MB, %s\n", kTargetRecordBytes * 1e-6,
              tta.memory_bytes * 1e-6, met(tta.memory_bytes <= kTargetRecordBytes));
  std::printf("  0.3 m wall <= %.0f x the thin wall's time to the same accuracy: %.1f x, %s; and its record memory: "
              "%.1f x, %s\n", kTargetThickRatio, time_ratio, met(time_ratio <= kTargetThickRatio), memory_ratio,
              met(memory_ratio <= kTargetThickRatio));
  std::printf("  standard errors say the error (own se_F / err E_F at the top rung, %d paths, in 0.7..1.4): %.2f, %s\n",
              top.paths, honesty, met(honesty >= 0.7 && honesty <= 1.4));
  std::printf("  (the forward check's target: scripts/forward_check_bench.py, after this bench)\n\n");
}

void print_summary(const TimeToAccuracy& tta, double one_pass_over_raw, const json& target, const json& matched,
                   double peak_rss) {
  const char* label = tta.measured ? "measured" : "EXTRAPOLATED";
  std::printf("Summary\n");
  std::printf("  one-pass time to accuracy (E 2%%, all-open 1%%): %.0f paths/sensor, %.1f s, Contributions %.0f MiB"
              " [%s]\n", tta.paths, tta.seconds, mib(tta.memory_bytes), label);
  std::printf("  peak RSS of the bench: %.0f MiB\n", peak_rss);
  std::printf("  one-pass tracer rays/s / raw Embree rays/s (all threads): %.2f\n", one_pass_over_raw);
  if (matched["available"].get<bool>())
    std::printf("  per-element / one-pass time at matched accuracy (measured): %.1f\n", matched["ratio"].get<double>());
  if (target["baseline_reached_target"].get<bool>() && tta.measured)
    std::printf("  per-element / one-pass time at the 2%% target (measured): %.1f\n", target["ratio"].get<double>());
  else
    std::printf("  per-element / one-pass time at the 2%% target: >= %.1f (lower bound), ~%.1f (EXTRAPOLATED)\n",
                target["ratio_lower_bound"].get<double>(), target["ratio"].get<double>());
}

std::string parse_json_path(int argc, char** argv, bool* estimators_only) {
  std::string path;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--json" && i + 1 < argc) {
      path = argv[++i];
    } else if (arg == "--estimators") {
      *estimators_only = true;
    } else {
      std::fprintf(stderr, "usage: fenestra_bench [--json PATH] [--estimators] | --thick-walls\n");
      std::exit(arg == "-h" || arg == "--help" ? 0 : 2);
    }
  }
  return path;
}

// ---------------------------------------------------------------------------------------------

int run(const std::string& json_path, bool estimators_only) {
  const auto bench_start = Clock::now();
  const Scene scene = fenestra::load_scene(kScenePath);
  const size_t elements = scene.domain.element_count();
  const std::vector<int> columns = baseline_columns(elements);
  const double load = load_average();
  print_header(scene, load);
  json report = {{"scene", scene.source},
                 {"sensors", scene.sensors.size()},
                 {"elements", elements},
                 {"triangles", scene.mesh.triangle_count()},
                 {"hardware_threads", std::thread::hardware_concurrency()},
                 {"load_average_at_start", load},
                 {"note", "wall-clock timings on this machine, noisy; the ratios are the meaningful numbers"}};

  const RawThroughput raw = raw_embree_throughput(scene);
  print_raw(raw);
  report["raw_embree"] = raw_json(raw);

  std::printf("[2] One pass (render.sampler \"sobol\"): E for all %zu elements; errors against the reference; own se_F is the run's own\n"
              "    estimated relative Frobenius standard error; err 8col: the baseline's columns only\n",
              elements);
  double pilot_seconds_per_path = 0.0;
  const int top = choose_top_rung(scene, &pilot_seconds_per_path);
  std::printf("    pilot: %d paths at %.2f us per path per sensor -> top rung %d paths\n", kPilotPaths,
              1e6 * pilot_seconds_per_path / scene.sensors.size(), top);
  std::fflush(stdout);
  const Reference ref = run_reference(scene, top, kReferenceFactor);
  print_reference(ref, top);
  report["reference"] = reference_json(ref);

  const std::vector<Rung> ladder = one_pass_ladder(scene, top, ref, columns);
  const TimeToAccuracy tta = time_to_accuracy(ladder);
  print_time_to_accuracy(tta, ladder);
  const double one_pass_rate = ref.rays / ref.seconds;
  std::printf("    one-pass tracer (reference runs): %.2f Mrays/s = %.2f x raw Embree on all threads\n\n",
              one_pass_rate * 1e-6, one_pass_rate / raw.all_threads);
  report["ladder"] = json::array();
  for (const Rung& r : ladder) report["ladder"].push_back(rung_json(r));
  report["time_to_accuracy"] = time_to_accuracy_json(tta, ladder);
  report["one_pass_over_raw_embree"] = one_pass_rate / raw.all_threads;
  report["estimators"] = estimator_comparison(scene, top, ref, columns, ladder, raw);
  if (estimators_only) {
    if (!json_path.empty()) write_json(json_path, report);
    return 0;
  }

  std::printf("[3] The paper's way: one element open at a time, %d columns k = i*%zu/%d, each\n"
              "    evaluate({element k}) - evaluate({}) with shared seed; 'all cols s' = closed + %zu/%d x 8 cols\n",
              kBaselineColumns, elements, kBaselineColumns, elements, kBaselineColumns);
  const std::vector<BaselineRung> baseline = baseline_ladder(scene, top, columns, ref);
  report["baseline"] = json::array();
  for (const BaselineRung& r : baseline) report["baseline"].push_back(baseline_rung_json(r, elements));
  report["baseline_ratio_at_target"] = target_ratio_json(baseline, tta, elements);
  report["baseline_ratio_at_matched_accuracy"] = matched_ratio_json(baseline, ladder, elements);
  print_target_ratio(report["baseline_ratio_at_target"]);
  print_matched_ratio(report["baseline_ratio_at_matched_accuracy"]);
  std::printf("\n");

  const double peak_rss = peak_rss_mib();
  print_memory(tta, ladder.back(), peak_rss);
  report["memory"] = memory_json(tta, peak_rss);

  report["thick_walls"] = thick_wall_comparison(kScenePath);
  print_targets(tta, raw, ladder.back(), report["thick_walls"]);

  print_summary(tta, one_pass_rate / raw.all_threads, report["baseline_ratio_at_target"],
                report["baseline_ratio_at_matched_accuracy"], peak_rss);
  const double total = seconds_since(bench_start);
  std::printf("bench total: %.1f s; load average at end: %.2f (this bench alone accounts for up to %u)\n", total,
              load_average(), std::thread::hardware_concurrency());
  report["bench_seconds"] = total;
  report["load_average_at_end"] = load_average();
  if (!json_path.empty()) write_json(json_path, report);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::string(argv[1]) == "--thick-walls") {  // section 5 alone
    try {
      thick_wall_comparison(kScenePath);
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "fenestra_bench: error: %s\n", e.what());
      return 1;
    }
  }
  bool estimators_only = false;  // sections 1, 2 and 2b: the estimators side by side
  const std::string json_path = parse_json_path(argc, argv, &estimators_only);
  try {
    return run(json_path, estimators_only);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fenestra_bench: error: %s\n", e.what());
    return 1;
  }
}
