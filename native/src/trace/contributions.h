#pragma once
// The opening contribution matrix and everything kept with it, from one set of paths per sensor.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "trace/contributions_origin.h"
#include "trace/open_region.h"
#include "trace/path_record.h"
#include "trace/record_sink.h"
#include "trace/sensor_range.h"
#include "util/progress.h"

namespace fenestra {

struct AnnualRecords;  // annual/annual_records.h

struct SensorValues {
  Eigen::VectorXd value;   // luminance-weighted irradiance per sensor (lux for a sky in cd/m^2)
  Eigen::VectorXd standard_error;  // standard error of each value (same units)
};

struct Contributions {
  int paths_per_sensor = 0;
  // E(i, k): what element k, alone open, adds to sensor i (value with {k} open minus all closed).
  Eigen::MatrixXd E, E_stderr;
  // A(i, k): light reaching sensor i on paths after they reflected off element k while it was closed.
  Eigen::MatrixXd A;
  // T(m, n): symmetric transport between elements m and n: light leaving through n on paths that
  // reflected off m before (and vice versa), averaged over all paths of all sensors.
  Eigen::MatrixXd T;
  SensorValues closed;    // every element closed
  SensorValues all_open;  // every element open
  std::vector<SensorRecord> records;  // per sensor, per path: events for exact evaluation
  double seconds = 0.0;
  uint64_t events = 0;
  // What the tracer dropped while recording (record_sink.h): non-finite light, and light or
  // sub-paths beyond the limit of conditions. Both 0 in a sound scene; written to the summary's "dropped".
  DropCounts dropped;
  // The scene it was computed for (set by the callers that hand it on: Python, solve_openings).
  ContributionsOrigin origin;
  // A climate scene's annual pass: the records' events name their sources (sky patches, sun
  // clusters) and carry their coefficients; values are the mean of the occupied hours.
  std::shared_ptr<const AnnualRecords> annual;
  size_t annual_bytes = 0;  // what `annual` holds (set with it: the records are complete by then)
  // The setup checks' warnings (study/setup_checks.h), set by the front end that ran them; written
  // to the summary's "warnings".
  std::vector<std::string> warnings;

  size_t sensor_count() const { return records.size(); }
  size_t element_count() const { return static_cast<size_t>(E.cols()); }
  // Exact value of every sensor with the elements where open[k] != 0 open, from the same paths.
  // With `progress`, polls cancellation every few thousand paths (throws Cancelled).
  SensorValues evaluate(const std::vector<uint8_t>& open, const Progress* progress = nullptr) const;
  // The same for any open region: rectangles whose edges need not lie on the element grid (exact
  // on zero-thickness panels; in thick walls where the edges lie on the lines of the grid traced).
  SensorValues evaluate(const OpenRegion& region, const Progress* progress = nullptr) const;
  size_t memory_bytes() const;
};

class PathTracer;
class SkyPatches;

// A sky of many sources traced in one pass (a climate's sky patches and sun clusters): the scene
// the paths see, and what becomes of each chunk of records as it is traced and of the pass after.
// annual/annual_contributions.h fills it in; the tracer knows nothing of the year.
class SourcedPass {
 public:
  virtual ~SourcedPass() = default;
  // The scene traced in place of the study's (a unit sky, the sources as its suns), and its patches.
  virtual const Scene& traced_scene() const = 0;
  virtual const SkyPatches* patches() const = 0;
  // Each chunk of a sensor's paths once traced, on the worker that traced it.
  virtual void chunk_traced(SensorRecord* record) const = 0;
  // After the records are assembled: what the pass adds with the same tracer (annual, annual_bytes).
  virtual void tracing_done(const PathTracer& tracer, int threads, SensorRange sensors, Contributions* out) = 0;
};

// The contributions of a scene whose sky is one source, or with `pass` of many (a climate scene
// needs one: annual/annual_contributions.h's compute_contributions gives it).
// With `transport` false, T is left empty (a records-only pass: the edges of thick walls).
// `sensors`: only that block of the scene's sensors (a shard); the rows and records are theirs, in
// order, and equal those of the whole scene's pass bit for bit.
Contributions trace_contributions(const Scene& scene, Progress* progress, bool transport, SensorRange sensors,
                                  SourcedPass* pass);

}  // namespace fenestra
