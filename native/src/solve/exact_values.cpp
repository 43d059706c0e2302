#include "solve/exact_values.h"

#include <algorithm>
#include <cmath>

#include "trace/parallel.h"
#include "trace/path_record.h"
#include "util/progress.h"

namespace fenestra {
namespace {

// A sensor more than this share of whose paths met a changed element is evaluated in full: read
// in order, the others' values cost about as much as reading them all.
constexpr double kMaxShareFromReference = 0.75;
// Changed paths fewer than 1 / this of a sensor's are sorted; more are read off their marks.
constexpr size_t kSortedPathsShare = 32;
// Paths asked of the memory ahead of their reading (prefetch_path).
constexpr size_t kPrefetchAhead = 8;
// A sensor whose changed paths are at most this many times the share is not sampled: all of them
// cost little, and a sample of few would estimate its own error poorly.
constexpr size_t kSampledAtLeast = 64;

// Whether path p is in the sample of one path in `share` (a fixed, scrambled choice: not every
// share-th path, which could follow the replicate groups or the order paths were traced in).
bool in_sample(uint32_t p, uint32_t share) { return share <= 1 || ((p * 2654435761u) >> 8) % share == 0; }

}  // namespace

const SensorValues& ExactValues::operator()(const std::vector<uint8_t>& open) {
  auto it = known_.find(open);
  if (it == known_.end()) it = known_.emplace(open, evaluate(open)).first;
  return it->second;
}

int ExactValues::free_slot() {
  for (size_t s = 0; s < reference_users_.size(); ++s)
    if (reference_users_[s] == 0) return static_cast<int>(s);
  reference_sets_.emplace_back();
  reference_users_.push_back(0);
  return static_cast<int>(reference_sets_.size() - 1);
}

SensorValues ExactValues::evaluate(const std::vector<uint8_t>& open) {
  if (open.size() != c_.element_count()) return c_.evaluate(open, progress_);  // which refuses it
  const size_t sensors = c_.records.size();
  if (references_.empty()) {
    references_.resize(sensors);
    last_.assign(sensors, 0);
  } else if (element_begin_.empty()) {
    build_index();
  }
  const std::vector<std::vector<int32_t>> changed = changed_elements(open);
  const int slot = free_slot();  // the new reference of every sensor evaluated
  reference_sets_[slot] = open;
  std::vector<uint8_t> in_full(sensors, 0);
  std::vector<size_t> evaluated(sensors, 0), reused(sensors, 0);
  const bool after_sample = !sampled_paths_.empty() && open == sampled_set_;  // its paths' values taken
  SensorValues out;
  out.value.resize(static_cast<Eigen::Index>(sensors));
  out.standard_error.resize(static_cast<Eigen::Index>(sensors));
  // A cancelled pass leaves some sensors unevaluated: the bookkeeping below runs before it throws.
  for_each_sensor(sensors, nullptr, [&](size_t i) {
    if (progress_ && progress_->cancelled()) return;
    bool full = false;
    const ReplicateSums sums = sensor_sums(i, open, changed, slot, after_sample ? &sampled_paths_[i] : nullptr, &full,
                                            &evaluated[i], &reused[i]);
    in_full[i] = full;
    const auto e = static_cast<Eigen::Index>(i);
    sums.estimate(c_.records[i].path_count(), &out.value[e], &out.standard_error[e]);
  });
  // The references' users, from the sensors' choices (a cancelled pass leaves some unchanged).
  std::fill(reference_users_.begin(), reference_users_.end(), 0);
  for (const std::array<Reference, 2>& refs : references_)
    for (const Reference& r : refs)
      if (r.slot >= 0) ++reference_users_[static_cast<size_t>(r.slot)];
  for (size_t s = 0; s < reference_sets_.size(); ++s)
    if (reference_users_[s] == 0) std::vector<uint8_t>().swap(reference_sets_[s]);
  if (progress_) progress_->throw_if_cancelled();
  full_evaluations_ += static_cast<size_t>(std::count(in_full.begin(), in_full.end(), 1));
  sensor_evaluations_ += sensors;
  for (size_t n : evaluated) path_evaluations_ += n;
  for (size_t n : reused) sampled_paths_reused_ += n;
  return out;
}

// In full: as Contributions::evaluate (the same sums in the same order), keeping each path's
// value. From a reference: its sums, plus the change of every path that met a changed element,
// whose new value it keeps.
ReplicateSums ExactValues::sensor_sums(size_t i, const std::vector<uint8_t>& open,
                                       const std::vector<std::vector<int32_t>>& changed, int slot,
                                       const SampledPaths* sampled, bool* in_full, size_t* evaluated,
                                       size_t* reused_paths) {
  const SensorRecord& r = c_.records[i];
  std::array<Reference, 2>& refs = references_[i];
  const int last = last_[i], other = 1 - last;
  size_t met = 0;
  const int from = nearer_reference(i, changed, &met);
  std::vector<uint32_t> paths;
  if (from >= 0 && changed_paths(i, changed[static_cast<size_t>(refs[from].slot)], &paths)) {
    // The reference started from becomes the other; the last becomes `open`.
    refs[from == last ? other : last] = refs[from];
    Reference& to = refs[last];
    // The paths the sample of this set evaluated (ascending, as `paths`) are not evaluated again.
    static const SampledPaths kNone;
    const SampledPaths& sample = sampled ? *sampled : kNone;
    size_t s = 0, reused = 0;
    for (size_t n = 0; n < paths.size(); ++n) {
      const uint32_t p = paths[n];
      while (s < sample.paths.size() && sample.paths[s] < p) ++s;
      double value;
      if (s < sample.paths.size() && sample.paths[s] == p) {
        value = sample.values[s], ++reused;
      } else {
        if (n + kPrefetchAhead < paths.size()) prefetch_path(r, paths[n + kPrefetchAhead]);
        value = path_value(r, p, open);
      }
      to.sums.add(p, value - to.values[p]);
      to.values[p] = value;
    }
    *reused_paths = reused;
    to.slot = slot;
    *evaluated = paths.size();
    return to.sums;
  }
  // In full into the other: the last stays as the reference beside it.
  Reference& to = refs[other];
  to.values.resize(r.path_count());
  ReplicateSums sums;
  for (size_t p = 0; p < r.path_count(); ++p) sums.add(p, to.values[p] = path_value(r, p, open));
  to.sums = sums;
  to.slot = slot;
  last_[i] = static_cast<uint8_t>(other);
  *in_full = true;
  *evaluated = r.path_count();
  return sums;
}

std::vector<std::vector<int32_t>> ExactValues::changed_elements(const std::vector<uint8_t>& open) const {
  std::vector<std::vector<int32_t>> changed(reference_sets_.size());
  for (size_t s = 0; s < reference_sets_.size(); ++s)
    if (reference_users_[s] > 0)
      for (size_t k = 0; k < open.size(); ++k)
        if ((open[k] != 0) != (reference_sets_[s][k] != 0)) changed[s].push_back(static_cast<int32_t>(k));
  return changed;
}

int ExactValues::nearer_reference(size_t i, const std::vector<std::vector<int32_t>>& changed, size_t* met) const {
  const std::array<Reference, 2>& refs = references_[i];
  const int last = last_[i];
  int from = -1;
  for (int k : {last, 1 - last})
    if (refs[k].slot >= 0 && !element_begin_.empty()) {
      const size_t n = paths_met(i, changed[static_cast<size_t>(refs[k].slot)]);
      if (from < 0 || n < *met) from = k, *met = n;
    }
  return from;
}

SensorValues ExactValues::sampled(const std::vector<uint8_t>& open, uint32_t share) {
  if (references_.empty() || open.size() != c_.element_count() || known_.count(open)) {
    SensorValues exact = (*this)(open);
    exact.standard_error.setZero();
    return exact;
  }
  if (element_begin_.empty()) build_index();
  share = std::max<uint32_t>(share, 1);
  const std::vector<std::vector<int32_t>> changed = changed_elements(open);
  const size_t sensors = c_.records.size();
  SensorValues out;
  out.value.resize(static_cast<Eigen::Index>(sensors));
  out.standard_error.resize(static_cast<Eigen::Index>(sensors));
  std::vector<size_t> evaluated(sensors, 0);
  sampled_set_ = open;
  sampled_paths_.resize(sensors);
  for_each_sensor(sensors, nullptr, [&](size_t i) {
    if (progress_ && progress_->cancelled()) return sampled_paths_[i].paths.clear();
    const auto e = static_cast<Eigen::Index>(i);
    sampled_sensor(i, open, changed, share, &out.value[e], &out.standard_error[e], &evaluated[i]);
  });
  if (progress_) progress_->throw_if_cancelled();
  for (size_t n : evaluated) sampled_path_evaluations_ += n;
  return out;
}

// Horvitz-Thompson: each changed path is in the sample with probability 1 / share, so the sampled
// changes times share estimate the whole change, with variance share (share - 1) sum d^2 / N^2.
void ExactValues::sampled_sensor(size_t i, const std::vector<uint8_t>& open,
                                 const std::vector<std::vector<int32_t>>& changed, uint32_t share, double* value,
                                 double* standard_error, size_t* evaluated) {
  const SensorRecord& r = c_.records[i];
  const size_t n = r.path_count();
  size_t met = 0;
  const int from = nearer_reference(i, changed, &met);
  SampledPaths& kept = sampled_paths_[i];
  kept.paths.clear(), kept.values.clear();
  if (from < 0) {  // never evaluated (a cancelled pass): every path
    ReplicateSums sums;
    for (size_t p = 0; p < n; ++p) sums.add(p, path_value(r, p, open));
    sums.estimate(n, value, standard_error);
    *standard_error = 0.0, *evaluated = n;
    return;
  }
  const Reference& ref = references_[i][static_cast<size_t>(from)];
  const std::vector<int32_t>& differs = changed[static_cast<size_t>(ref.slot)];
  if (met <= kSampledAtLeast * share) share = 1;  // so few that sampling would save nothing
  std::vector<uint32_t>& paths = kept.paths;
  sampled_paths(i, differs, share, &paths);
  kept.values.resize(paths.size());
  double change = 0.0, squares = 0.0;
  for (size_t k = 0; k < paths.size(); ++k) {
    if (k + kPrefetchAhead < paths.size()) prefetch_path(r, paths[k + kPrefetchAhead]);
    kept.values[k] = path_value(r, paths[k], open);
    const double d = kept.values[k] - ref.values[paths[k]];
    change += d, squares += d * d;
  }
  double reference_value = 0.0, unused = 0.0;
  ref.sums.estimate(n, &reference_value, &unused);
  const double scale = static_cast<double>(share), count = static_cast<double>(n);
  *value = reference_value + scale * change / count;
  *standard_error = std::sqrt(scale * (scale - 1.0) * squares) / count;
  *evaluated = paths.size();
}

void ExactValues::sampled_paths(size_t i, const std::vector<int32_t>& changed, uint32_t share,
                                std::vector<uint32_t>* out) const {
  const std::vector<uint32_t>& begin = element_begin_[i];
  const std::vector<uint32_t>& element_paths = element_paths_[i];
  thread_local std::vector<uint8_t> seen;
  if (seen.size() < c_.records[i].path_count()) seen.resize(c_.records[i].path_count(), 0);
  for (int32_t k : changed)
    for (uint32_t e = begin[k], end = begin[k + 1]; e < end; ++e) {
      const uint32_t p = element_paths[e];
      if (!seen[p] && in_sample(p, share)) seen[p] = 1, out->push_back(p);
    }
  for (uint32_t p : *out) seen[p] = 0;
  std::sort(out->begin(), out->end());
}

size_t ExactValues::paths_met(size_t i, const std::vector<int32_t>& changed) const {
  const std::vector<uint32_t>& begin = element_begin_[i];
  size_t n = 0;
  for (int32_t k : changed) n += begin[static_cast<size_t>(k) + 1] - begin[static_cast<size_t>(k)];
  return n;
}

bool ExactValues::changed_paths(size_t i, const std::vector<int32_t>& changed, std::vector<uint32_t>* out) const {
  const std::vector<uint32_t>& begin = element_begin_[i];
  const std::vector<uint32_t>& element_paths = element_paths_[i];
  const size_t path_count = c_.records[i].path_count();
  const auto limit = static_cast<size_t>(kMaxShareFromReference * static_cast<double>(path_count));
  // A path met by several changed elements (a thick wall's conditions name the neighbours) is
  // listed by each: marked when first seen.
  thread_local std::vector<uint8_t> seen;
  if (seen.size() < path_count) seen.resize(path_count, 0);
  for (size_t n = 0; n < changed.size() && out->size() <= limit; ++n)
    for (uint32_t e = begin[changed[n]], end = begin[changed[n] + 1]; e < end && out->size() <= limit; ++e) {
      const uint32_t p = element_paths[e];
      if (!seen[p]) seen[p] = 1, out->push_back(p);
    }
  if (out->size() > limit) {
    for (uint32_t p : *out) seen[p] = 0;
    return false;
  }
  // In the records' order (paths stored one after another are read as a stream): a few sorted,
  // many read off the marks.
  if (out->size() < path_count / kSortedPathsShare) {
    for (uint32_t p : *out) seen[p] = 0;
    std::sort(out->begin(), out->end());
    return true;
  }
  out->clear();
  for (uint32_t p = 0; p < path_count; ++p)
    if (seen[p]) seen[p] = 0, out->push_back(p);
  return true;
}

void ExactValues::build_index() {
  const size_t sensors = c_.records.size(), elements = c_.element_count();
  element_begin_.resize(sensors);
  element_paths_.resize(sensors);
  for_each_sensor(sensors, nullptr, [&](size_t i) {
    const SensorRecord& r = c_.records[i];
    std::vector<uint32_t>& begin = element_begin_[i];
    std::vector<uint32_t>& paths = element_paths_[i];
    std::vector<int32_t> met;
    begin.assign(elements + 1, 0);
    for (size_t p = 0; p < r.path_count(); ++p) {
      path_elements(r, p, &met);
      for (int32_t k : met) ++begin[k + 1];
    }
    for (size_t k = 0; k < elements; ++k) begin[k + 1] += begin[k];
    paths.resize(begin[elements]);
    std::vector<uint32_t> next(begin.begin(), begin.end() - 1);
    for (size_t p = 0; p < r.path_count(); ++p) {
      path_elements(r, p, &met);
      for (int32_t k : met) paths[next[k]++] = static_cast<uint32_t>(p);
    }
  });
}

size_t ExactValues::memory_bytes() const {
  size_t bytes = references_.capacity() * sizeof(std::array<Reference, 2>) + last_.capacity();
  for (const std::vector<uint8_t>& set : reference_sets_) bytes += set.capacity();
  for (const std::array<Reference, 2>& refs : references_)
    for (const Reference& r : refs) bytes += r.values.capacity() * sizeof(double);
  bytes += sampled_set_.capacity() + sampled_paths_.capacity() * sizeof(SampledPaths);
  for (const SampledPaths& kept : sampled_paths_)
    bytes += kept.paths.capacity() * sizeof(uint32_t) + kept.values.capacity() * sizeof(double);
  for (size_t i = 0; i < element_begin_.size(); ++i)
    bytes += (element_begin_[i].capacity() + element_paths_[i].capacity()) * sizeof(uint32_t);
  return bytes;
}

}  // namespace fenestra
