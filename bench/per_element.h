#pragma once
// [3] The paper's way: one element open at a time, each column of E from two evaluations with real
// cutters, on a few columns spread over the wall, timed to the same accuracy as the one pass.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "accuracy_ladder.h"

namespace bench {

// S: the columns measured (the rest extrapolated).
inline constexpr int kBaselineColumns = 8;

// S columns spread over the wall: k = i * No / S.
std::vector<int> baseline_columns(size_t elements);

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

// Doubles the paths until the S columns are within the Frobenius target or `top` is reached.
std::vector<BaselineRung> baseline_ladder(const Scene& scene, int top, const std::vector<int>& columns,
                                          const Reference& ref);

// JSON of a rung ("baseline").
json baseline_rung_json(const BaselineRung& r, size_t elements);

// Ratio of the baseline's time for all No columns to the one-pass time, at the 2% target. Measured
// when both reached it; else a lower bound (baseline time spent so far) and an extrapolation.
json target_ratio_json(const std::vector<BaselineRung>& baseline, const TimeToAccuracy& one_pass, size_t elements);
void print_target_ratio(const json& r);

// Ratio at the accuracy the baseline did reach, against the first one-pass rung at least as accurate
// on the same columns: both measured, no extrapolation.
json matched_ratio_json(const std::vector<BaselineRung>& baseline, const std::vector<Rung>& ladder, size_t elements);
void print_matched_ratio(const json& m);

}  // namespace bench
