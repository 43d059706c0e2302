#include "trace/transport_matrix.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "trace/parallel.h"
#include "util/release_in_background.h"

namespace fenestra {
namespace {

// Columns per block: a block of T is a few megabytes at most for the largest domains the cost
// model admits, written in milliseconds (page faults included).
constexpr Eigen::Index kBlock = 32;

Eigen::Index blocks_of(Eigen::Index n) { return (n + kBlock - 1) / kBlock; }

// Calls add(m, n, value) for the light leaving through element n on paths that reflected off
// element m before, in path order.
template <typename Add>
void for_each_entry(const SensorRecord& rec, const Progress* progress, Add add) {
  for (size_t p = 0; p < rec.path_count(); ++p) {
    if (cancelled_at(progress, p)) progress->throw_if_cancelled();
    const uint32_t b = rec.path_begin[p], e = rec.path_begin[p + 1];
    for (uint32_t j = b; j < e; ++j) {
      const PathEvent& first = rec.events[j];
      if (!first.is_escape()) continue;  // escapes, not their parts, start a transport
      for (uint32_t l = j + 1; l < e; ++l) {
        const PathEvent& later = rec.events[l];
        if (!later.is_light() && later.element() != first.element()) add(first.element(), later.element(), later.value());
      }
    }
  }
}

void accumulate(const SensorRecord& rec, Eigen::MatrixXd* transport, const Progress* progress) {
  for_each_entry(rec, progress, [&](int32_t m, int32_t n, float v) { (*transport)(m, n) += v; });
}

Eigen::MatrixXd zeroed(Eigen::Index n, int threads, Progress* progress) {
  Eigen::MatrixXd T(n, n);
  parallel_tasks(blocks_of(n), threads, progress, [&](size_t block) {
    const Eigen::Index j0 = static_cast<Eigen::Index>(block) * kBlock;
    T.middleCols(j0, std::min(kBlock, n - j0)).setZero();
  });
  return T;
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


// T from `parts` sums added in order by add(part, &S) (zeroed first), then symmetrised over
// paths_per_sensor x sensors paths; a cancel frees it in the background.
template <typename Add>
Eigen::MatrixXd assemble(size_t parts, size_t elements, int paths_per_sensor, size_t sensors, int threads,
                         Progress* progress, Add add) {
  const Eigen::Index n = static_cast<Eigen::Index>(elements), blocks = blocks_of(n);
  if (progress) progress->start("assembling the transport matrix", 2 * blocks + parts);
  Eigen::MatrixXd T;
  try {
    T = zeroed(n, threads, progress);
    for (size_t i = 0; i < parts; ++i) {
      add(i, &T);
      if (progress) progress->advance();
    }
    const double norm = static_cast<double>(static_cast<size_t>(paths_per_sensor) * sensors);
    parallel_tasks(blocks, threads, progress,
                   [&](size_t block) { symmetrise_block_row(static_cast<Eigen::Index>(block), norm, &T); });
  } catch (const Cancelled&) {
    release_in_background(std::move(T));
    throw;
  }
  return T;
}

}  // namespace

Eigen::MatrixXd transport_matrix(const std::vector<SensorRecord>& records, size_t elements, int paths_per_sensor,
                                 int threads, Progress* progress) {
  return assemble(records.size(), elements, paths_per_sensor, records.size(), threads, progress,
                  [&](size_t i, Eigen::MatrixXd* T) { accumulate(records[i], T, progress); });
}

TransportEntries transport_entries(const std::vector<SensorRecord>& records, const Progress* progress) {
  TransportEntries out;
  out.sensors = records.size();
  for (const SensorRecord& rec : records)
    for_each_entry(rec, progress, [&](int32_t m, int32_t n, float v) {
      out.from.push_back(m);
      out.to.push_back(n);
      out.value.push_back(v);
    });
  return out;
}

Eigen::MatrixXd transport_matrix_from_entries(const std::vector<const TransportEntries*>& shards, size_t elements,
                                              int paths_per_sensor, int threads, Progress* progress) {
  const int32_t n = static_cast<int32_t>(elements);
  size_t sensors = 0;
  for (const TransportEntries* s : shards) {
    if (s->from.size() != s->to.size() || s->from.size() != s->value.size())
      throw std::invalid_argument("transport entries: their from, to and value lists differ in length");
    for (size_t i = 0; i < s->from.size(); ++i)
      if (s->from[i] < 0 || s->from[i] >= n || s->to[i] < 0 || s->to[i] >= n)
        throw std::invalid_argument("transport entries name element " + std::to_string(std::max(s->from[i], s->to[i])) +
                                    " of a domain with " + std::to_string(elements));
    sensors += s->sensors;
  }
  return assemble(shards.size(), elements, paths_per_sensor, sensors, threads, progress,
                  [&](size_t part, Eigen::MatrixXd* T) {
                    const TransportEntries& s = *shards[part];
                    for (size_t i = 0; i < s.from.size(); ++i) (*T)(s.from[i], s.to[i]) += s.value[i];
                  });
}

}  // namespace fenestra
