#pragma once
// Where the solver reads the path records: exact values of sets of open elements and of open
// regions, each element's flip effect, incremental searches over regions, and evaluations with
// real cutters. LocalRecordQueries reads one process's records; a study sharded by sensors over a
// cluster answers the same queries by asking every shard's local queries and concatenating their
// sensors (fenestra.distributed). Every answer is per sensor, so the two agree bit for bit.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "annual/annual_study.h"
#include "annual/hourly_flip_model.h"
#include "solve/climate_model.h"
#include "solve/climate_problem.h"
#include "trace/evaluate.h"
#include "solve/exact_values.h"
#include "solve/flip_effects_cache.h"
#include "solve/change_reach.h"
#include "trace/contributions.h"
#include "trace/open_region.h"
#include "trace/sensor_range.h"

namespace fenestra {

class Progress;
struct Scene;

// An open region whose rectangles change a little at a time (solve/region_search.h).
class RegionQueries {
 public:
  virtual ~RegionQueries() = default;
  virtual const Eigen::VectorXd& values() const = 0;  // per sensor, for rectangles()
  virtual const std::vector<PanelRectangle>& rectangles() const = 0;
  // Values with `candidate` instead; accept() makes the last try the current rectangles.
  virtual const Eigen::VectorXd& try_region(const std::vector<PanelRectangle>& candidate) = 0;
  virtual void accept() = 0;
  // Values of `candidate` good enough to rank many candidates by, the best of which try_region
  // then evaluates (by default try_region's own; CutRegionSearch: a cut of half the paths). Call
  // try_region again before accept(): only its values are kept.
  virtual Eigen::VectorXd rough_values(const std::vector<PanelRectangle>& candidate) { return try_region(candidate); }
};

class RecordQueries {
 public:
  virtual ~RecordQueries() = default;
  // E, E_stderr, A, T, closed and all-open values (its records may be elsewhere).
  virtual const Contributions& contributions() const = 0;
  // Exact values with the elements where open[k] != 0 open (ExactValues: kept, and evaluated from
  // each sensor's reference when near it).
  virtual const SensorValues& exact(const std::vector<uint8_t>& open) = 0;
  // Values of `open` good enough to rule it out before exact() scores it, with the standard error
  // of each against exact()'s (ExactValues::sampled: one changed path in kSampledShare). By
  // default exact()'s own, with no error.
  virtual SensorValues sampled(const std::vector<uint8_t>& open);
  // Exact values of an open region (rectangles on the domain's panels).
  virtual SensorValues evaluate(const std::vector<PanelRectangle>& region) = 0;
  // flip_effects (trace/flip_effects.h): sensors x elements (FlipEffectsCache: kept by `about`).
  virtual Eigen::MatrixXd flip_effects(const std::vector<uint8_t>& about) = 0;
  virtual std::unique_ptr<RegionQueries> region_search(const std::vector<PanelRectangle>& start) = 0;
  // The scene path-traced with these openings really cut (evaluate_openings; `paths` per sensor,
  // 0: the scene's; `stream` of random numbers, 0: the scene's evaluation's).
  virtual SensorValues cut(const std::vector<OpeningInput>& openings, int paths, uint64_t stream) = 0;
  // cut()'s values at the listed sensors only (indices into its answer, in the order given), bit
  // for bit. By default the whole cut, picked; LocalRecordQueries traces only those sensors.
  virtual SensorValues cut_at(const std::vector<OpeningInput>& openings, int paths, uint64_t stream,
                              const std::vector<size_t>& sensors);
  // The sensors (ascending) a change of openings from `before` to `after` can reach: those whose
  // records met an element near it (solve/change_reach.h). By default every sensor.
  virtual std::vector<size_t> sensors_reached(const std::vector<PanelRectangle>& before,
                                              const std::vector<PanelRectangle>& after);
  // Bytes the path records take, over all sensors.
  virtual double record_bytes() const = 0;

  // Climate goals (a climate sky's records; std::invalid_argument without one).
  // Its sources and hours (no per-sensor records): nullptr for another sky.
  virtual std::shared_ptr<const AnnualRecords> annual() const = 0;
  // The problem's hourly flip model about `about` (hourly_flip_model; the `excluded` elements'
  // flips dropped), held where the records are: one shard per block of sensors (climate_model.h).
  virtual std::unique_ptr<ClimateModel> climate_model(const ClimateProblem& problem, const std::vector<uint8_t>& about,
                                                      const std::vector<uint8_t>& excluded) = 0;
  // The tally of the exact year of `open` at the problem's sensors and hours (hourly_state), added
  // over the shards.
  virtual ClimateTally climate_tally(const ClimateProblem& problem, const std::vector<uint8_t>& open) = 0;
  // The annual study of an open region from the records (annual_study).
  virtual AnnualStudy annual_study(const std::vector<PanelRectangle>& region) = 0;
  // The annual study of openings really cut, from paths of their own (annual_study_with_cutters).
  virtual AnnualStudy annual_cut(const std::vector<OpeningInput>& openings, int paths) = 0;
};

class LocalRecordQueries : public RecordQueries {
 public:
  // `c`: the records of `scene`, which cut() traces.
  LocalRecordQueries(const Scene& scene, const Contributions& c, Progress* progress,
                     SensorRange sensors = {});

  const Contributions& contributions() const override { return c_; }
  const SensorValues& exact(const std::vector<uint8_t>& open) override { return exact_(open); }
  SensorValues sampled(const std::vector<uint8_t>& open) override { return exact_.sampled(open, kSampledShare); }
  SensorValues evaluate(const std::vector<PanelRectangle>& region) override;
  Eigen::MatrixXd flip_effects(const std::vector<uint8_t>& about) override;
  std::unique_ptr<RegionQueries> region_search(const std::vector<PanelRectangle>& start) override;
  SensorValues cut(const std::vector<OpeningInput>& openings, int paths, uint64_t stream) override;
  SensorValues cut_at(const std::vector<OpeningInput>& openings, int paths, uint64_t stream,
                      const std::vector<size_t>& sensors) override;
  std::vector<size_t> sensors_reached(const std::vector<PanelRectangle>& before,
                                      const std::vector<PanelRectangle>& after) override;
  double record_bytes() const override;
  std::shared_ptr<const AnnualRecords> annual() const override { return c_.annual; }
  std::unique_ptr<ClimateModel> climate_model(const ClimateProblem& problem, const std::vector<uint8_t>& about,
                                              const std::vector<uint8_t>& excluded) override;
  ClimateTally climate_tally(const ClimateProblem& problem, const std::vector<uint8_t>& open) override;
  // This process's shard of climate_model: the problem's sensors among these records'.
  std::unique_ptr<ClimateShard> climate_shard(const ClimateProblem& problem, const std::vector<uint8_t>& about,
                                              const std::vector<uint8_t>& excluded);
  // Bytes climate_shard() will hold for its model, counted from the records before it is built
  // (hourly_flip_model_reach): whatever the state, the same elements reach the same rows.
  double climate_shard_bytes(const ClimateProblem& problem, const std::vector<uint8_t>& excluded) const;
  AnnualStudy annual_study(const std::vector<PanelRectangle>& region) override;
  AnnualStudy annual_cut(const std::vector<OpeningInput>& openings, int paths) override;

 private:
  const Scene& scene_;
  const Contributions& c_;
  Progress* progress_;
  SensorRange sensors_;  // the scene's sensors the records hold (a shard's block)
  ExactValues exact_;
  FlipEffectsCache flip_effects_;
  std::optional<ChangeReach> reach_;  // built when first asked
  // The problem's rows among these records' sensors: their local indices and rows in the problem.
  void climate_rows(const ClimateProblem& problem, std::vector<int>* local, std::vector<int>* model_rows) const;
};

}  // namespace fenestra
