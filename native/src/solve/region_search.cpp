#include "solve/region_search.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace fenestra {

RegionSearch::RegionSearch(const Contributions& c, const OpeningDomain& domain, const std::vector<PanelRectangle>& start)
    : c_(c), domain_(domain), rectangles_(start) {
  const size_t sensors = c.records.size(), elements = c.element_count();
  path_values_.resize(sensors);
  element_begin_.resize(sensors);
  element_paths_.resize(sensors);
  changes_.resize(sensors);
  values_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sensors));
  const OpenRegion region(domain, start);
  tbb::parallel_for(size_t(0), sensors, [&](size_t i) {
    const SensorRecord& r = c.records[i];
    std::vector<uint32_t>& begin = element_begin_[i];
    std::vector<uint32_t>& paths = element_paths_[i];
    std::vector<int32_t> met;
    begin.assign(elements + 1, 0);
    for (size_t p = 0; p < r.path_count(); ++p) {  // counts, then offsets, then fill
      path_elements(r, p, &met);
      for (int32_t k : met) ++begin[k + 1];
    }
    for (size_t k = 0; k < elements; ++k) begin[k + 1] += begin[k];
    paths.resize(begin[elements]);
    std::vector<uint32_t> next(begin.begin(), begin.end() - 1);
    path_values_[i].resize(r.path_count());
    double sum = 0.0;
    const auto is_open = [&](int32_t k, const PanelPoint& q) { return region.is_open(k, q); };
    for (size_t p = 0; p < r.path_count(); ++p) {
      path_elements(r, p, &met);
      for (int32_t k : met) paths[next[k]++] = static_cast<uint32_t>(p);
      sum += path_values_[i][p] = path_value_in_region(r, p, is_open);
    }
    values_[static_cast<Eigen::Index>(i)] = r.path_count() ? sum / static_cast<double>(r.path_count()) : 0.0;
  });
}

const Eigen::VectorXd& RegionSearch::try_region(const std::vector<PanelRectangle>& candidate,
                                                const std::vector<int>& elements) {
  candidate_ = candidate;
  candidate_values_ = values_;
  const OpenRegion region(domain_, candidate);
  tbb::parallel_for(size_t(0), c_.records.size(), [&](size_t i) {
    const SensorRecord& r = c_.records[i];
    std::vector<Change>& changes = changes_[i];
    changes.clear();
    std::vector<uint32_t> paths;
    for (int k : elements)
      paths.insert(paths.end(), element_paths_[i].begin() + element_begin_[i][k],
                   element_paths_[i].begin() + element_begin_[i][k + 1]);
    std::sort(paths.begin(), paths.end());
    paths.erase(std::unique(paths.begin(), paths.end()), paths.end());
    const auto is_open = [&](int32_t k, const PanelPoint& q) { return region.is_open(k, q); };
    double delta = 0.0;
    for (uint32_t p : paths) {
      const double v = path_value_in_region(r, p, is_open);
      if (v != path_values_[i][p]) {
        delta += v - path_values_[i][p];
        changes.push_back({p, v});
      }
    }
    if (r.path_count()) candidate_values_[static_cast<Eigen::Index>(i)] += delta / static_cast<double>(r.path_count());
  });
  return candidate_values_;
}

void RegionSearch::accept() {
  rectangles_ = candidate_;
  values_ = candidate_values_;
  for (size_t i = 0; i < changes_.size(); ++i) {
    for (const Change& ch : changes_[i]) path_values_[i][ch.path] = ch.value;
    changes_[i].clear();
  }
}

}  // namespace fenestra
