#include "accuracy_ladder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "record_memory.h"
#include "annual/annual_contributions.h"
#include "trace/contributions.h"
#include "trace/ray_scene.h"

namespace bench {

namespace {

// Wall-clock budget of the reference; it bounds the top rung and so the whole bench (~2-3 min).
constexpr double kReferenceBudgetSeconds = 60.0;
constexpr int kMaxTopRung = 1 << 16;
// Errors below this many paths are not yet in the 1/sqrt(paths) regime (most entries of E still 0).
constexpr int kSlopeFromPaths = 1024;

// Largest relative deviation over sensors (sensors that receive no light at all are skipped).
double max_relative(const VectorXd& v, const VectorXd& ref) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (ref[i] > 0.0) worst = std::max(worst, std::abs(v[i] - ref[i]) / ref[i]);
  return worst;
}

struct OnePassRun {
  int paths = 0;
  double seconds = 0.0;  // wall clock of compute_contributions: tracing and assembling E
  uint64_t rays = 0;
  size_t memory_bytes = 0;
  size_t previous_layout_bytes = 0;  // the same, with the records laid out as before compaction
  MatrixXd E, E_stderr;
  VectorXd all_open;
};

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

}  // namespace

double relative_frobenius(const MatrixXd& E, const MatrixXd& ref) { return (E - ref).norm() / ref.norm(); }

MatrixXd take_columns(const MatrixXd& m, const std::vector<int>& columns) {
  MatrixXd out(m.rows(), static_cast<Eigen::Index>(columns.size()));
  for (size_t j = 0; j < columns.size(); ++j) out.col(static_cast<Eigen::Index>(j)) = m.col(columns[j]);
  return out;
}

int choose_top_rung(const Scene& scene, double* pilot_seconds_per_path) {
  const OnePassRun pilot = run_one_pass(scene, kPilotPaths, kPilotSeed);
  *pilot_seconds_per_path = pilot.seconds / kPilotPaths;
  int top = kMaxTopRung;
  while (top > kFirstRung && kReferenceFactor * top * *pilot_seconds_per_path > kReferenceBudgetSeconds) top /= 2;
  return top;
}

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

TimeToAccuracy time_to_accuracy(const std::vector<Rung>& ladder) {
  const Rung& top = ladder.back();
  if (top.meets_targets())
    return {double(top.paths), top.seconds, double(top.memory_bytes), double(top.previous_layout_bytes), true};
  const double factor =
      std::max({1.0, path_factor(top.frobenius, kFrobeniusTarget), path_factor(top.all_open, kAllOpenTarget)});
  return {top.paths * factor, top.seconds * factor, top.memory_bytes * factor, top.previous_layout_bytes * factor, false};
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

}  // namespace bench
