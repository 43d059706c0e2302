#include "solve/record_queries.h"

#include "annual/annual_contributions.h"
#include "annual/annual_cut_study.h"
#include "scene/scene.h"
#include "solve/region_search.h"
#include "trace/evaluate.h"
#include "trace/flip_effects.h"

namespace fenestra {

LocalRecordQueries::LocalRecordQueries(const Scene& scene, const Contributions& c, Progress* progress,
                                       SensorRange sensors)
    : scene_(scene), c_(c), progress_(progress), sensors_(sensors), exact_(c, progress) {}

SensorValues LocalRecordQueries::evaluate(const std::vector<PanelRectangle>& region) {
  return c_.evaluate(OpenRegion(scene_.domain, region), progress_);
}

Eigen::MatrixXd LocalRecordQueries::flip_effects(const std::vector<uint8_t>& about) {
  return fenestra::flip_effects(c_, about, progress_);
}

std::unique_ptr<RegionQueries> LocalRecordQueries::region_search(const std::vector<PanelRectangle>& start) {
  return std::make_unique<RegionSearch>(c_, scene_.domain, start, progress_);
}

SensorValues LocalRecordQueries::cut(const std::vector<OpeningInput>& openings, int paths, uint64_t stream) {
  return evaluate_openings(scene_, openings, progress_, paths, {}, stream);
}

double LocalRecordQueries::record_bytes() const {
  double bytes = 0.0;
  for (const SensorRecord& r : c_.records) bytes += static_cast<double>(r.memory_bytes());
  return bytes;
}

HourlyFlipModel LocalRecordQueries::hourly_model(const std::vector<uint8_t>& about, const std::vector<int>& rows,
                                                 const HourlyColumns& columns, bool flips) {
  return flips ? hourly_flip_model(c_, about, rows, columns, progress_) : hourly_state(c_, about, rows, columns, progress_);
}

AnnualStudy LocalRecordQueries::annual_study(const std::vector<PanelRectangle>& region) {
  return fenestra::annual_study(scene_, c_, OpenRegion(scene_.domain, region), progress_);
}

AnnualStudy LocalRecordQueries::annual_cut(const std::vector<OpeningInput>& openings, int paths) {
  return annual_study_with_cutters(scene_, openings, progress_, paths);
}

}  // namespace fenestra
