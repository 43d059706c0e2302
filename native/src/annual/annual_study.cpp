#include "annual/annual_study.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "scene/scene.h"
#include "trace/contributions_origin.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

void check_annual(const Contributions& c) {
  if (!c.annual)
    throw std::invalid_argument("an annual study needs the contributions of a scene whose sky is \"climate\" (a "
                                "weather file); these were computed for " +
                                (c.origin.source.empty() ? std::string("another sky") : "scene '" + c.origin.source + "' without one"));
}

template <typename Open>
AnnualStudy study(const Contributions& c, Open is_open, const SensorValues& mean, const Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  AnnualStudy s = annual_study_of(annual_coefficients(c.records, *c.annual, is_open, progress), c.annual, mean);
  s.paths_per_sensor = c.paths_per_sensor;
  s.dropped = c.dropped;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace

AnnualMetricSettings annual_metric_settings(const Scene& scene) {
  AnnualMetricSettings s;
  if (scene.climate) {
    s.occupied_start_hour = scene.climate->settings.occupied_start_hour;
    s.occupied_end_hour = scene.climate->settings.occupied_end_hour;
  }
  // EN 17037: rooflights alone are judged by the criterion for horizontal openings.
  bool any_vertical = false;
  for (const Panel& p : scene.domain.panels()) any_vertical = any_vertical || std::abs(p.normal.z()) < 0.7f;
  if (!scene.domain.panels().empty() && !any_vertical) s.en17037_openings = DaylightOpenings::Horizontal;
  return s;
}

AnnualStudy annual_study_of(const AnnualCoefficients& coefficients, std::shared_ptr<const AnnualRecords> annual,
                            const SensorValues& mean) {
  AnnualStudy s;
  s.illuminance = annual_illuminance(coefficients, *annual);
  const SkyMatrix& sky = *annual->climate->sky;
  s.hours = sky.hours;
  s.settings = annual->metric_settings;
  for (const HourStamp& h : s.hours)
    s.occupied.push_back(h.clock_hour >= s.settings.occupied_start_hour && h.clock_hour < s.settings.occupied_end_hour);
  s.occupied_mean = mean;
  AnnualMetricInputs inputs;
  inputs.hours = s.hours;
  inputs.external_horizontal_illuminance = sky.diffuse_horizontal_lux;  // EN 17037's daylight hours
  s.metrics = annual_metrics(s.illuminance.total, inputs, s.settings, &s.illuminance.direct);
  s.annual = std::move(annual);
  return s;
}

AnnualMetrics annual_metrics_of(const AnnualStudy& study, const std::vector<int>& sensors) {
  const Eigen::Index n = study.illuminance.total.rows();
  if (sensors.empty()) throw std::invalid_argument("annual metrics of no sensor");
  Eigen::MatrixXf total(static_cast<Eigen::Index>(sensors.size()), study.illuminance.total.cols());
  Eigen::MatrixXf direct(total.rows(), study.illuminance.direct.cols());  // sensors x hours, as total
  for (size_t i = 0; i < sensors.size(); ++i) {
    if (sensors[i] < 0 || sensors[i] >= n)
      throw std::invalid_argument("annual metrics: sensor " + std::to_string(sensors[i]) + " is not one of the study's " +
                                  std::to_string(n));
    total.row(static_cast<Eigen::Index>(i)) = study.illuminance.total.row(sensors[i]);
    direct.row(static_cast<Eigen::Index>(i)) = study.illuminance.direct.row(sensors[i]);
  }
  AnnualMetricInputs inputs;
  inputs.hours = study.hours;
  inputs.external_horizontal_illuminance = study.annual->climate->sky->diffuse_horizontal_lux;  // as the study's
  return annual_metrics(total, inputs, study.settings, &direct);
}

AnnualStudy annual_study(const Scene& scene, const Contributions& c, const OpenRegion& region,
                         const Progress* progress) {
  check_contributions_match(scene, c, "an annual study");
  check_annual(c);
  return study(c, [&](int32_t k, const CellPoint& p) { return region.is_open(k, p); },
               c.evaluate(region, progress), progress);
}

AnnualRegionParts annual_region_parts(const Contributions& c, const OpenRegion& region, const Progress* progress) {
  check_annual(c);
  AnnualRegionParts parts;
  parts.occupied_mean = c.evaluate(region, progress);
  parts.coefficients = annual_coefficients(
      c.records, *c.annual, [&](int32_t k, const CellPoint& p) { return region.is_open(k, p); }, progress);
  return parts;
}

AnnualStudy annual_study(const Contributions& c, const std::vector<uint8_t>& open, const Progress* progress) {
  check_annual(c);
  const SensorValues mean = c.evaluate(open, progress);  // checks the mask's size
  return study(c, [&](int32_t k, const CellPoint&) { return open[k] != 0; }, mean, progress);
}

OpenRegion region_of_openings(const Scene& scene, const std::vector<OpeningInput>& openings) {
  std::vector<PanelRectangle> rects;
  for (size_t i = 0; i < openings.size(); ++i) {
    try {
      rects.push_back(to_panel_rectangle(scene.domain, openings[i]));
      check_on_elements(scene.domain, rects.back());
      check_on_grid_lines_in_thick_walls(scene.domain, rects.back());
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("opening " + std::to_string(i) + " " + e.what());
    }
  }
  return OpenRegion(scene.domain, rects);
}

}  // namespace fenestra
