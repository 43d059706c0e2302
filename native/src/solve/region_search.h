#pragma once
// Exact sensor values of an open region (rectangles on panels), updated incrementally: a change
// re-evaluates only the paths that met the domain where it changed (the strips an edge swept), so
// a step of a few centimetres costs a few centimetres' worth of paths. What the edge refinement
// searches with.
#include <Eigen/Core>
#include <vector>

#include "solve/record_queries.h"
#include "trace/contributions.h"
#include "trace/open_region.h"

namespace fenestra {

class Progress;

class RegionSearch : public RegionQueries {
 public:
  // With `progress`, building the index polls cancellation (throws Cancelled): on records of a
  // hundred thousand paths per sensor it takes most of a second.
  RegionSearch(const Contributions& c, const OpeningDomain& domain, const std::vector<PanelRectangle>& start,
               const Progress* progress = nullptr);

  const Eigen::VectorXd& values() const override { return values_; }  // per sensor, mean over its paths
  const std::vector<PanelRectangle>& rectangles() const override { return rectangles_; }
  // Values with `candidate` instead of the current rectangles. Remembered until the next try, so
  // that accept() can take it.
  const Eigen::VectorXd& try_region(const std::vector<PanelRectangle>& candidate) override;
  void accept() override;
  // Paths re-evaluated by tries so far (over all sensors).
  size_t paths_evaluated() const { return paths_evaluated_; }
  // Bytes of the index and the per-path values (the cost model's edge_search_index).
  size_t memory_bytes() const;

 private:
  // A point where a path met an element (as OpenRegion tests it, inside the element's cell), and
  // which of the path's points it is: event `index` (an escape), or condition entry `index`.
  struct Met {
    float u, v;
    uint32_t path;
    uint32_t index : 31;
    uint32_t is_event : 1;
  };
  // Per sensor: the open flags of its points for the current rectangles.
  struct PointFlags {
    std::vector<uint8_t> event, condition;
    uint8_t& of(const Met& m) { return m.is_event ? event[m.index] : condition[m.index]; }
  };
  // What a try changes for one sensor: the points whose flag flips, and the paths' new values.
  struct Try {
    std::vector<const Met*> flipped;
    std::vector<std::pair<uint32_t, double>> values;
    std::vector<uint32_t> paths;  // scratch: the paths the flipped points belong to
  };
  // The met points of a sensor that lie in one of the strips (with a little slack).
  template <typename Visit>
  void points_in(size_t sensor, const std::vector<PanelRectangle>& strips, Visit visit) const;

  const Contributions& c_;
  const OpeningDomain& domain_;
  std::vector<PanelRectangle> rectangles_, candidate_;
  OpenRegion candidate_region_;
  Eigen::VectorXd values_, candidate_values_;
  std::vector<std::vector<double>> path_values_;  // [sensor][path]
  // Per sensor, the met points of each element, sorted by u (CSR: begin[k] .. begin[k + 1]).
  std::vector<std::vector<uint32_t>> element_begin_;
  std::vector<std::vector<Met>> met_;
  std::vector<PointFlags> open_;
  std::vector<Try> tries_;  // per sensor, of the last try
  size_t paths_evaluated_ = 0;
};

// Panel rectangles that cover every point inside exactly one of a and b (none when they are equal):
// the strips each moved edge swept, across both rectangles' extent.
std::vector<PanelRectangle> changed_strips(const PanelRectangle& a, const PanelRectangle& b);

}  // namespace fenestra
