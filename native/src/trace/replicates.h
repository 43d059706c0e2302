#pragma once
// Standard errors from independent replicates. The paths of a sensor fall into kReplicates groups
// (path p in group p % kReplicates); within a group, portal points on each element form a randomly
// shifted low-discrepancy set, independent of the other groups. Group means are therefore i.i.d.,
// and their spread gives an honest standard error for the stratified estimate (a per-path variance
// would overstate it many times).
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace fenestra {

constexpr size_t kReplicates = 16;

inline size_t replicate_of(size_t path) { return path % kReplicates; }

// Paths of `n_paths` in group g.
inline size_t replicate_size(size_t g, size_t n_paths) {
  return n_paths / kReplicates + (g < n_paths % kReplicates ? 1 : 0);
}

// Mean over all paths and its standard error from the per-group sums.
inline void replicate_estimate(const double* group_sums, size_t n_paths, double* mean, double* standard_error) {
  double total = 0.0;
  for (size_t g = 0; g < kReplicates; ++g) total += group_sums[g];
  const double m = n_paths ? total / static_cast<double>(n_paths) : 0.0;
  double var = 0.0;
  size_t groups = 0;
  for (size_t g = 0; g < kReplicates; ++g) {
    const size_t n = replicate_size(g, n_paths);
    if (n == 0) continue;
    const double share = static_cast<double>(n) / static_cast<double>(n_paths);
    const double d = group_sums[g] / static_cast<double>(n) - m;
    var += share * share * d * d;
    ++groups;
  }
  *mean = m;
  // One path fills one group: its spread cannot be told, and an unknown error is infinite.
  *standard_error = groups > 1 ? std::sqrt(var * static_cast<double>(groups) / static_cast<double>(groups - 1))
                               : std::numeric_limits<double>::infinity();
}

struct ReplicateSums {
  std::array<double, kReplicates> sum{};
  void add(size_t path, double x) { sum[replicate_of(path)] += x; }
  void merge(const ReplicateSums& other) {
    for (size_t g = 0; g < kReplicates; ++g) sum[g] += other.sum[g];
  }
  void estimate(size_t n_paths, double* mean, double* standard_error) const {
    replicate_estimate(sum.data(), n_paths, mean, standard_error);
  }
};

}  // namespace fenestra
