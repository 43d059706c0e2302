#pragma once
// A region search whose values are real cuts: the scene path-traced with the openings cut
// (RecordQueries::cut, reveals in thick walls), so that any rectangle is evaluated, whatever grid
// the records were traced on. The same random numbers for every candidate (one seed), so that
// nearby candidates differ by the light their change makes, not by noise of their own. A candidate
// that changes the openings of some panels only is traced at the sensors whose records met them
// (RecordQueries::sensors_meeting); the others keep their values, which their own paths, never
// reaching those panels, would give again bit for bit.
#include <optional>
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
  // Sensors traced over every cut and rough cut, and what tracing every sensor each time would
  // have been.
  size_t sensors_traced() const { return sensors_traced_; }
  size_t sensors_cut() const { return sensors_cut_; }

 private:
  SensorValues cut(const std::vector<PanelRectangle>& rects, int paths);  // counted in cuts()
  // `rects` cut at the sensors its change from the current rectangles can reach, the others'
  // values taken from `base` (the current rectangles' at the same paths; nullptr: every sensor).
  SensorValues traced(const std::vector<PanelRectangle>& rects, int paths, const SensorValues* base);

  RecordQueries& records_;
  int paths_;
  uint64_t stream_;
  std::vector<PanelRectangle> rects_, tried_;
  SensorValues current_, tried_values_;
  std::optional<SensorValues> rough_current_;  // the current rectangles' rough cut, when asked
  int cuts_ = 0, rough_cuts_ = 0;
  size_t sensors_traced_ = 0, sensors_cut_ = 0;
};

}  // namespace fenestra
