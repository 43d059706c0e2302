#pragma once
// A region search whose values are real cuts: the scene path-traced with the openings cut
// (RecordQueries::cut, reveals in thick walls), so that any rectangle is evaluated, whatever grid
// the records were traced on. The same random numbers for every candidate (one seed), so that
// nearby candidates differ mostly by the light their change makes (their sky samples, aimed at
// each candidate's openings, differ too). A candidate is traced at the sensors its change from the
// current rectangles can reach (RecordQueries::sensors_reached); the others keep the current
// values, whose light their paths, never coming near the change, would find again within the
// noise; their difference is then 0, as a comparison of candidates wants.
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

  // The current rectangles' values with their standard errors (the sensors a change did not reach
  // keep the values cut before it).
  const SensorValues& current() const { return current_; }
  // The same from a cut of every sensor (cut once, unless the current values are one): the values
  // a search hands on.
  const SensorValues& whole();
  int cuts() const { return cuts_; }
  int rough_cuts() const { return rough_cuts_; }
  // Sensors traced over every cut and rough cut, and what tracing every sensor each time would
  // have been.
  size_t sensors_traced() const { return sensors_traced_; }
  size_t sensors_cut() const { return sensors_cut_; }

 private:
  // Counted in cuts(); *whole: whether every sensor was traced.
  SensorValues cut(const std::vector<PanelRectangle>& rects, int paths, bool* whole);
  // `rects` cut at the sensors its change from the current rectangles can reach, the others'
  // values taken from `base` (the current rectangles' at the same paths; nullptr: every sensor).
  SensorValues traced(const std::vector<PanelRectangle>& rects, int paths, const SensorValues* base, bool* whole);

  RecordQueries& records_;
  int paths_;
  uint64_t stream_;
  std::vector<PanelRectangle> rects_, tried_;
  SensorValues current_, tried_values_;
  std::optional<SensorValues> rough_current_;  // the current rectangles' rough cut, when asked
  bool current_whole_ = true, tried_whole_ = true;  // the values come from a cut of every sensor
  int cuts_ = 0, rough_cuts_ = 0;
  size_t sensors_traced_ = 0, sensors_cut_ = 0;
};

}  // namespace fenestra
