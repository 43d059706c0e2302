#include "solve/record_queries.h"

#include "annual/annual_contributions.h"
#include "annual/annual_cut_study.h"
#include "scene/scene.h"
#include "solve/region_search.h"
#include "trace/evaluate.h"
#include "trace/flip_effects.h"

namespace fenestra {

LocalRecordQueries::LocalRecordQueries(const Scene& scene, const Contributions& c, const OpeningDomain& domain,
                                       Progress* progress, SensorRange sensors)
    : scene_(scene), c_(c), domain_(domain), progress_(progress), sensors_(sensors), exact_(c, progress) {}

namespace {

// Refined records with the scene and contributions they read (held first, so they outlive the
// queries that refer to them).
struct RefinedStudy {
  Scene scene;
  Contributions contributions;
};

class OwningRecordQueries : private RefinedStudy, public LocalRecordQueries {
 public:
  OwningRecordQueries(RefinedStudy study, Progress* progress, SensorRange sensors)
      : RefinedStudy(std::move(study)),
        LocalRecordQueries(RefinedStudy::scene, RefinedStudy::contributions, RefinedStudy::scene.domain, progress,
                           sensors) {}
};

}  // namespace

std::unique_ptr<RecordQueries> LocalRecordQueries::refined(const std::vector<RefinedRegion>& regions) {
  RefinedStudy study{scene_, Contributions()};
  study.scene.render.paths_per_sensor = c_.paths_per_sensor;  // as many as these records
  study.scene.domain = scene_.domain.refined(regions);
  study.contributions = compute_contributions(study.scene, progress_, false, sensors_);
  return std::make_unique<OwningRecordQueries>(std::move(study), progress_, sensors_);
}

SensorValues LocalRecordQueries::evaluate(const std::vector<PanelRectangle>& region) {
  return c_.evaluate(OpenRegion(domain_, region), progress_);
}

Eigen::MatrixXd LocalRecordQueries::flip_effects(const std::vector<uint8_t>& about) {
  return fenestra::flip_effects(c_, about, progress_);
}

std::unique_ptr<RegionQueries> LocalRecordQueries::region_search(const std::vector<PanelRectangle>& start) {
  return std::make_unique<RegionSearch>(c_, domain_, start, progress_);
}

SensorValues LocalRecordQueries::cut(const std::vector<OpeningInput>& openings, int paths) {
  return evaluate_openings(scene_, openings, progress_, paths);
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
  return fenestra::annual_study(scene_, c_, OpenRegion(domain_, region), progress_);
}

AnnualStudy LocalRecordQueries::annual_cut(const std::vector<OpeningInput>& openings, int paths) {
  return annual_study_with_cutters(scene_, openings, progress_, paths);
}

}  // namespace fenestra
