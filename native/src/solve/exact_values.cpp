#include "solve/exact_values.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "trace/path_record.h"
#include "util/progress.h"

namespace fenestra {
namespace {

// A set whose changed elements were met by more than this share of the paths is evaluated in
// full (and becomes the reference): a search over scattered paths would cost about as much.
constexpr double kMaxShareFromReference = 0.5;

// Each sensor's value and standard error from its replicate sums (sums_of(i)), in parallel,
// polling for a cancel.
template <typename SumsOf>
SensorValues from_sums(const Contributions& c, const Progress* progress, SumsOf sums_of) {
  const size_t sensors = c.records.size();
  SensorValues out;
  out.value.resize(static_cast<Eigen::Index>(sensors));
  out.standard_error.resize(static_cast<Eigen::Index>(sensors));
  tbb::parallel_for(size_t(0), sensors, [&](size_t i) {
    if (progress && progress->cancelled()) return;
    const ReplicateSums sums = sums_of(i);
    const auto e = static_cast<Eigen::Index>(i);
    sums.estimate(c.records[i].path_count(), &out.value[e], &out.standard_error[e]);
  });
  if (progress) progress->throw_if_cancelled();
  return out;
}

}  // namespace

const SensorValues& ExactValues::operator()(const std::vector<uint8_t>& open) {
  auto it = known_.find(open);
  if (it == known_.end()) it = known_.emplace(open, evaluate(open)).first;
  return it->second;
}

SensorValues ExactValues::evaluate(const std::vector<uint8_t>& open) {
  if (open.size() != c_.element_count() || reference_.empty()) return evaluate_in_full(open);
  std::vector<int32_t> changed;
  for (size_t k = 0; k < open.size(); ++k)
    if ((open[k] != 0) != (reference_[k] != 0)) changed.push_back(static_cast<int32_t>(k));
  if (element_begin_.empty()) build_index();
  double met = 0.0, paths = 0.0;
  for (size_t i = 0; i < c_.records.size(); ++i) {
    paths += static_cast<double>(c_.records[i].path_count());
    for (int32_t k : changed) met += element_begin_[i][k + 1] - element_begin_[i][k];
  }
  if (met > kMaxShareFromReference * paths) return evaluate_in_full(open);
  return evaluate_from_reference(open, changed);
}

// As Contributions::evaluate (the same sums in the same order), keeping each path's value.
SensorValues ExactValues::evaluate_in_full(const std::vector<uint8_t>& open) {
  if (open.size() != c_.element_count()) return c_.evaluate(open, progress_);  // which refuses it
  const size_t sensors = c_.records.size();
  reference_.clear();  // until complete
  reference_values_.resize(sensors);
  reference_sums_.assign(sensors, ReplicateSums{});
  SensorValues out = from_sums(c_, progress_, [&](size_t i) {
    const SensorRecord& r = c_.records[i];
    std::vector<double>& values = reference_values_[i];
    values.resize(r.path_count());
    for (size_t p = 0; p < r.path_count(); ++p) reference_sums_[i].add(p, values[p] = path_value(r, p, open));
    return reference_sums_[i];
  });
  reference_ = open;
  ++full_evaluations_;
  return out;
}

SensorValues ExactValues::evaluate_from_reference(const std::vector<uint8_t>& open, const std::vector<int32_t>& changed) {
  return from_sums(c_, progress_, [&](size_t i) {
    const std::vector<uint32_t>& begin = element_begin_[i];
    std::vector<uint32_t> paths;
    for (int32_t k : changed)
      paths.insert(paths.end(), element_paths_[i].begin() + begin[k], element_paths_[i].begin() + begin[k + 1]);
    std::sort(paths.begin(), paths.end());
    paths.erase(std::unique(paths.begin(), paths.end()), paths.end());
    ReplicateSums sums = reference_sums_[i];
    for (uint32_t p : paths) sums.add(p, path_value(c_.records[i], p, open) - reference_values_[i][p]);
    return sums;
  });
}

void ExactValues::build_index() {
  const size_t sensors = c_.records.size(), elements = c_.element_count();
  element_begin_.resize(sensors);
  element_paths_.resize(sensors);
  tbb::parallel_for(size_t(0), sensors, [&](size_t i) {
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
  size_t bytes = reference_.capacity() + reference_sums_.capacity() * sizeof(ReplicateSums);
  for (size_t i = 0; i < reference_values_.size(); ++i) bytes += reference_values_[i].capacity() * sizeof(double);
  for (size_t i = 0; i < element_begin_.size(); ++i)
    bytes += (element_begin_[i].capacity() + element_paths_[i].capacity()) * sizeof(uint32_t);
  return bytes;
}

}  // namespace fenestra
