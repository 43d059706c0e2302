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

}  // namespace fenestra
