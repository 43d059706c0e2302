#include "solve/thick_wall_merges.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "solve/catalogue_snap.h"
#include "solve/cut_region_search.h"
#include "solve/thick_wall_edges.h"
#include "util/progress.h"

namespace fenestra {
namespace {

double snapped(double x, double unit) { return unit > 0.0 ? unit * std::round(x / unit) : x; }

double area(const PanelRectangle& r) { return r.width() * r.height(); }

bool thick(const OpeningDomain& domain, const PanelRectangle& r) {
  return domain.panels()[static_cast<size_t>(r.panel)].thickness > 0.0f;
}

// The openings with i and j (i < j) replaced by `joint`, placed where i was.
std::vector<PanelRectangle> with_merged(const std::vector<PanelRectangle>& openings, size_t i, size_t j,
                                        const PanelRectangle& joint) {
  std::vector<PanelRectangle> out = openings;
  out[i] = joint;
  out.erase(out.begin() + static_cast<std::ptrdiff_t>(j));
  return out;
}

// The openings with only opening i left on its panel.
std::vector<PanelRectangle> alone_on_its_panel(const std::vector<PanelRectangle>& openings, size_t i) {
  std::vector<PanelRectangle> out;
  for (size_t k = 0; k < openings.size(); ++k)
    if (k == i || openings[k].panel != openings[i].panel) out.push_back(openings[k]);
  return out;
}

// Opening i's index in alone_on_its_panel(openings, i).
size_t index_alone(const std::vector<PanelRectangle>& openings, size_t i) {
  size_t before = 0;
  for (size_t k = 0; k < i; ++k) before += openings[k].panel != openings[i].panel;
  return before;
}

struct Candidate {
  double error = 0.0;
  std::vector<PanelRectangle> openings;
  size_t merged_index = 0;  // the merged (or kept) opening's index in `openings`
  bool merge = false;       // two openings merged (else others removed)
};

class MergeSearch {
 public:
  MergeSearch(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
              const OpeningConstraints& constraints, const std::vector<PanelRectangle>& start, int paths,
              uint64_t stream, Progress* progress)
      : domain_(domain), closed_(records.contributions().closed.value), objective_(objective),
        constraints_(constraints), search_(records, start, paths, stream), progress_(progress) {
    error_ = error_of(search_.values());
  }

  // One opening on thick panel `panel` instead of its several: each pair merged (merged_openings;
  // with the panel's others kept, and alone) and each opening kept alone, the best by its cut
  // then with its edges searched (when its cut is within kThickWallMergeWorthSearching of the
  // error); kept when that lowers the error.
  // Returns whether it was kept.
  bool one_opening_on(int panel, ThickWallMerges* out) {
    const std::vector<PanelRectangle> now = search_.rectangles();
    const double before = error_;
    Candidate best{std::numeric_limits<double>::infinity(), {}, 0};
    const double unit = edge_steps(domain_.element_size(), constraints_.module, true).back();
    for (size_t i = 0; i < now.size(); ++i) {
      if (now[i].panel != panel) continue;
      consider(alone_on_its_panel(now, i), index_alone(now, i), false, &best);
      for (size_t j = i + 1; j < now.size(); ++j)
        if (now[j].panel == panel)
          for (const PanelRectangle& joint : merged_openings(now[i], now[j], unit)) {
            const std::vector<PanelRectangle> merged = with_merged(now, i, j, joint);
            consider(merged, i, true, &best);
            // The others on the panel may only make up for the two's misplaced light.
            const std::vector<PanelRectangle> alone = alone_on_its_panel(merged, i);
            if (alone.size() < merged.size()) consider(alone, index_alone(merged, i), true, &best);
          }
    }
    if (best.openings.empty() || !(best.error <= kThickWallMergeWorthSearching * before)) return false;
    keep(best.openings);
    refine_edges(domain_, closed_, objective_, constraints_, &search_, progress_, edges_of(best.merged_index));
    ++out->merges_searched;
    error_ = error_of(search_.values());
    if (error_ < before * (1.0 - 1e-9)) {
      const int fewer = static_cast<int>(now.size() - best.openings.size());
      out->merged += best.merge;
      out->removed += fewer - best.merge;
      return true;
    }
    keep(now);  // back to the openings as they were
    return false;
  }

  // One opening removed, the best by its cut, when that lowers the error. Returns whether it was.
  bool remove_one(ThickWallMerges* out) {
    const std::vector<PanelRectangle> now = search_.rectangles();
    Candidate best{error_ * (1.0 - 1e-9), {}, 0};
    for (size_t i = 0; now.size() >= 2 && i < now.size(); ++i) {
      std::vector<PanelRectangle> fewer = now;
      fewer.erase(fewer.begin() + static_cast<std::ptrdiff_t>(i));
      consider(fewer, 0, false, &best);
    }
    if (best.openings.empty()) return false;
    keep(best.openings);
    ++out->removed;
    return true;
  }

  const CutRegionSearch& search() const { return search_; }
  const SensorValues& whole() { return search_.whole(); }

 private:
  double error_of(const Eigen::VectorXd& values) const { return prediction_error(objective_, values - closed_); }

  // The edge search of opening `merged_index` alone, as the thick-wall edge search's; free sizes
  // by single moves only (the joint steps follow), catalogue sizes by pairs of edges too.
  EdgeSearchScope edges_of(size_t merged_index) const {
    EdgeSearchScope scope = thick_wall_edge_scope(domain_, constraints_);
    scope.only_opening = static_cast<int>(merged_index);
    if (!uses_catalogue(domain_, constraints_)) scope.scan_span = 0.0;
    return scope;
  }

  // Cut `openings` (when admissible); `best` becomes them when their error is lower.
  void consider(const std::vector<PanelRectangle>& openings, size_t merged_index, bool merge, Candidate* best) {
    if (!constraint_violations(domain_, openings, constraints_).empty()) return;
    if (progress_) progress_->throw_if_cancelled();
    const double e = error_of(search_.try_region(openings));
    if (e < best->error) *best = {e, openings, merged_index, merge};
  }

  void keep(const std::vector<PanelRectangle>& openings) {
    search_.try_region(openings);
    search_.accept();
    error_ = error_of(search_.values());
  }

  const OpeningDomain& domain_;
  const Eigen::VectorXd& closed_;
  const LinearObjective& objective_;
  const OpeningConstraints& constraints_;
  CutRegionSearch search_;
  Progress* progress_;
  double error_ = 0.0;
};

}  // namespace

std::vector<PanelRectangle> merged_openings(const PanelRectangle& a, const PanelRectangle& b, double unit) {
  const PanelRectangle box{a.panel, snapped(std::min(a.u0, b.u0), unit), snapped(std::max(a.u1, b.u1), unit),
                           snapped(std::min(a.v0, b.v0), unit), snapped(std::max(a.v1, b.v1), unit)};
  std::vector<PanelRectangle> out = {box};
  const double joint_area = area(a) + area(b);
  if (!(joint_area > 0.0) || !(box.width() > 0.0) || !(box.height() > 0.0)) return out;
  const double cu = (area(a) * (a.u0 + a.u1) + area(b) * (b.u0 + b.u1)) / (2.0 * joint_area);
  const double cv = (area(a) * (a.v0 + a.v1) + area(b) * (b.v0 + b.v1)) / (2.0 * joint_area);
  const double w = std::sqrt(joint_area * box.width() / box.height()), h = joint_area / w;
  const PanelRectangle joint{a.panel, snapped(cu - 0.5 * w, unit), snapped(cu + 0.5 * w, unit),
                             snapped(cv - 0.5 * h, unit), snapped(cv + 0.5 * h, unit)};
  if (joint != box && joint.width() > 0.0 && joint.height() > 0.0) out.push_back(joint);
  return out;
}

ThickWallMerges merge_thick_wall_openings(const OpeningDomain& domain, RecordQueries& records,
                                          const LinearObjective& objective, const OpeningConstraints& constraints,
                                          const std::vector<PanelRectangle>& start, int paths, uint64_t stream,
                                          Progress* progress) {
  ThickWallMerges out;
  MergeSearch search(domain, records, objective, constraints, start, paths, stream, progress);
  // Each thick panel with several openings once (a search of one opening's edges each), then
  // removals while they gain (a cut each).
  std::vector<int> panels;
  for (const PanelRectangle& r : start)
    if (thick(domain, r) && std::count_if(start.begin(), start.end(), [&](const PanelRectangle& o) {
          return o.panel == r.panel;
        }) > 1 && std::find(panels.begin(), panels.end(), r.panel) == panels.end())
      panels.push_back(r.panel);
  for (const int panel : panels) search.one_opening_on(panel, &out);
  while (search.remove_one(&out)) {
  }
  out.openings = search.search().rectangles();
  out.values = search.whole();
  out.cuts = search.search().cuts();
  out.rough_cuts = search.search().rough_cuts();
  out.sensors_traced = search.search().sensors_traced();
  out.sensors_cut = search.search().sensors_cut();
  return out;
}

}  // namespace fenestra
