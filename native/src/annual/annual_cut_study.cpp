#include "annual/annual_cut_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "annual/annual_records.h"
#include "trace/parallel.h"
#include "trace/path_tracer.h"
#include "trace/replicates.h"

namespace fenestra {
namespace {

// Stream salt: independent of the contribution pass and of evaluate_openings.
constexpr uint64_t kAnnualCutStream = 0x616e6e75616c6375ULL;

}  // namespace

AnnualStudy annual_study_with_cutters(const Scene& scene, const std::vector<OpeningInput>& openings, Progress* progress,
                                      int paths_per_sensor) {
  const auto start = std::chrono::steady_clock::now();
  AnnualStudy study = annual_cut_study_of(scene, annual_cut_coefficients(scene, openings, progress, paths_per_sensor, {}));
  study.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return study;
}

AnnualCutCoefficients annual_cut_coefficients(const Scene& scene, const std::vector<OpeningInput>& openings,
                                              Progress* progress, int paths_per_sensor, SensorRange range) {
  if (!scene.climate || !scene.climate->sky)
    throw std::invalid_argument("an annual study needs a scene whose sky is \"climate\" (a weather file); scene '" +
                                scene.source + "' has another sky");
  if (paths_per_sensor < 0)
    throw std::invalid_argument("paths per sensor must be at least 1 (0: the scene's), got " +
                                std::to_string(paths_per_sensor));
  range = range.within(scene.sensors.size());
  const std::shared_ptr<AnnualRecords> annual = prepare_annual(scene);
  OpeningsGeometry g = build_openings(scene, openings);  // names an opening off its panel
  const Scene traced = annual_tracing_scene(scene, annual->sources);
  const PathTracer tracer(traced, std::move(g.cutters), std::move(g.reveals), &scene.climate->sky->patches);
  tracer.check_sensors(range);

  const size_t sensors = range.size();
  const size_t sources = static_cast<size_t>(annual->sources.count());
  const int paths = paths_per_sensor > 0 ? paths_per_sensor : scene.render.paths_per_sensor;
  const size_t tasks_per_sensor = path_tasks_per_sensor(paths);
  const size_t batch = std::max<size_t>(1, kAnnualCutBatchBytes / (sizeof(double) * sources * tasks_per_sensor));
  AnnualCutCoefficients out;
  out.paths_per_sensor = paths;
  out.annual = annual;
  AnnualCoefficients& k = out.coefficients;
  k.sources.setZero(sensors, sources);
  k.direct.setZero(sensors, annual->sun_hours.size());
  // Per task, the sum and the sum of squares of its paths' values under the design sky (the
  // occupied hours' mean strengths) without the sun straight to the sensor, which is exact.
  // By replicate group: stratified paths are not independent, the groups are (replicates.h).
  std::vector<ReplicateSums> sum(sensors * tasks_per_sensor);
  if (progress) progress->start("tracing the year with the openings cut", sum.size() + sensors);
  for (size_t first = 0; first < sensors; first += batch) {
    const size_t count = std::min(batch, sensors - first);
    Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(sources),
                                                 static_cast<Eigen::Index>(count * tasks_per_sensor));
    const SensorRange batch_range{range.begin + first, range.begin + first + count};
    parallel_path_tasks(batch_range, paths, scene.render.threads, progress, [&](const PathTask& t) {
      const size_t task = first * tasks_per_sensor + t.index;
      auto row = rows.col(static_cast<Eigen::Index>(t.index));
      std::vector<PathTracer::SourceLight> lights;
      const uint64_t seed = scene.render.seed ^ kAnnualCutStream;
      t.for_each_path(scene.render, seed, [&](size_t p, Rng& rng, const PathSamples* samples) {
        lights.clear();
        tracer.sensor_sample_by_source(t.sensor, samples, rng, &lights);
        double design = 0.0;
        for (const PathTracer::SourceLight& l : lights) {
          // The sun a sensor's own sample finds straight away: the exact hourly sun counts it below.
          if (l.source & AnnualSources::kDirect) continue;
          const double unit = l.value * annual->unit_scale[l.source];
          row[l.source] += unit;
          design += unit * annual->design_strength[l.source];
        }
        sum[task].add(p, design);
      });
    });
    for (size_t i = 0; i < count; ++i)
      k.sources.row(static_cast<Eigen::Index>(first + i)) =
          rows.middleCols(static_cast<Eigen::Index>(i * tasks_per_sensor), static_cast<Eigen::Index>(tasks_per_sensor))
              .rowwise()
              .sum()
              .transpose() /
          static_cast<double>(paths);
  }

  // The sun straight to the sensor at each sun hour's exact position, through the holes alone.
  const SkyMatrix& sky = *scene.climate->sky;
  parallel_tasks(sensors, scene.render.threads, progress, [&](size_t i) {
    for (size_t j = 0; j < annual->sun_hours.size(); ++j) {
      const PathTracer::DirectSun sun =
          tracer.direct_sun_through_openings(range.begin + i, sky.sun_direction[annual->sun_hours[j]]);
      if (sun.visible) k.direct(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = sun.cosine * sun.attenuation;
    }
  });

  // The occupied hours' mean: the paths' mean under the design sky plus the exact direct sun's
  // mean, which has no spread.
  const AnnualMetricSettings& settings = annual->metric_settings;
  auto occupied = [&](int h) {
    return sky.hours[h].clock_hour >= settings.occupied_start_hour && sky.hours[h].clock_hour < settings.occupied_end_hour;
  };
  std::vector<double> occupied_sun;  // per sun hour: its normal illuminance when occupied
  size_t occupied_hours = 0;
  for (size_t h = 0; h < sky.hours.size(); ++h) occupied_hours += occupied(static_cast<int>(h));
  for (const int h : annual->sun_hours) occupied_sun.push_back(occupied(h) ? sky.sun_normal_illuminance[h] : 0.0);
  SensorValues& mean = out.occupied_mean;
  mean.value.resize(static_cast<Eigen::Index>(sensors));
  mean.standard_error.resize(static_cast<Eigen::Index>(sensors));
  for (size_t i = 0; i < sensors; ++i) {
    ReplicateSums total;
    for (size_t t = 0; t < tasks_per_sensor; ++t) total.merge(sum[i * tasks_per_sensor + t]);
    double m = 0.0, standard_error = 0.0;
    total.estimate(paths, &m, &standard_error);
    double direct = 0.0;
    for (size_t j = 0; j < occupied_sun.size(); ++j)
      direct += static_cast<double>(k.direct(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j))) * occupied_sun[j];
    mean.value[static_cast<Eigen::Index>(i)] = m + direct / static_cast<double>(occupied_hours);
    mean.standard_error[static_cast<Eigen::Index>(i)] = standard_error;
  }
  return out;
}

AnnualStudy annual_cut_study_of(const Scene& scene, AnnualCutCoefficients whole) {
  const Eigen::Index sensors = static_cast<Eigen::Index>(scene.sensors.size());
  if (whole.coefficients.sources.rows() != sensors || whole.occupied_mean.value.size() != sensors)
    throw std::invalid_argument("an annual study with cutters needs the coefficients of all " +
                                std::to_string(sensors) + " sensors of scene '" + scene.source + "'");
  AnnualStudy study = annual_study_of(whole.coefficients, whole.annual ? whole.annual : prepare_annual(scene),
                                      whole.occupied_mean);
  study.paths_per_sensor = whole.paths_per_sensor;
  study.cutters = true;
  return study;
}

}  // namespace fenestra
