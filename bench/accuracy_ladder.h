#pragma once
// [2] Time to accuracy: the one-pass contribution matrix E at doubling path counts (the ladder),
// each rung's errors against a reference of 16x the top rung's paths, until both accuracy targets
// are met; the time and memory that takes, measured or extrapolated at 1/sqrt(paths).
#include <cmath>
#include <cstdint>
#include <vector>

#include "bench_common.h"

namespace bench {

// Accuracy targets.
inline constexpr double kFrobeniusTarget = 0.02;  // ||E - E_ref||_F / ||E_ref||_F
inline constexpr double kAllOpenTarget = 0.01;    // every sensor's |all_open - ref| / ref
// The reference has 16x the paths of the ladder's top rung, so its noise barely shows in the errors.
inline constexpr int kReferenceFactor = 16;
inline constexpr int kFirstRung = 64;
inline constexpr int kPilotPaths = 8192;

// ||E - ref||_F / ||ref||_F.
double relative_frobenius(const MatrixXd& E, const MatrixXd& ref);

// The columns `columns` of `m`, in that order.
MatrixXd take_columns(const MatrixXd& m, const std::vector<int>& columns);

// Largest power-of-two top rung whose 16x reference fits the budget, judged by a pilot run's pace
// (the pilot includes fixed costs, so the estimate errs on the long side).
int choose_top_rung(const Scene& scene, double* pilot_seconds_per_path);

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
Reference run_reference(const Scene& scene, int chunk_paths, int chunks);

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

// Doubles the paths from kFirstRung up to `top`, stopping at the first rung that meets both targets.
std::vector<Rung> one_pass_ladder(const Scene& scene, int top, const Reference& ref, const std::vector<int>& subset);

struct TimeToAccuracy {
  double paths = 0.0, seconds = 0.0, memory_bytes = 0.0, previous_layout_bytes = 0.0;
  bool measured = false;  // false: extrapolated from the top rung
};

// The first rung meeting both targets or, failing that, the top rung scaled by the paths both
// errors would need at 1/sqrt(paths), time and memory growing linearly with paths.
TimeToAccuracy time_to_accuracy(const std::vector<Rung>& ladder);

// The report: JSON ("reference", "ladder", "time_to_accuracy") and printed lines.
json reference_json(const Reference& ref);
void print_reference(const Reference& ref, int top);
json rung_json(const Rung& r);
json time_to_accuracy_json(const TimeToAccuracy& t, const std::vector<Rung>& ladder);
void print_time_to_accuracy(const TimeToAccuracy& t, const std::vector<Rung>& ladder);

}  // namespace bench
