#include "solve/cut_region_search.h"

#include <algorithm>
#include <utility>

namespace fenestra {

CutRegionSearch::CutRegionSearch(RecordQueries& records, std::vector<PanelRectangle> start, int paths,
                                 uint64_t stream)
    : records_(records), paths_(paths), stream_(stream), rects_(std::move(start)) {
  current_ = cut(rects_, paths_, &current_whole_);
}

const Eigen::VectorXd& CutRegionSearch::try_region(const std::vector<PanelRectangle>& candidate) {
  tried_ = candidate;
  tried_values_ = cut(candidate, paths_, &tried_whole_);
  return tried_values_.value;
}

Eigen::VectorXd CutRegionSearch::rough_values(const std::vector<PanelRectangle>& candidate) {
  const int rough_paths = paths_ > 0 ? std::max(1, paths_ / 2) : 0;
  if (!rough_current_) {
    ++rough_cuts_;
    rough_current_ = traced(rects_, rough_paths, nullptr, nullptr);
  }
  ++rough_cuts_;
  return traced(candidate, rough_paths, &*rough_current_, nullptr).value;
}

void CutRegionSearch::accept() {
  rects_ = tried_;
  current_ = tried_values_;
  current_whole_ = tried_whole_;
  rough_current_.reset();
}

const SensorValues& CutRegionSearch::whole() {
  if (!current_whole_) current_ = cut(rects_, paths_, &current_whole_);
  return current_;
}

SensorValues CutRegionSearch::cut(const std::vector<PanelRectangle>& rects, int paths, bool* whole) {
  const bool every_sensor = cuts_++ == 0 || &rects == &rects_;  // the start, or the current ones again
  return traced(rects, paths, every_sensor ? nullptr : &current_, whole);
}

SensorValues CutRegionSearch::traced(const std::vector<PanelRectangle>& rects, int paths, const SensorValues* base,
                                     bool* whole) {
  const std::vector<OpeningInput> openings(rects.begin(), rects.end());
  const auto sensors = static_cast<size_t>(records_.contributions().E.rows());
  sensors_cut_ += sensors;
  const std::vector<size_t> reached =
      base ? records_.sensors_reached(rects_, rects) : std::vector<size_t>{};
  if (!base || reached.size() == sensors) {
    sensors_traced_ += sensors;
    if (whole) *whole = true;
    return records_.cut(openings, paths, stream_);
  }
  if (whole) *whole = false;
  sensors_traced_ += reached.size();
  SensorValues out = *base;
  if (reached.empty()) return out;
  const SensorValues part = records_.cut_at(openings, paths, stream_, reached);
  for (size_t i = 0; i < reached.size(); ++i) {
    const auto at = static_cast<Eigen::Index>(reached[i]), from = static_cast<Eigen::Index>(i);
    out.value[at] = part.value[from];
    out.standard_error[at] = part.standard_error[from];
  }
  return out;
}

}  // namespace fenestra
