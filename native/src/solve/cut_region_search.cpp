#include "solve/cut_region_search.h"

#include <algorithm>
#include <tuple>
#include <utility>

namespace fenestra {
namespace {

// The panels whose openings differ between `a` and `b` (each panel's rectangles as a set).
std::vector<int> changed_panels(const std::vector<PanelRectangle>& a, const std::vector<PanelRectangle>& b) {
  auto on = [](const std::vector<PanelRectangle>& rects, int panel) {
    std::vector<PanelRectangle> out;
    for (const PanelRectangle& r : rects)
      if (r.panel == panel) out.push_back(r);
    std::sort(out.begin(), out.end(), [](const PanelRectangle& x, const PanelRectangle& y) {
      return std::tie(x.u0, x.u1, x.v0, x.v1) < std::tie(y.u0, y.u1, y.v0, y.v1);
    });
    return out;
  };
  std::vector<int> panels;
  for (const auto* rects : {&a, &b})
    for (const PanelRectangle& r : *rects)
      if (std::find(panels.begin(), panels.end(), r.panel) == panels.end()) panels.push_back(r.panel);
  std::vector<int> changed;
  for (int p : panels)
    if (on(a, p) != on(b, p)) changed.push_back(p);
  return changed;
}

}  // namespace

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
  const int rough_paths = paths_ > 0 ? std::max(1, paths_ / 2) : 0;
  if (!rough_current_) {
    ++rough_cuts_;
    rough_current_ = traced(rects_, rough_paths, nullptr);
  }
  ++rough_cuts_;
  return traced(candidate, rough_paths, &*rough_current_).value;
}

void CutRegionSearch::accept() {
  rects_ = tried_;
  current_ = tried_values_;
  rough_current_.reset();
}

SensorValues CutRegionSearch::cut(const std::vector<PanelRectangle>& rects, int paths) {
  ++cuts_;
  return traced(rects, paths, cuts_ > 1 ? &current_ : nullptr);
}

SensorValues CutRegionSearch::traced(const std::vector<PanelRectangle>& rects, int paths, const SensorValues* base) {
  const std::vector<OpeningInput> openings(rects.begin(), rects.end());
  const auto sensors = static_cast<size_t>(records_.contributions().E.rows());
  sensors_cut_ += sensors;
  const std::vector<size_t> reached =
      base ? records_.sensors_meeting(changed_panels(rects_, rects)) : std::vector<size_t>{};
  if (!base || reached.size() == sensors) {
    sensors_traced_ += sensors;
    return records_.cut(openings, paths, stream_);
  }
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
