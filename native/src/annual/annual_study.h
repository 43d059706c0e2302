#pragma once
// An annual study of one set of openings: every sensor's hourly illuminance over the weather
// file's year, its direct-sun part, and the climate-based metrics (daylight/annual_metrics.h),
// from a climate scene's contributions. See docs/annual.md.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "annual/annual_illuminance.h"
#include "daylight/annual_metrics.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"
#include "trace/open_region.h"

namespace fenestra {

struct AnnualStudy {
  AnnualIlluminance illuminance;  // sensors x hours, lux
  std::vector<HourStamp> hours;
  std::vector<char> occupied;     // per hour
  // The mean illuminance of the occupied hours per sensor straight from the records (the scene's
  // design values), with its Monte Carlo standard error (lux).
  SensorValues occupied_mean;
  AnnualMetricSettings settings;
  AnnualMetrics metrics;
  double seconds = 0.0;  // coefficients, product and metrics
  // What it was computed from: the sources and the sky, the paths per sensor, and whether the
  // paths were traced with the openings really cut (annual_study_with_cutters) or are the records'.
  std::shared_ptr<const AnnualRecords> annual;
  int paths_per_sensor = 0;
  bool cutters = false;
  std::vector<std::string> warnings;  // the setup checks' (study/setup_checks.h), set by the front end
  // From the records (not `cutters`): what the tracer dropped while recording them (record_sink.h).
  DropCounts dropped;
};

// The metric settings of a climate scene: the standards' defaults, its occupied hours.
AnnualMetricSettings annual_metric_settings(const Scene& scene);

// Throws std::invalid_argument when the contributions were not computed for a climate sky (or,
// with a scene, for another scene).
AnnualStudy annual_study(const Scene& scene, const Contributions& c, const OpenRegion& region,
                         const Progress* progress = nullptr);
AnnualStudy annual_study(const Contributions& c, const std::vector<uint8_t>& open, const Progress* progress = nullptr);

// What annual_study(scene, c, region) is made of, per sensor of `c` (a shard's sensors when its
// records are a shard's): the region's daylight coefficients and the occupied hours' mean (lux).
struct AnnualRegionParts {
  AnnualCoefficients coefficients;
  SensorValues occupied_mean;
};
AnnualRegionParts annual_region_parts(const Contributions& c, const OpenRegion& region,
                                      const Progress* progress = nullptr);

// The metrics of some of the study's sensors (a room's, by their indices in the study), as the
// study's own are computed over all of them. std::invalid_argument for an index out of range or
// no sensor.
AnnualMetrics annual_metrics_of(const AnnualStudy& study, const std::vector<int>& sensors);

// The study of given daylight coefficients: the hourly illuminance, the occupied hours and the
// metrics; `mean` is the occupied hours' mean per sensor with its standard error (lux).
AnnualStudy annual_study_of(const AnnualCoefficients& coefficients, std::shared_ptr<const AnnualRecords> annual,
                            const SensorValues& mean);

// The openings as a region of the contributions' domain: each on its panel, on elements, and in a
// thick wall on the grid's lines (throws std::invalid_argument naming the opening).
OpenRegion region_of_openings(const Scene& scene, const std::vector<OpeningInput>& openings);

}  // namespace fenestra
