// fenestra_bench: on the paper-scale scene, in one run on this machine,
//  1. how many paths (and seconds) the one-pass contribution matrix E needs to reach the target
//     accuracy against a 16x longer reference,
//  2. its ray throughput against raw Embree on the same geometry,
//  3. its memory,
//  4. how long the paper's one-element-at-a-time approach would take for the same accuracy,
//  5. what a 0.3 m wall costs against the zero-thickness one: time to the same accuracy, memory.
// Wall-clock timings are noisy; the ratios are the numbers meant to be compared.
#include <pmmintrin.h>
#include <sys/resource.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "annual/annual_contributions.h"
#include "format/atomic_file.h"
#include "scene/scene.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"
#include "trace/ray_scene.h"

namespace {

using Clock = std::chrono::steady_clock;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using fenestra::Scene;
using nlohmann::json;

const char* const kScenePath = FENESTRA_EXAMPLES "/paper_scale/scene.json";

// Accuracy targets.
constexpr double kFrobeniusTarget = 0.02;  // ||E - E_ref||_F / ||E_ref||_F
constexpr double kAllOpenTarget = 0.01;    // every sensor's |all_open - ref| / ref
// The reference has 16x the paths of the ladder's top rung, so its noise barely shows in the errors.
constexpr int kReferenceFactor = 16;
// Wall-clock budget of the reference; it bounds the top rung and so the whole bench (~2-3 min).
constexpr double kReferenceBudgetSeconds = 60.0;
constexpr int kFirstRung = 64;
constexpr int kMaxTopRung = 1 << 16;
constexpr int kPilotPaths = 8192;
// Errors below this many paths are not yet in the 1/sqrt(paths) regime (most entries of E still 0).
constexpr int kSlopeFromPaths = 1024;
constexpr int kBaselineColumns = 8;
// Distinct seeds: ladder and baseline runs must be independent of the reference.
constexpr uint64_t kLadderSeed = 1, kBaselineSeed = 2, kPilotSeed = 3, kReferenceSeed = 1000;
constexpr size_t kRawRayCount = size_t(1) << 20;
constexpr double kRawMinSeconds = 1.5;

// ---------------------------------------------------------------------------------------------
// Small utilities

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

// Other work on the machine slows every timing; the reader should see how busy it was.
double load_average() {
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : std::nan("");
}

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

Scene with_paths(const Scene& base, int paths, uint64_t seed) {
  Scene scene = base;
  scene.render.paths_per_sensor = paths;
  scene.render.seed = seed;
  return scene;
}

// Extra paths needed to bring `error` down to `target` when error falls as 1/sqrt(paths).
double path_factor(double error, double target) { return (error / target) * (error / target); }

// The tracer's workers flush denormals (Embree's advice); the raw measurement does the same.
void flush_denormals() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

// ---------------------------------------------------------------------------------------------
// Errors against the reference

double relative_frobenius(const MatrixXd& E, const MatrixXd& ref) { return (E - ref).norm() / ref.norm(); }

// Largest relative deviation over sensors (sensors that receive no light at all are skipped).
double max_relative(const VectorXd& v, const VectorXd& ref) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (ref[i] > 0.0) worst = std::max(worst, std::abs(v[i] - ref[i]) / ref[i]);
  return worst;
}

MatrixXd take_columns(const MatrixXd& m, const std::vector<int>& columns) {
  MatrixXd out(m.rows(), static_cast<Eigen::Index>(columns.size()));
  for (size_t j = 0; j < columns.size(); ++j) out.col(static_cast<Eigen::Index>(j)) = m.col(columns[j]);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Raw Embree throughput

struct Ray {
  fenestra::Vec3 org, dir;
};

// Incoherent rays: origins uniform in the room's box [0,6]x[0,6]x[0,3], directions uniform on the sphere.
std::vector<Ray> random_rays(size_t count) {
  std::mt19937_64 gen(12345);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Ray> rays(count);
  for (Ray& r : rays) {
    r.org = fenestra::Vec3(6.0f * u(gen), 6.0f * u(gen), 3.0f * u(gen));
    const float z = 1.0f - 2.0f * u(gen), phi = 2.0f * fenestra::kPi * u(gen);
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    r.dir = fenestra::Vec3(s * std::cos(phi), s * std::sin(phi), z);
  }
  return rays;
}

struct RawThroughput {
  double one_thread = 0.0, all_threads = 0.0;  // rays per second
  double hit_fraction = 0.0;                   // sanity: rays from inside a closed room nearly all hit
};

// Repeats `trace_all` (which traces every ray once and returns its hits) for at least
// kRawMinSeconds; returns rays per second and the hit fraction of the last pass.
template <typename TraceAll>
std::pair<double, double> rays_per_second(size_t ray_count, TraceAll trace_all) {
  const auto start = Clock::now();
  size_t traced = 0, hits = 0;
  double seconds = 0.0;
  do {
    hits = trace_all();
    traced += ray_count;
    seconds = seconds_since(start);
  } while (seconds < kRawMinSeconds);
  return {static_cast<double>(traced) / seconds, static_cast<double>(hits) / static_cast<double>(ray_count)};
}

RawThroughput raw_embree_throughput(const Scene& scene) {
  const fenestra::RayScene embree(scene.mesh, fenestra::Mesh{});
  const std::vector<Ray> rays = random_rays(kRawRayCount);
  const float inf = std::numeric_limits<float>::infinity();
  auto trace_range = [&](size_t begin, size_t end) {
    size_t hits = 0;
    for (size_t i = begin; i < end; ++i) hits += embree.intersect(rays[i].org, rays[i].dir, 0.0f, inf, nullptr).valid();
    return hits;
  };
  RawThroughput raw;
  flush_denormals();
  raw.one_thread = rays_per_second(rays.size(), [&] { return trace_range(0, rays.size()); }).first;
  const auto all = rays_per_second(rays.size(), [&] {
    std::atomic<size_t> hits{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
      flush_denormals();
      hits += trace_range(r.begin(), r.end());
    });
    return hits.load();
  });
  raw.all_threads = all.first;
  raw.hit_fraction = all.second;
  return raw;
}

// ---------------------------------------------------------------------------------------------
// One-pass runs and the reference

struct OnePassRun {
  int paths = 0;
  double seconds = 0.0;  // wall clock of compute_contributions: tracing and assembling E
  uint64_t rays = 0;
  size_t memory_bytes = 0;
  size_t previous_layout_bytes = 0;  // the same, with the records laid out as before compaction
  MatrixXd E, E_stderr;
  VectorXd all_open;
};

// Contributions::memory_bytes() had the same records been laid out as before they were compacted:
// a 16-byte event and an 8-byte panel point each, every condition (light through one element's
// too) 4 bytes and an 8-byte point, one 4-byte offset per path. The baseline of the memory target.
size_t bytes_in_previous_layout(const fenestra::Contributions& c) {
  size_t bytes = c.memory_bytes();
  for (const fenestra::SensorRecord& r : c.records) {
    size_t conditions = 0;
    for (size_t p = 0; p < r.path_count(); ++p)
      r.walk(p, [&](uint32_t, const fenestra::PathEvent&, const fenestra::EventConditions& ec) {
        conditions += ec.count();
        return true;
      });
    bytes -= r.memory_bytes();
    bytes += r.events.size() * 24 + conditions * 12 + r.path_count() * 4 +
             r.event_sources.size() * sizeof(uint16_t) + r.event_coefficients.size() * sizeof(float);
  }
  return bytes;
}

OnePassRun run_one_pass(const Scene& base, int paths, uint64_t seed) {
  const Scene scene = with_paths(base, paths, seed);
  const uint64_t rays_before = fenestra::rays_traced();
  const auto start = Clock::now();
  fenestra::Contributions c = fenestra::compute_contributions(scene);
  OnePassRun run;
  run.seconds = seconds_since(start);
  run.rays = fenestra::rays_traced() - rays_before;
  run.paths = paths;
  run.memory_bytes = c.memory_bytes();
  run.previous_layout_bytes = bytes_in_previous_layout(c);
  run.E = std::move(c.E);
  run.E_stderr = std::move(c.E_stderr);
  run.all_open = std::move(c.all_open.value);
  return run;  // the path records die with `c` here: only the small matrices are kept
}

// Sum of a run's own squared standard errors relative to its ||E||_F: the noise it expects of itself.
double own_relative_stderr(const MatrixXd& E, const MatrixXd& E_stderr) {
  return std::sqrt(E_stderr.array().square().sum()) / E.norm();
}

// Largest power-of-two top rung whose 16x reference fits the budget, judged by a pilot run's pace
// (the pilot includes fixed costs, so the estimate errs on the long side).
int choose_top_rung(const Scene& scene, double* pilot_seconds_per_path) {
  const OnePassRun pilot = run_one_pass(scene, kPilotPaths, kPilotSeed);
  *pilot_seconds_per_path = pilot.seconds / kPilotPaths;
  int top = kMaxTopRung;
  while (top > kFirstRung && kReferenceFactor * top * *pilot_seconds_per_path > kReferenceBudgetSeconds) top /= 2;
  return top;
}

struct Reference {
  int paths = 0, chunks = 0;
  double seconds = 0.0;
  uint64_t rays = 0;
  MatrixXd E, E_variance;
  VectorXd all_open;
  double relative_stderr() const { return std::sqrt(E_variance.sum()) / E.norm(); }
};

// `chunks` independent runs of `chunk_paths` averaged: statistically one run of chunks x chunk_paths
// paths (equal-sized means), with the memory of a single chunk.
Reference run_reference(const Scene& scene, int chunk_paths, int chunks) {
  Reference ref;
  ref.paths = chunk_paths * chunks;
  ref.chunks = chunks;
  for (int j = 0; j < chunks; ++j) {
    const OnePassRun run = run_one_pass(scene, chunk_paths, kReferenceSeed + static_cast<uint64_t>(j));
    if (j == 0) {
      ref.E.setZero(run.E.rows(), run.E.cols());
      ref.E_variance.setZero(run.E.rows(), run.E.cols());
      ref.all_open.setZero(run.all_open.size());
    }
    ref.E += run.E / chunks;
    ref.E_variance += run.E_stderr.array().square().matrix() / (static_cast<double>(chunks) * chunks);
    ref.all_open += run.all_open / chunks;
    ref.seconds += run.seconds;
    ref.rays += run.rays;
  }
  return ref;
}

// ---------------------------------------------------------------------------------------------
// The one-pass ladder

struct Rung {
  int paths = 0;
  double seconds = 0.0;
  uint64_t rays = 0;
  size_t memory_bytes = 0, previous_layout_bytes = 0;
  double frobenius = 0.0;   // relative Frobenius error of E against the reference
  double all_open = 0.0;    // worst sensor's relative all-open error
  double subset = 0.0;      // relative Frobenius error on the baseline's columns only
  double own_stderr = 0.0;  // the run's own relative Frobenius standard error
  bool meets_targets() const { return frobenius <= kFrobeniusTarget && all_open <= kAllOpenTarget; }
};

Rung measure_rung(const Scene& scene, int paths, const Reference& ref, const std::vector<int>& subset) {
  const OnePassRun run = run_one_pass(scene, paths, kLadderSeed);
  Rung r;
  r.paths = paths;
  r.seconds = run.seconds;
  r.rays = run.rays;
  r.memory_bytes = run.memory_bytes;
  r.previous_layout_bytes = run.previous_layout_bytes;
  r.frobenius = relative_frobenius(run.E, ref.E);
  r.all_open = max_relative(run.all_open, ref.all_open);
  r.subset = relative_frobenius(take_columns(run.E, subset), take_columns(ref.E, subset));
  r.own_stderr = own_relative_stderr(run.E, run.E_stderr);
  return r;
}

void print_rung_header() {
  std::printf("  %7s %8s %8s %8s %9s %9s %9s %9s %8s\n", "paths", "seconds", "Mrays", "Mrays/s", "err E_F",
              "all-open", "err 8col", "own se_F", "mem MiB");
}

void print_rung(const Rung& r) {
  std::printf("  %7d %8.3f %8.2f %8.2f %9.4f %9.4f %9.4f %9.4f %8.1f%s\n", r.paths, r.seconds, r.rays * 1e-6,
              r.rays * 1e-6 / r.seconds, r.frobenius, r.all_open, r.subset, r.own_stderr, mib(r.memory_bytes),
              r.meets_targets() ? "  <- targets met" : "");
  std::fflush(stdout);
}

// Doubles the paths from kFirstRung up to `top`, stopping at the first rung that meets both targets.
std::vector<Rung> one_pass_ladder(const Scene& scene, int top, const Reference& ref, const std::vector<int>& subset) {
  std::vector<Rung> ladder;
  print_rung_header();
  for (int paths = kFirstRung; paths <= top; paths *= 2) {
    ladder.push_back(measure_rung(scene, paths, ref, subset));
    print_rung(ladder.back());
    if (ladder.back().meets_targets()) break;
  }
  return ladder;
}

// Least-squares slope of log(error) against log(paths) from kSlopeFromPaths on; Monte Carlo noise
// gives -0.5, which is what any extrapolation below relies on.
double error_slope(const std::vector<Rung>& ladder, double Rung::*error) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const Rung& r : ladder) {
    if (r.paths < kSlopeFromPaths) continue;
    const double x = std::log(r.paths), y = std::log(r.*error);
    n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return n >= 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : std::nan("");
}

struct TimeToAccuracy {
  double paths = 0.0, seconds = 0.0, memory_bytes = 0.0, previous_layout_bytes = 0.0;
  bool measured = false;  // false: extrapolated from the top rung
};

// The first rung meeting both targets or, failing that, the top rung scaled by the paths both
// errors would need at 1/sqrt(paths), time and memory growing linearly with paths.
TimeToAccuracy time_to_accuracy(const std::vector<Rung>& ladder) {
  const Rung& top = ladder.back();
  if (top.meets_targets())
    return {double(top.paths), top.seconds, double(top.memory_bytes), double(top.previous_layout_bytes), true};
  const double factor =
      std::max({1.0, path_factor(top.frobenius, kFrobeniusTarget), path_factor(top.all_open, kAllOpenTarget)});
  return {top.paths * factor, top.seconds * factor, top.memory_bytes * factor, top.previous_layout_bytes * factor, false};
}

// ---------------------------------------------------------------------------------------------
// The paper's way: one element open at a time

// S columns spread over the wall: k = i * No / S.
std::vector<int> baseline_columns(size_t elements) {
  std::vector<int> columns;
  for (int i = 0; i < kBaselineColumns; ++i) columns.push_back(static_cast<int>(i * elements / kBaselineColumns));
  return columns;
}

struct Evaluation {
  VectorXd value;
  double seconds = 0.0;
  uint64_t rays = 0;
};

Evaluation timed_evaluate(const Scene& scene, const std::vector<fenestra::Rectangle>& openings) {
  const uint64_t rays_before = fenestra::rays_traced();
  const auto start = Clock::now();
  Evaluation e;
  e.value = fenestra::evaluate_openings(scene, {openings.begin(), openings.end()}).value;
  e.seconds = seconds_since(start);
  e.rays = fenestra::rays_traced() - rays_before;
  return e;
}

struct BaselineRung {
  int paths = 0;
  double closed_seconds = 0.0, columns_seconds = 0.0;  // the all-closed run; all S single-element runs
  uint64_t rays = 0;
  double subset = 0.0;  // relative Frobenius error of the S columns against the reference's
  // Closed run once, then No / S times the S columns: what all No columns would take.
  double total_seconds(size_t elements) const {
    return closed_seconds + static_cast<double>(elements) / kBaselineColumns * columns_seconds;
  }
};

// Column k = evaluate({element k}) - evaluate({}). Every run shares the seed, so paths stay identical
// until they reach the opened element (common random numbers): this favours the baseline.
BaselineRung measure_baseline(const Scene& base, int paths, const std::vector<int>& columns, const MatrixXd& ref_columns) {
  const Scene scene = with_paths(base, paths, kBaselineSeed);
  BaselineRung r;
  r.paths = paths;
  const Evaluation closed = timed_evaluate(scene, {});
  r.closed_seconds = closed.seconds;
  r.rays = closed.rays;
  MatrixXd estimate(ref_columns.rows(), ref_columns.cols());
  for (size_t j = 0; j < columns.size(); ++j) {
    const Evaluation open = timed_evaluate(scene, {scene.domain.elements()[columns[j]].corners});
    estimate.col(static_cast<Eigen::Index>(j)) = open.value - closed.value;
    r.columns_seconds += open.seconds;
    r.rays += open.rays;
  }
  r.subset = relative_frobenius(estimate, ref_columns);
  return r;
}

void print_baseline_header() {
  std::printf("  %7s %9s %9s %8s %9s %13s\n", "paths", "closed s", "8 cols s", "Mrays/s", "err 8col", "all cols s");
}

void print_baseline_rung(const BaselineRung& r, size_t elements) {
  const double seconds = r.closed_seconds + r.columns_seconds;
  std::printf("  %7d %9.3f %9.3f %8.2f %9.4f %13.1f%s\n", r.paths, r.closed_seconds, r.columns_seconds,
              r.rays * 1e-6 / seconds, r.subset, r.total_seconds(elements),
              r.subset <= kFrobeniusTarget ? "  <- 2% met" : "");
  std::fflush(stdout);
}

// Doubles the paths until the S columns are within the Frobenius target or `top` is reached.
std::vector<BaselineRung> baseline_ladder(const Scene& scene, int top, const std::vector<int>& columns,
                                          const Reference& ref) {
  const MatrixXd ref_columns = take_columns(ref.E, columns);
  const size_t elements = scene.domain.element_count();
  std::vector<BaselineRung> ladder;
  print_baseline_header();
  for (int paths = kFirstRung; paths <= top; paths *= 2) {
    ladder.push_back(measure_baseline(scene, paths, columns, ref_columns));
    print_baseline_rung(ladder.back(), elements);
    if (ladder.back().subset <= kFrobeniusTarget) break;
  }
  return ladder;
}

// The one-pass rung that first matches the baseline's reached error on the same columns, or null.
const Rung* matching_rung(const std::vector<Rung>& ladder, double subset_error) {
  for (const Rung& r : ladder)
    if (r.subset <= subset_error) return &r;
  return nullptr;
}

// ---------------------------------------------------------------------------------------------
// Report sections (stdout and JSON)

void print_header(const Scene& scene, double load) {
  std::printf("Fenestra benchmark: %s\n", scene.source.c_str());
  std::printf("  %zu sensors, %zu opening elements, %zu triangles, max %d bounces\n", scene.sensors.size(),
              scene.domain.element_count(), scene.mesh.triangle_count(), scene.render.max_bounces);
  std::printf("  hardware threads: %u (TBB uses %d); load average at start: %.2f\n",
              std::thread::hardware_concurrency(), tbb::this_task_arena::max_concurrency(), load);
  std::printf("  Timings are wall-clock seconds on this machine, in one run, and noisy (other load on the\n"
              "  machine shows up in them); the ratios are the meaningful numbers.\n\n");
}

json raw_json(const RawThroughput& raw) {
  return {{"rays_per_second_1_thread", raw.one_thread},
          {"rays_per_second_all_threads", raw.all_threads},
          {"hit_fraction", raw.hit_fraction}};
}

void print_raw(const RawThroughput& raw) {
  std::printf("[1] Raw Embree throughput: RayScene::intersect, scene mesh, incoherent rays (origins uniform in\n"
              "    [0,6]x[0,6]x[0,3], directions uniform), closest hit, %.0f%% of rays hit\n",
              100.0 * raw.hit_fraction);
  std::printf("    1 thread:    %8.2f Mrays/s\n", raw.one_thread * 1e-6);
  std::printf("    all threads: %8.2f Mrays/s\n\n", raw.all_threads * 1e-6);
}

json reference_json(const Reference& ref) {
  return {{"paths", ref.paths},          {"chunks", ref.chunks}, {"seconds", ref.seconds},
          {"rays", ref.rays},            {"rays_per_second", ref.rays / ref.seconds},
          {"relative_frobenius_stderr", ref.relative_stderr()}};
}

void print_reference(const Reference& ref, int top) {
  std::printf("    reference: %d paths per sensor (= %d x the top rung %d, as %d independent runs of %d\n"
              "    paths averaged, seed %llu..), %.1f s, %.2f Mrays/s\n",
              ref.paths, kReferenceFactor, top, ref.chunks, ref.paths / ref.chunks,
              static_cast<unsigned long long>(kReferenceSeed), ref.seconds, ref.rays * 1e-6 / ref.seconds);
  std::printf("    reference's own relative Frobenius standard error sqrt(sum E_stderr^2)/||E||_F = %.4f\n"
              "    (1/4 of the top rung's own, since it has %dx the paths: it inflates the errors below by\n"
              "    ~sqrt(1 + 1/%d) = %.2fx; it is %s the 2%% target)\n\n",
              ref.relative_stderr(), kReferenceFactor, kReferenceFactor, std::sqrt(1.0 + 1.0 / kReferenceFactor),
              ref.relative_stderr() < 0.25 * kFrobeniusTarget ? "small against" : "NOT small against");
}

json rung_json(const Rung& r) {
  return {{"paths", r.paths},
          {"seconds", r.seconds},
          {"rays", r.rays},
          {"rays_per_second", r.rays / r.seconds},
          {"memory_bytes", r.memory_bytes},
          {"relative_frobenius_error", r.frobenius},
          {"max_all_open_relative_error", r.all_open},
          {"baseline_columns_relative_frobenius_error", r.subset},
          {"own_relative_frobenius_stderr", r.own_stderr},
          {"meets_targets", r.meets_targets()}};
}

json time_to_accuracy_json(const TimeToAccuracy& t, const std::vector<Rung>& ladder) {
  return {{"measured", t.measured},
          {"paths", t.paths},
          {"seconds", t.seconds},
          {"memory_bytes", t.memory_bytes},
          {"frobenius_error_slope", error_slope(ladder, &Rung::frobenius)},
          {"all_open_error_slope", error_slope(ladder, &Rung::all_open)}};
}

void print_time_to_accuracy(const TimeToAccuracy& t, const std::vector<Rung>& ladder) {
  std::printf("    log-log slope of the errors against paths (from %d paths; Monte Carlo: -0.5):\n"
              "      E Frobenius %.2f, worst all-open %.2f\n",
              kSlopeFromPaths, error_slope(ladder, &Rung::frobenius), error_slope(ladder, &Rung::all_open));
  if (t.measured) {
    std::printf("    TIME TO ACCURACY (measured): %.0f paths per sensor, %.3f s\n\n", t.paths, t.seconds);
    return;
  }
  const Rung& top = ladder.back();
  std::printf("    Targets NOT reached within the ladder (budget: reference <= %.0f s).\n", kReferenceBudgetSeconds);
  std::printf("    TIME TO ACCURACY (EXTRAPOLATED from the %d-path rung, errors ~ 1/sqrt(paths), time ~ paths):\n"
              "      ~%.0f paths per sensor, ~%.1f s (Frobenius alone needs x%.1f paths, all-open alone x%.1f)\n\n",
              top.paths, t.paths, t.seconds, path_factor(top.frobenius, kFrobeniusTarget),
              path_factor(top.all_open, kAllOpenTarget));
}

json memory_json(const TimeToAccuracy& t, double peak_rss) {
  return {{"contributions_memory_bytes", t.memory_bytes},
          {"contributions_memory_measured", t.measured},
          {"peak_rss_mib", peak_rss}};
}

void print_memory(const TimeToAccuracy& t, const Rung& top, double peak_rss) {
  std::printf("[4] Memory\n");
  if (t.measured)
    std::printf("    Contributions::memory_bytes() of the time-to-accuracy run: %.1f MiB\n", mib(t.memory_bytes));
  else
    std::printf("    Contributions::memory_bytes(): %.1f MiB at the top rung (%d paths); EXTRAPOLATED to the\n"
                "    time-to-accuracy path count: ~%.0f MiB (path records grow linearly with paths)\n",
                mib(top.memory_bytes), top.paths, mib(t.memory_bytes));
  std::printf("    peak RSS of this process: %.1f MiB (its largest run: a %d-path rung or reference chunk)\n\n",
              peak_rss, top.paths);
}

json baseline_rung_json(const BaselineRung& r, size_t elements) {
  return {{"paths", r.paths},
          {"closed_seconds", r.closed_seconds},
          {"columns_seconds", r.columns_seconds},
          {"rays", r.rays},
          {"relative_frobenius_error", r.subset},
          {"all_columns_seconds", r.total_seconds(elements)}};
}

// Ratio of the baseline's time for all No columns to the one-pass time, at the 2% target. Measured
// when both reached it; else a lower bound (baseline time spent so far) and an extrapolation.
json target_ratio_json(const std::vector<BaselineRung>& baseline, const TimeToAccuracy& one_pass, size_t elements) {
  const BaselineRung& last = baseline.back();
  const double spent = last.total_seconds(elements);
  const bool reached = last.subset <= kFrobeniusTarget;
  const double needed = reached ? spent : spent * path_factor(last.subset, kFrobeniusTarget);
  return {{"baseline_reached_target", reached},
          {"one_pass_measured", one_pass.measured},
          {"baseline_error_reached", last.subset},
          {"baseline_all_columns_seconds", needed},
          {"ratio", needed / one_pass.seconds},
          {"ratio_lower_bound", spent / one_pass.seconds}};
}

void print_target_ratio(const json& r) {
  const bool measured = r["baseline_reached_target"].get<bool>() && r["one_pass_measured"].get<bool>();
  const char* one_pass = r["one_pass_measured"].get<bool>() ? "measured" : "EXTRAPOLATED";
  if (measured) {
    std::printf("    ratio at the 2%% target (measured): t_per_element_total / t_one_pass = %.1f\n",
                r["ratio"].get<double>());
    return;
  }
  if (!r["baseline_reached_target"].get<bool>())
    std::printf("    The per-element approach did NOT reach 2%% within the budget (reached %.4f).\n",
                r["baseline_error_reached"].get<double>());
  std::printf("    ratio at the 2%% target, one-pass time %s:\n", one_pass);
  std::printf("      LOWER BOUND (per-element time already spent, all No columns / one-pass time): >= %.1f\n",
              r["ratio_lower_bound"].get<double>());
  std::printf("      EXTRAPOLATED (both at 2%%, errors ~ 1/sqrt(paths)):                          ~ %.1f\n",
              r["ratio"].get<double>());
}

// Ratio at the accuracy the baseline did reach, against the first one-pass rung at least as accurate
// on the same columns: both measured, no extrapolation.
json matched_ratio_json(const std::vector<BaselineRung>& baseline, const std::vector<Rung>& ladder, size_t elements) {
  const BaselineRung& last = baseline.back();
  const Rung* match = matching_rung(ladder, last.subset);
  if (!match) return {{"available", false}};
  return {{"available", true},
          {"baseline_paths", last.paths},
          {"baseline_error", last.subset},
          {"baseline_all_columns_seconds", last.total_seconds(elements)},
          {"one_pass_paths", match->paths},
          {"one_pass_error", match->subset},
          {"one_pass_seconds", match->seconds},
          {"ratio", last.total_seconds(elements) / match->seconds}};
}

void print_matched_ratio(const json& m) {
  if (!m["available"].get<bool>()) {
    std::printf("    ratio at matched accuracy: no one-pass rung was as accurate on these columns\n");
    return;
  }
  std::printf("    ratio at matched accuracy (measured, same %d columns, one-pass error <= baseline error):\n"
              "      per-element %d paths: error %.4f, %.1f s for all columns; one-pass %d paths: error %.4f,\n"
              "      %.3f s  =>  t_per_element_total / t_one_pass = %.1f\n",
              kBaselineColumns, m["baseline_paths"].get<int>(), m["baseline_error"].get<double>(),
              m["baseline_all_columns_seconds"].get<double>(), m["one_pass_paths"].get<int>(),
              m["one_pass_error"].get<double>(), m["one_pass_seconds"].get<double>(), m["ratio"].get<double>());
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

void write_json(const std::string& path, const json& report) {
  fenestra::write_atomically(path, [&](std::ostream& out) { out << report.dump(2) << "\n"; });
  std::printf("wrote %s\n", path.c_str());
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
// Estimators side by side: the stratified first decisions (render.sampler "sobol", the default)
// against independent random numbers (the estimator before them), same scene, same reference.

Scene with_sampler(const Scene& base, fenestra::RenderSettings::Sampler sampler) {
  Scene scene = base;
  scene.render.sampler = sampler;
  return scene;
}

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

// ---------------------------------------------------------------------------------------------
// Thick walls: the same scene with its domain 0.3 m thick, against the zero-thickness wall

constexpr int kWallPaths = 2048;
constexpr float kWallThickness = 0.3f;  // meters

struct WallCost {
  double seconds = 0.0;
  size_t record_bytes = 0;
  double relative_variance = 0.0;  // mean over sensors and open sets of (standard error / value)^2
  std::array<double, 3> set_variance{};  // the same, per open set (all open, random half, bands)
  double rays_per_path = 0.0;
};

// All open, a random half, bands of four in ten.
std::vector<std::vector<uint8_t>> wall_open_sets(size_t n) {
  std::vector<std::vector<uint8_t>> sets(3, std::vector<uint8_t>(n, 0));
  std::mt19937 rng(5);
  for (size_t k = 0; k < n; ++k) sets[0][k] = 1, sets[1][k] = rng() % 2, sets[2][k] = k % 10 < 4;
  return sets;
}

// One pass, and the run's own noise on the exact values of a few open sets (all open, half, a band).
WallCost wall_cost(const Scene& base) {
  const Scene scene = with_paths(base, kWallPaths, kReferenceSeed + 7);
  const uint64_t rays_before = fenestra::rays_traced();
  const auto start = Clock::now();
  const fenestra::Contributions c = fenestra::compute_contributions(scene);
  WallCost cost;
  cost.seconds = seconds_since(start);
  cost.rays_per_path = static_cast<double>(fenestra::rays_traced() - rays_before) /
                       static_cast<double>(kWallPaths * scene.sensors.size());
  for (const auto& r : c.records) cost.record_bytes += r.memory_bytes();
  const std::vector<std::vector<uint8_t>> sets = wall_open_sets(c.element_count());
  size_t count = 0;
  for (size_t s = 0; s < sets.size(); ++s) {
    const fenestra::SensorValues v = c.evaluate(sets[s]);
    size_t set_count = 0;
    for (Eigen::Index i = 0; i < v.value.size(); ++i) {
      if (!(v.value[i] > 0.0)) continue;
      const double r = std::pow(v.standard_error[i] / v.value[i], 2);
      cost.relative_variance += r, cost.set_variance[s] += r, ++count, ++set_count;
    }
    cost.set_variance[s] /= std::max<size_t>(1, set_count);
  }
  cost.relative_variance /= std::max<size_t>(1, count);
  return cost;
}

json wall_cost_json(const WallCost& w) {
  return {{"seconds", w.seconds},
          {"record_bytes", w.record_bytes},
          {"rays_per_path", w.rays_per_path},
          {"relative_variance", w.relative_variance},
          {"relative_variance_per_set", {{"all_open", w.set_variance[0]}, {"random_half", w.set_variance[1]},
                                         {"bands", w.set_variance[2]}}}};
}

// What the wall's light costs a forward path tracer: `evaluate` with the same open sets really cut
// (one opening per open element), seconds x mean relative variance over the sets.
constexpr int kForwardPaths = 256;

double forward_cost(const Scene& base) {
  const Scene scene = with_paths(base, kForwardPaths, kReferenceSeed + 11);
  double seconds = 0.0, variance = 0.0;
  size_t count = 0;
  for (const auto& open : wall_open_sets(scene.domain.element_count())) {
    std::vector<fenestra::OpeningInput> openings;
    for (size_t k = 0; k < open.size(); ++k)
      if (open[k]) {
        const fenestra::Element& e = scene.domain.elements()[k];
        openings.push_back(fenestra::PanelRectangle{e.panel, e.u0, e.u1, e.v0, e.v1});
      }
    const auto start = Clock::now();
    const fenestra::SensorValues v = fenestra::evaluate_openings(scene, openings);
    seconds += seconds_since(start);
    for (Eigen::Index i = 0; i < v.value.size(); ++i)
      if (v.value[i] > 0.0) variance += std::pow(v.standard_error[i] / v.value[i], 2), ++count;
  }
  return seconds * variance / std::max<size_t>(1, count);
}

json thick_wall_comparison(const std::string& scene_path) {
  std::ifstream in(scene_path);
  json text = json::parse(in);
  text["opening_domain"]["thickness"] = kWallThickness;
  const std::string dir = scene_path.substr(0, scene_path.find_last_of('/'));
  const Scene thick = fenestra::parse_scene(text.dump(), dir, scene_path + " (0.3 m walls)");
  text["opening_domain"]["thickness"] = 0.0;
  const Scene thin = fenestra::parse_scene(text.dump(), dir, scene_path);
  const WallCost a = wall_cost(thin), b = wall_cost(thick);
  const double time_ratio = (b.seconds * b.relative_variance) / (a.seconds * a.relative_variance);
  const double memory_ratio = static_cast<double>(b.record_bytes) / static_cast<double>(a.record_bytes);
  std::printf("[5] Thick walls: the domain as a %.1f m wall against the zero-thickness one, %d paths per sensor\n"
              "    %-8s %9s %12s %10s %14s  %s\n", kWallThickness, kWallPaths, "wall", "seconds", "records MiB",
              "rays/path", "rel. variance", "(all open, random half, bands)");
  for (const auto& [name, w] : {std::pair<const char*, const WallCost&>{"thin", a}, {"0.3 m", b}})
    std::printf("    %-8s %9.2f %12.1f %10.1f %14.3g  (%.3g, %.3g, %.3g)\n", name, w.seconds, mib(w.record_bytes),
                w.rays_per_path, w.relative_variance, w.set_variance[0], w.set_variance[1], w.set_variance[2]);
  std::printf("    time to the same accuracy (seconds x relative variance): %.2f x the thin wall's; path-record "
              "memory %.2f x\n", time_ratio, memory_ratio);
  const double forward_ratio = forward_cost(thick) / forward_cost(thin);
  std::printf("    the same sets really cut (evaluate, %d paths): time to the same accuracy %.2f x the thin wall's\n\n",
              kForwardPaths, forward_ratio);
  return {{"paths", kWallPaths},
          {"thickness_m", kWallThickness},
          {"thin", wall_cost_json(a)},
          {"thick", wall_cost_json(b)},
          {"time_to_accuracy_ratio", time_ratio},
          {"forward_time_to_accuracy_ratio", forward_ratio},
          {"record_memory_ratio", memory_ratio}};
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
