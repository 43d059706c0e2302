#include "trace/transport_matrix.h"

#include <algorithm>

#include "trace/parallel.h"
#include "util/release_in_background.h"

namespace fenestra {
namespace {

// Columns per block: a block of T is a few megabytes at most for the largest domains the cost
// model admits, written in milliseconds (page faults included).
constexpr Eigen::Index kBlock = 32;
// Paths between two polls while accumulating (well under a millisecond).
constexpr size_t kPollPaths = 4096;

Eigen::Index blocks_of(Eigen::Index n) { return (n + kBlock - 1) / kBlock; }

// Light leaving through element n on paths that reflected off element m before, summed.
void accumulate(const SensorRecord& rec, Eigen::MatrixXd* transport, const Progress* progress) {
  for (size_t p = 0; p < rec.path_count(); ++p) {
    if (progress && p % kPollPaths == 0) progress->throw_if_cancelled();
    const uint32_t b = rec.path_begin[p], e = rec.path_begin[p + 1];
    for (uint32_t j = b; j < e; ++j) {
      const PathEvent& first = rec.events[j];
      if (!first.is_escape()) continue;  // escapes, not their parts, start a transport
      for (uint32_t l = j + 1; l < e; ++l) {
        const PathEvent& later = rec.events[l];
        if (!later.is_light() && later.element() != first.element())
          (*transport)(first.element(), later.element()) += later.value();
      }
    }
  }
}

// T(i, j) and T(j, i) both become (T(i, j) + T(j, i)) / norm, over the block row `block` and the
// blocks right of it; distinct block rows touch distinct entries.
void symmetrise_block_row(Eigen::Index block, double norm, Eigen::MatrixXd* t) {
  Eigen::MatrixXd& T = *t;
  const Eigen::Index n = T.rows(), i0 = block * kBlock, i1 = std::min(n, i0 + kBlock);
  for (Eigen::Index j0 = i0; j0 < n; j0 += kBlock) {
    const Eigen::Index j1 = std::min(n, j0 + kBlock);
    for (Eigen::Index j = j0; j < j1; ++j)
      for (Eigen::Index i = i0; i < std::min(i1, j + 1); ++i) {
        const double v = (T(i, j) + T(j, i)) / norm;
        T(i, j) = v;
        T(j, i) = v;
      }
  }
}

}  // namespace

Eigen::MatrixXd transport_matrix(const std::vector<SensorRecord>& records, size_t elements, int paths_per_sensor,
                                 int threads, Progress* progress) {
  const Eigen::Index n = static_cast<Eigen::Index>(elements), blocks = blocks_of(n);
  if (progress) progress->start("assembling the transport matrix", 2 * blocks + records.size());
  Eigen::MatrixXd T(n, n);
  try {
    parallel_tasks(blocks, threads, progress, [&](size_t block) {
      const Eigen::Index j0 = static_cast<Eigen::Index>(block) * kBlock;
      T.middleCols(j0, std::min(kBlock, n - j0)).setZero();
    });
    for (const SensorRecord& rec : records) {
      accumulate(rec, &T, progress);
      if (progress) progress->advance();
    }
    const double norm = static_cast<double>(static_cast<size_t>(paths_per_sensor) * records.size());
    parallel_tasks(blocks, threads, progress,
                   [&](size_t block) { symmetrise_block_row(static_cast<Eigen::Index>(block), norm, &T); });
  } catch (const Cancelled&) {
    release_in_background(std::move(T));
    throw;
  }
  return T;
}

}  // namespace fenestra
