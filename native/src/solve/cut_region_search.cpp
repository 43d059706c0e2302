#include "solve/cut_region_search.h"

#include <algorithm>
#include <utility>

namespace fenestra {

CutRegionSearch::CutRegionSearch(RecordQueries& records, std::vector<PanelRectangle> start, int paths,
                                 uint64_t stream)
    : records_(records), paths_(paths), stream_(stream), rects_(std::move(start)) {
  current_ = cut(rects_, paths_);
}

const Eigen::VectorXd& CutRegionSearch::try_region(const std::vector<PanelRectangle>& candidate) {
  tried_ = candidate;
  tried_values_ = cut(candidate, paths_);
  return tried_values_.value;
}

Eigen::VectorXd CutRegionSearch::rough_values(const std::vector<PanelRectangle>& candidate) {
  ++rough_cuts_;
  return traced(candidate, paths_ > 0 ? std::max(1, paths_ / 2) : 0).value;
}

void CutRegionSearch::accept() {
  rects_ = tried_;
  current_ = tried_values_;
}

SensorValues CutRegionSearch::cut(const std::vector<PanelRectangle>& rects, int paths) {
  ++cuts_;
  return traced(rects, paths);
}

SensorValues CutRegionSearch::traced(const std::vector<PanelRectangle>& rects, int paths) {
  const std::vector<OpeningInput> openings(rects.begin(), rects.end());
  return records_.cut(openings, paths, stream_);
}

}  // namespace fenestra
