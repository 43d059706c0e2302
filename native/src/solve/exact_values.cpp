#include "solve/exact_values.h"

#include <algorithm>

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
  // The elements whose state differs from each reference in use.
  std::vector<std::vector<int32_t>> changed(reference_sets_.size());
  for (size_t s = 0; s < reference_sets_.size(); ++s)
    if (reference_users_[s] > 0)
      for (size_t k = 0; k < open.size(); ++k)
        if ((open[k] != 0) != (reference_sets_[s][k] != 0)) changed[s].push_back(static_cast<int32_t>(k));
  const int slot = free_slot();  // the new reference of every sensor evaluated
  reference_sets_[slot] = open;
  std::vector<uint8_t> in_full(sensors, 0);
  std::vector<size_t> evaluated(sensors, 0);
  SensorValues out;
  out.value.resize(static_cast<Eigen::Index>(sensors));
  out.standard_error.resize(static_cast<Eigen::Index>(sensors));
  // A cancelled pass leaves some sensors unevaluated: the bookkeeping below runs before it throws.
  for_each_sensor(sensors, nullptr, [&](size_t i) {
    if (progress_ && progress_->cancelled()) return;
    bool full = false;
    const ReplicateSums sums = sensor_sums(i, open, changed, slot, &full, &evaluated[i]);
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
  return out;
}

// In full: as Contributions::evaluate (the same sums in the same order), keeping each path's
// value. From a reference: its sums, plus the change of every path that met a changed element,
// whose new value it keeps.
ReplicateSums ExactValues::sensor_sums(size_t i, const std::vector<uint8_t>& open,
                                       const std::vector<std::vector<int32_t>>& changed, int slot, bool* in_full,
                                       size_t* evaluated) {
  const SensorRecord& r = c_.records[i];
  std::array<Reference, 2>& refs = references_[i];
  const int last = last_[i], other = 1 - last;
  int from = -1;  // the reference fewer paths' changes separate from `open` (the last on a tie)
  size_t fewest = 0;
  for (int k : {last, other})
    if (refs[k].slot >= 0 && !element_begin_.empty()) {
      const size_t met = paths_met(i, changed[static_cast<size_t>(refs[k].slot)]);
      if (from < 0 || met < fewest) from = k, fewest = met;
    }
  std::vector<uint32_t> paths;
  if (from >= 0 && changed_paths(i, changed[static_cast<size_t>(refs[from].slot)], &paths)) {
    // The reference started from becomes the other; the last becomes `open`.
    refs[from == last ? other : last] = refs[from];
    Reference& to = refs[last];
    for (uint32_t p : paths) {
      const double value = path_value(r, p, open);
      to.sums.add(p, value - to.values[p]);
      to.values[p] = value;
    }
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
  for (size_t i = 0; i < element_begin_.size(); ++i)
    bytes += (element_begin_[i].capacity() + element_paths_[i].capacity()) * sizeof(uint32_t);
  return bytes;
}

}  // namespace fenestra
