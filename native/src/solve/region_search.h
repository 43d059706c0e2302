#pragma once
// Exact sensor values of an open region (rectangles on panels), updated incrementally: a change
// confined to some elements re-evaluates only the paths that met them. What the edge refinement
// searches with.
#include <Eigen/Core>
#include <vector>

#include "trace/contributions.h"
#include "trace/open_region.h"

namespace fenestra {

class Progress;

class RegionSearch {
 public:
  RegionSearch(const Contributions& c, const OpeningDomain& domain, const std::vector<PanelRectangle>& start);

  const Eigen::VectorXd& values() const { return values_; }  // per sensor, mean over its paths
  const std::vector<PanelRectangle>& rectangles() const { return rectangles_; }
  // Values with `candidate` instead, when it differs from the current region only on `elements`.
  // Remembered until the next try, so that accept() can take it.
  const Eigen::VectorXd& try_region(const std::vector<PanelRectangle>& candidate, const std::vector<int>& elements);
  void accept();

 private:
  struct Change {
    uint32_t path;
    double value;
  };
  const Contributions& c_;
  const OpeningDomain& domain_;
  std::vector<PanelRectangle> rectangles_, candidate_;
  Eigen::VectorXd values_, candidate_values_;
  std::vector<std::vector<double>> path_values_;  // [sensor][path]
  // Per sensor, the paths that met each element (CSR: begin[k] .. begin[k + 1] in paths).
  std::vector<std::vector<uint32_t>> element_begin_, element_paths_;
  std::vector<std::vector<Change>> changes_;  // per sensor, of the last try
};

}  // namespace fenestra
