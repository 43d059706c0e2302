#pragma once
// What an annual pass keeps beside the contribution records to give every sensor's illuminance
// for every hour of the year, for any set of open elements: the sources the records' events name,
// and the sun seen straight from each sensor at each sunny hour. See docs/annual.md.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "daylight/annual_metrics.h"
#include "daylight/annual_sources.h"
#include "daylight/sky_matrix.h"
#include "trace/path_record.h"
#include "trace/sensor_range.h"

namespace fenestra {

class PathTracer;
struct Scene;

struct AnnualRecords {
  std::shared_ptr<const Climate> climate;
  std::string scene_source;           // for messages and outputs
  AnnualMetricSettings metric_settings;  // the standards' defaults, the climate's occupied hours
  AnnualSources sources;
  // Per source, its mean strength over the occupied hours: cd/m^2 for a patch, lux of normal
  // illuminance for a sun cluster. The records' values are their coefficients times this: the
  // mean illuminance of the occupied hours, the scene's design quantity.
  std::vector<double> design_strength;
  // Per source, what turns a recorded value at the tracing strength into a unit coefficient.
  std::vector<double> unit_scale;
  // Columns of the sky matrix with any light (day), and, of those, the hours with sun.
  std::vector<int> day_hours, sun_hours;
  Eigen::MatrixXf day_sky;  // sky-patch rows x day_hours: the sky matrix's day columns, cd/m^2
  // Per sensor, one "path" per sun hour (sun_hours[j]): a light event worth 1, with the elements
  // the sun's ray crosses as conditions (all must be open); direct_factor[sensor][j], cos x
  // attenuation, is its value (kept at full precision: it is exact, not a Monte Carlo sample).
  std::vector<SensorRecord> direct;
  std::vector<std::vector<float>> direct_factor;
  size_t memory_bytes() const;
};

// The scene an annual pass traces: the scene with a unit sky and the sun clusters, each at the
// normal illuminance of its hours summed (so sampling favours the clusters that matter).
Scene annual_tracing_scene(const Scene& scene, const AnnualSources& sources);

// Sources, strengths and the sky's day columns of a climate scene (no tracing).
std::shared_ptr<AnnualRecords> prepare_annual(const Scene& scene);

// After tracing: the events' coefficients from their recorded values, and their values under the
// design sky (record.sourced must be set and event_sources filled).
void convert_to_design_values(const AnnualRecords& annual, SensorRecord* record);

// The direct-sun records of the sensors in `sensors` (parallel over sensors), indexed from its
// first.
void record_direct_sun(const Scene& scene, const PathTracer& tracer, AnnualRecords* annual, int threads,
                       SensorRange sensors);

}  // namespace fenestra
