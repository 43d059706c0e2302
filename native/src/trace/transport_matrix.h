#pragma once
// The element transport matrix T of Contributions (trace/contributions.h), from the path records.
// T has elements^2 entries: gigabytes for tens of thousands of elements, whose zeroing and
// symmetrising took tens of seconds that no cancel could stop. It is built in place, block of
// columns by block of columns, polling cancellation between blocks.
#include <Eigen/Core>
#include <vector>

#include "trace/path_record.h"
#include "util/progress.h"

namespace fenestra {

// T(m, n) = (S(m, n) + S(n, m)) / (paths x sensors), S(m, n) the light leaving through n on paths
// that reflected off m before. Reports the stage "assembling the transport matrix"; throws
// Cancelled soon after a cancel.
Eigen::MatrixXd transport_matrix(const std::vector<SensorRecord>& records, size_t elements, int paths_per_sensor,
                                 int threads, Progress* progress);

// What records add to S, entry by entry in the order transport_matrix adds them: a shard of a
// study hands these on instead of its part of T (elements^2 doubles).
struct TransportEntries {
  std::vector<int32_t> from, to;  // m, n
  std::vector<float> value;
  size_t sensors = 0;  // whose records they came from
};
TransportEntries transport_entries(const std::vector<SensorRecord>& records, const Progress* progress = nullptr);

// T from the entries of consecutive shards of one study, in sensor order: the same sums in the
// same order, so bit for bit transport_matrix of the whole study's records.
Eigen::MatrixXd transport_matrix_from_entries(const std::vector<const TransportEntries*>& shards, size_t elements,
                                              int paths_per_sensor, int threads, Progress* progress);

}  // namespace fenestra
