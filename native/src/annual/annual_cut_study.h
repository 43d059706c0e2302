#pragma once
// The annual study of openings from paths traced with the openings really cut (cutters and
// reveals through thick walls), independent of the contribution records: the ground truth an
// annual study from the records answers to, and a study of openings the records cannot give
// (edges off the element grid in a thick wall). See docs/annual.md.
#include <vector>

#include "annual/annual_illuminance.h"
#include "annual/annual_study.h"
#include "scene/scene.h"
#include "trace/evaluate.h"
#include "trace/sensor_range.h"
#include "util/progress.h"

namespace fenestra {

// Per-task coefficient rows held at once (sensors are traced in batches within it; a batch holds
// at least one sensor's). The cost model counts them (study/cost_model.cpp).
inline constexpr size_t kAnnualCutBatchBytes = size_t(64) << 20;

// The same AnnualStudy as annual_study(): per sensor and source the unit daylight coefficients of
// the light that reflected at least once for suns, traced under the unit sources (sky patches and
// sun clusters) with the openings cut, and per sun hour the sun straight to the sensor at its exact
// position through the openings' holes. The occupied hours' mean carries the standard error of the
// paths' spread. Paths per sensor: `paths_per_sensor`, or the scene's render.paths_per_sensor when
// 0. The same numbers for a seed whatever the thread count.
// Throws std::invalid_argument when the scene's sky is not "climate" or an opening is off its panel
// (naming it), Cancelled when `progress` is cancelled.
AnnualStudy annual_study_with_cutters(const Scene& scene, const std::vector<OpeningInput>& openings,
                                      Progress* progress = nullptr, int paths_per_sensor = 0);

// Its parts for the sensors of `range` (a shard of a study on a cluster; rows from range.begin):
// the coefficients and the occupied hours' mean, the same per sensor as the whole study's.
struct AnnualCutCoefficients {
  AnnualCoefficients coefficients;
  SensorValues occupied_mean;  // lux
  int paths_per_sensor = 0;
  std::shared_ptr<const AnnualRecords> annual;  // the sources and hours they are of (null: the scene's)
};
AnnualCutCoefficients annual_cut_coefficients(const Scene& scene, const std::vector<OpeningInput>& openings,
                                              Progress* progress, int paths_per_sensor, SensorRange range);

// The study of the coefficients of all the scene's sensors (stacked in order from ranges).
AnnualStudy annual_cut_study_of(const Scene& scene, AnnualCutCoefficients whole);

}  // namespace fenestra
