#include "annual/annual_records.h"

#include <stdexcept>
#include <string>

#include "annual/annual_study.h"  // annual_metric_settings
#include "scene/environment_map.h"
#include "scene/scene.h"
#include "trace/parallel.h"
#include "trace/path_tracer.h"

namespace fenestra {
namespace {

bool occupied(const HourStamp& hour, const ClimateSettings& settings) {
  return hour.clock_hour >= settings.occupied_start_hour && hour.clock_hour < settings.occupied_end_hour;
}

}  // namespace

size_t AnnualRecords::memory_bytes() const {
  size_t bytes = sizeof(float) * day_sky.size() + sizeof(double) * (design_strength.size() + unit_scale.size());
  for (const SensorRecord& r : direct) bytes += r.memory_bytes();
  for (const std::vector<float>& f : direct_factor) bytes += sizeof(float) * f.capacity();
  return bytes;
}

Scene annual_tracing_scene(const Scene& scene, const AnnualSources& sources) {
  Scene traced = scene;
  traced.sky = std::make_shared<UniformSky>(Rgb::Ones());
  std::vector<SunLight> suns;
  suns.reserve(sources.suns.size());  // exactly the clusters (the cost model counts them: traced_scene)
  for (size_t c = 0; c < sources.suns.size(); ++c) {
    SunLight sun;
    sun.direction = sources.suns.direction[c];
    sun.normal_illuminance = Rgb::Constant(static_cast<float>(sources.suns.energy_lux_h[c]));
    suns.push_back(sun);
  }
  traced.suns = SunLights(std::move(suns));
  return traced;
}

std::shared_ptr<AnnualRecords> prepare_annual(const Scene& scene) {
  if (!scene.climate || !scene.climate->sky) throw std::invalid_argument("the scene has no climate sky");
  auto annual = std::make_shared<AnnualRecords>();
  annual->climate = scene.climate;
  annual->scene_source = scene.source;
  annual->metric_settings = annual_metric_settings(scene);
  const SkyMatrix& sky = *scene.climate->sky;
  const ClimateSettings& settings = scene.climate->settings;
  AnnualSources& sources = annual->sources;
  sources.patch_count = sky.patches.count();
  sources.suns = cluster_suns(sky);
  if (sources.count() > AnnualSources::kMaxSources)
    throw std::invalid_argument("sky.patches: " + std::to_string(sources.count()) + " sources (patches and sun positions), at most " +
                                std::to_string(AnnualSources::kMaxSources));

  const size_t hours = sky.hours.size();
  size_t occupied_hours = 0;
  annual->design_strength.assign(sources.count(), 0.0);
  annual->unit_scale.assign(sources.count(), 1.0);
  for (size_t h = 0; h < hours; ++h) {
    const bool sunny = sky.sun_normal_illuminance[h] > 0.0f && sources.suns.cluster_of_hour[h] >= 0;
    if (sunny || sky.radiance.col(h).maxCoeff() > 0.0f) annual->day_hours.push_back(static_cast<int>(h));
    if (sunny) annual->sun_hours.push_back(static_cast<int>(h));
    if (!occupied(sky.hours[h], settings)) continue;
    ++occupied_hours;
    for (int p = 0; p < sources.patch_count; ++p) annual->design_strength[p] += sky.radiance(p, h);
    if (sunny) annual->design_strength[sources.sun_source(sources.suns.cluster_of_hour[h])] += sky.sun_normal_illuminance[h];
  }
  if (occupied_hours == 0)
    throw std::invalid_argument("sky.occupied: no hour of the weather file falls in the occupied period " +
                                std::to_string(settings.occupied_start_hour) + "-" +
                                std::to_string(settings.occupied_end_hour) + " h");
  for (double& s : annual->design_strength) s /= static_cast<double>(occupied_hours);
  for (size_t c = 0; c < sources.suns.size(); ++c)
    annual->unit_scale[sources.sun_source(static_cast<int>(c))] = 1.0 / sources.suns.energy_lux_h[c];

  annual->day_sky.resize(sources.patch_count, annual->day_hours.size());
  for (size_t j = 0; j < annual->day_hours.size(); ++j) annual->day_sky.col(j) = sky.radiance.col(annual->day_hours[j]);
  return annual;
}

void convert_to_design_values(const AnnualRecords& annual, SensorRecord* record) {
  record->event_coefficients.resize(record->events.size());
  for (size_t e = 0; e < record->events.size(); ++e) {
    const int source = record->event_sources[e] & ~AnnualSources::kDirect;
    PathEvent& event = record->events[e];
    const double coefficient = event.value() * annual.unit_scale[source];
    record->event_coefficients[e] = static_cast<float>(coefficient);
    const float design = static_cast<float>(coefficient * annual.design_strength[source]);
    event.set_value(design, event_dither(design, e));
  }
}

void record_direct_sun(const Scene& scene, const PathTracer& tracer, AnnualRecords* annual, int threads,
                       SensorRange sensors) {
  const SkyMatrix& sky = *annual->climate->sky;
  sensors = sensors.within(scene.sensors.size());
  annual->direct.assign(sensors.size(), SensorRecord());
  annual->direct_factor.assign(sensors.size(), std::vector<float>(annual->sun_hours.size(), 0.0f));
  parallel_tasks(sensors.size(), threads, nullptr, [&](size_t local) {
    const size_t i = sensors.begin + local;
    SensorRecord& r = annual->direct[local];
    std::vector<float>& factor = annual->direct_factor[local];
    std::vector<MetElement> crossed;
    for (size_t j = 0; j < annual->sun_hours.size(); ++j) {
      const PathTracer::DirectSun sun = tracer.direct_sun(i, sky.sun_direction[annual->sun_hours[j]]);
      if (sun.visible) {
        crossed.clear();
        for (const PathTracer::Crossing& c : sun.crossed)
          crossed.push_back({c.element, CellPoint::of(scene.domain.elements()[c.element], c.point)});
        r.add_light(1.0f, crossed.data(), crossed.size(), nullptr, 0);
        factor[j] = sun.cosine * sun.attenuation;
      }
      r.end_path();
    }
  });
}

}  // namespace fenestra
