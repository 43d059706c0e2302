#include "solve/cut_region_search.h"

#include <utility>

namespace fenestra {

CutRegionSearch::CutRegionSearch(RecordQueries& records, std::vector<PanelRectangle> start, int paths,
                                 uint64_t stream)
    : records_(records), paths_(paths), stream_(stream), rects_(std::move(start)) {
  current_ = cut(rects_);
}

const Eigen::VectorXd& CutRegionSearch::try_region(const std::vector<PanelRectangle>& candidate) {
  tried_ = candidate;
  tried_values_ = cut(candidate);
  return tried_values_.value;
}

void CutRegionSearch::accept() {
  rects_ = tried_;
  current_ = tried_values_;
}

SensorValues CutRegionSearch::cut(const std::vector<PanelRectangle>& rects) {
  ++cuts_;
  const std::vector<OpeningInput> openings(rects.begin(), rects.end());
  return records_.cut(openings, paths_, stream_);
}

}  // namespace fenestra
