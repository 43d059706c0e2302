#include "solve/record_queries.h"

#include <stdexcept>
#include <string>

#include "annual/annual_contributions.h"
#include "annual/annual_cut_study.h"
#include "scene/scene.h"
#include "solve/region_search.h"
#include "trace/evaluate.h"
#include "trace/flip_effects.h"
#include "util/progress.h"

namespace fenestra {

SensorValues RecordQueries::sampled(const std::vector<uint8_t>& open) {
  SensorValues values = exact(open);
  values.standard_error.setZero();
  return values;
}

SensorValues RecordQueries::cut_at(const std::vector<OpeningInput>& openings, int paths, uint64_t stream,
                                   const std::vector<size_t>& sensors) {
  const SensorValues all = cut(openings, paths, stream);
  SensorValues out;
  out.value.resize(static_cast<Eigen::Index>(sensors.size()));
  out.standard_error.resize(static_cast<Eigen::Index>(sensors.size()));
  for (size_t i = 0; i < sensors.size(); ++i) {
    const auto s = static_cast<Eigen::Index>(sensors[i]);
    if (s >= all.value.size())
      throw std::invalid_argument("sensor " + std::to_string(s) + " is not one of the cut's " +
                                  std::to_string(all.value.size()));
    out.value[static_cast<Eigen::Index>(i)] = all.value[s];
    out.standard_error[static_cast<Eigen::Index>(i)] = all.standard_error[s];
  }
  return out;
}

std::vector<size_t> RecordQueries::sensors_reached(const std::vector<PanelRectangle>&,
                                                   const std::vector<PanelRectangle>&) {
  return ChangeReach().sensors({}, static_cast<size_t>(contributions().E.rows()));
}

LocalRecordQueries::LocalRecordQueries(const Scene& scene, const Contributions& c, Progress* progress,
                                       SensorRange sensors)
    : scene_(scene), c_(c), progress_(progress), sensors_(sensors), exact_(c, progress) {}

SensorValues LocalRecordQueries::evaluate(const std::vector<PanelRectangle>& region) {
  return c_.evaluate(OpenRegion(scene_.domain, region), progress_);
}

Eigen::MatrixXd LocalRecordQueries::flip_effects(const std::vector<uint8_t>& about) {
  return flip_effects_.about(about, [&] { return fenestra::flip_effects(c_, about, progress_); },
                             [&] { return !(progress_ && progress_->cancelled()); });
}

std::unique_ptr<RegionQueries> LocalRecordQueries::region_search(const std::vector<PanelRectangle>& start) {
  return std::make_unique<RegionSearch>(c_, scene_.domain, start, progress_);
}

SensorValues LocalRecordQueries::cut(const std::vector<OpeningInput>& openings, int paths, uint64_t stream) {
  return evaluate_openings(scene_, openings, progress_, paths, {}, stream);
}

SensorValues LocalRecordQueries::cut_at(const std::vector<OpeningInput>& openings, int paths, uint64_t stream,
                                        const std::vector<size_t>& sensors) {
  return evaluate_openings_at(scene_, openings, sensors, progress_, paths, stream);
}

std::vector<size_t> LocalRecordQueries::sensors_reached(const std::vector<PanelRectangle>& before,
                                                        const std::vector<PanelRectangle>& after) {
  if (!reach_) reach_.emplace(c_, scene_.domain);
  // A shard's worker keeps only the records; records kept elsewhere: E's rows.
  const size_t sensors = c_.records.empty() ? static_cast<size_t>(c_.E.rows()) : c_.sensor_count();
  return reach_->sensors(elements_near_change(scene_.domain, before, after), sensors);
}

double LocalRecordQueries::record_bytes() const {
  double bytes = 0.0;
  for (const SensorRecord& r : c_.records) bytes += static_cast<double>(r.memory_bytes());
  return bytes;
}

void LocalRecordQueries::climate_rows(const ClimateProblem& problem, std::vector<int>* local,
                                      std::vector<int>* model_rows) const {
  const size_t begin = sensors_.begin, end = begin + c_.sensor_count();
  for (size_t r = 0; r < problem.rows.size(); ++r) {
    const size_t sensor = static_cast<size_t>(problem.rows[r]);
    if (sensor < begin || sensor >= end) continue;
    local->push_back(static_cast<int>(sensor - begin));
    model_rows->push_back(static_cast<int>(r));
  }
}

std::unique_ptr<ClimateShard> LocalRecordQueries::climate_shard(const ClimateProblem& problem,
                                                                const std::vector<uint8_t>& about,
                                                                const std::vector<uint8_t>& excluded) {
  std::vector<int> local, model_rows;
  climate_rows(problem, &local, &model_rows);
  // Excluded elements change nothing in the model (their flips are left out).
  HourlyFlipModel part = hourly_flip_model(c_, about, local, problem.columns, progress_, excluded);
  return std::make_unique<ClimateShard>(std::move(part), std::move(model_rows), *problem.objective);
}

double LocalRecordQueries::climate_shard_bytes(const ClimateProblem& problem,
                                               const std::vector<uint8_t>& excluded) const {
  std::vector<int> local, model_rows;
  climate_rows(problem, &local, &model_rows);
  double pairs = 0.0;
  for (size_t n : hourly_flip_model_reach(c_, local, excluded)) pairs += static_cast<double>(n);
  return hourly_flip_model_bytes(static_cast<double>(local.size()), static_cast<double>(problem.columns.hour.size()),
                                 pairs);
}

std::unique_ptr<ClimateModel> LocalRecordQueries::climate_model(const ClimateProblem& problem,
                                                                const std::vector<uint8_t>& about,
                                                                const std::vector<uint8_t>& excluded) {
  std::vector<std::unique_ptr<ClimateShard>> shards;
  shards.push_back(climate_shard(problem, about, excluded));
  return std::make_unique<LocalClimateModel>(*problem.objective, std::move(shards));
}

ClimateTally LocalRecordQueries::climate_tally(const ClimateProblem& problem, const std::vector<uint8_t>& open) {
  std::vector<int> local, model_rows;
  climate_rows(problem, &local, &model_rows);
  const HourlyFlipModel year = hourly_state(c_, open, local, problem.columns, progress_);
  return problem.objective->tally(year.total, year.direct, &model_rows);
}

AnnualStudy LocalRecordQueries::annual_study(const std::vector<PanelRectangle>& region) {
  return fenestra::annual_study(scene_, c_, OpenRegion(scene_.domain, region), progress_);
}

AnnualStudy LocalRecordQueries::annual_cut(const std::vector<OpeningInput>& openings, int paths) {
  return annual_study_with_cutters(scene_, openings, progress_, paths);
}

}  // namespace fenestra
