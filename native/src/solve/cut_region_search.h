#pragma once
// A region search whose values are real cuts: the scene path-traced with the openings cut
// (RecordQueries::cut, reveals in thick walls), so that any rectangle is evaluated, whatever grid
// the records were traced on. The same random numbers for every candidate (one seed), so that
// nearby candidates differ by the light their change makes, not by noise of their own.
#include <cstdint>
#include <vector>

#include "solve/record_queries.h"

namespace fenestra {

class CutRegionSearch : public RegionQueries {
 public:
  // `paths` per sensor for every cut (0: the scene's), on random numbers of `stream`
  // (RecordQueries::cut).
  CutRegionSearch(RecordQueries& records, std::vector<PanelRectangle> start, int paths, uint64_t stream);

  const Eigen::VectorXd& values() const override { return current_.value; }
  const std::vector<PanelRectangle>& rectangles() const override { return rects_; }
  const Eigen::VectorXd& try_region(const std::vector<PanelRectangle>& candidate) override;
  void accept() override;
  // A cut of half the paths, on the same stream (all of the scene's when `paths` is 0).
  Eigen::VectorXd rough_values(const std::vector<PanelRectangle>& candidate) override;

  // The current rectangles' values with their standard errors.
  const SensorValues& current() const { return current_; }
  int cuts() const { return cuts_; }
  int rough_cuts() const { return rough_cuts_; }

 private:
  SensorValues cut(const std::vector<PanelRectangle>& rects, int paths);  // counted in cuts()
  SensorValues traced(const std::vector<PanelRectangle>& rects, int paths);

  RecordQueries& records_;
  int paths_;
  uint64_t stream_;
  std::vector<PanelRectangle> rects_, tried_;
  SensorValues current_, tried_values_;
  int cuts_ = 0, rough_cuts_ = 0;
};

}  // namespace fenestra
