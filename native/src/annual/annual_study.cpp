#include "annual/annual_study.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/npz_writer.h"
#include "io/output_pair.h"
#include "scene/scene.h"
#include "trace/contributions_origin.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using json = nlohmann::json;

std::vector<double> to_vector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

// Row-major floats of a column-major matrix (sensors x hours: one row per sensor in the file).
std::vector<float> row_major(const Eigen::MatrixXf& m) {
  std::vector<float> out(static_cast<size_t>(m.size()));
  Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(out.data(), m.rows(), m.cols()) = m;
  return out;
}

// JSON has no infinity: an unbounded band edge is null.
json finite_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

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

json annual_space_json(const AnnualMetrics& m) {
  json udi = json::array();
  for (const UdiBand& b : m.udi)
    udi.push_back({{"name", b.name}, {"lower_lux", finite_or_null(b.lower_lux)}, {"upper_lux", finite_or_null(b.upper_lux)},
                   {"space_fraction", b.space_fraction}, {"sensor_fraction", to_vector(b.sensor_fraction)}});
  json sda_levels = json::array();
  for (const PassLevel& p : m.sda_levels) sda_levels.push_back({{"level", p.level}, {"passed", p.passed}});
  json en = {{"openings", m.en17037.openings == DaylightOpenings::Horizontal ? "horizontal" : "vertical_or_inclined"},
             {"daylight_hours", m.en17037.daylight_hours},
             {"daylight_hours_basis", m.en17037.daylight_hours_basis},
             {"level_reached", m.en17037.level_reached},
             {"levels", json::array()}};
  for (const En17037LevelResult& l : m.en17037.levels)
    en["levels"].push_back({{"name", l.level.name}, {"target_lux", l.level.target_lux},
                            {"minimum_target_lux", l.level.minimum_target_lux},
                            {"target_hours_fraction", finite_or_null(l.target_hours_fraction)},
                            {"minimum_hours_fraction", finite_or_null(l.minimum_hours_fraction)},
                            {"target_met", l.target_met}, {"minimum_met", l.minimum_met}, {"met", l.met}});
  return {{"mean_illuminance_lux", m.space_mean_illuminance_lux},
          {"daylight_autonomy", m.space_daylight_autonomy},
          {"continuous_daylight_autonomy", m.space_continuous_daylight_autonomy},
          {"spatial_daylight_autonomy", m.spatial_daylight_autonomy},
          {"sda_levels", sda_levels},
          {"annual_sunlight_exposure", m.annual_sunlight_exposure},
          {"ase_passes", m.ase_passes},
          {"udi", udi},
          {"en17037", en}};
}

json annual_json(const AnnualStudy& s) {
  const AnnualMetrics& m = s.metrics;
  const AnnualRecords& a = *s.annual;
  const ClimateSettings& cs = a.climate->settings;
  std::vector<int> ase_hours(m.ase_sensor_hours.data(), m.ase_sensor_hours.data() + m.ase_sensor_hours.size());
  json per_sensor = {{"mean_illuminance_lux", to_vector(m.mean_illuminance_lux)},
                     {"mean_illuminance_stderr_lux", to_vector(s.occupied_mean.standard_error)},
                     {"daylight_autonomy", to_vector(m.daylight_autonomy)},
                     {"continuous_daylight_autonomy", to_vector(m.continuous_daylight_autonomy)},
                     {"ase_hours", ase_hours}};
  // With the openings cut, the occupied hours' mean is the year's own: there are no records.
  if (!s.cutters) per_sensor["mean_illuminance_from_records_lux"] = to_vector(s.occupied_mean.value);
  return {
      {"format", "fenestra-annual"},
      {"version", 1},
      {"scene", a.scene_source},
      {"units", "illuminance in lux; fractions of occupied hours or of the sensors (equal areas)"},
      {"weather", cs.weather_path},
      {"climate", cs.describe()},
      {"sensors", m.sensors},
      {"hours", m.hours},
      {"occupied_hours", m.occupied_hours},
      {"occupied", {{"start_hour", s.settings.occupied_start_hour}, {"end_hour", s.settings.occupied_end_hour},
                    {"clock", "local standard time"}}},
      {"settings", s.settings.describe()},
      {"space", annual_space_json(m)},
      {"per_sensor", per_sensor},
      {"sources",
       {{"sky_patches", a.sources.patch_count - 1},
        {"sky_subdivision", a.climate->sky->patches.subdivision()},
        {"sun_clusters", a.sources.suns.size()},
        {"sun_cluster_subdivision", a.sources.suns.subdivision},
        {"sun_cluster_max_error_deg", a.sources.suns.max_error_deg},
        {"sun_cluster_mean_error_deg", a.sources.suns.mean_error_deg}}},
      {"paths", s.cutters ? "traced with the openings cut" : "contribution records"},
      {"paths_per_sensor", s.paths_per_sensor},
      {"seconds", s.seconds},
      {"warnings", s.warnings},
  };
}

std::pair<std::string, std::string> write_annual(const Scene& scene, const AnnualStudy& s, const std::string& out) {
  const auto [npz_path, json_path] = npz_json_pair(out);
  check_output_paths({npz_path, json_path}, scene.input_files);
  const size_t sensors = static_cast<size_t>(s.illuminance.total.rows()), hours = s.hours.size();
  NpzWriter npz;
  npz.add("illuminance", row_major(s.illuminance.total), {sensors, hours});
  npz.add("direct_sun", row_major(s.illuminance.direct), {sensors, hours});
  std::vector<int32_t> month, day, occupied;
  std::vector<double> clock;
  for (size_t h = 0; h < hours; ++h) {
    month.push_back(s.hours[h].month), day.push_back(s.hours[h].day), clock.push_back(s.hours[h].clock_hour);
    occupied.push_back(s.occupied[h]);
  }
  npz.add("hour_month", month, {hours});
  npz.add("hour_day", day, {hours});
  npz.add("hour_clock", clock, {hours});
  npz.add("occupied", occupied, {hours});
  npz.add("mean_illuminance", to_vector(s.metrics.mean_illuminance_lux), {sensors});
  npz.add("daylight_autonomy", to_vector(s.metrics.daylight_autonomy), {sensors});
  npz.add("continuous_daylight_autonomy", to_vector(s.metrics.continuous_daylight_autonomy), {sensors});
  std::vector<int32_t> ase(s.metrics.ase_sensor_hours.data(), s.metrics.ase_sensor_hours.data() + sensors);
  npz.add("ase_hours", ase, {sensors});
  const json summary = annual_json(s);
  write_files_atomically(
      {{npz_path, [&](std::ostream& o) { npz.write(o); }},
       {json_path, [&](std::ostream& o) { o << summary.dump(2, ' ', false, json::error_handler_t::replace) << "\n"; }}},
      scene.input_files);
  return {npz_path, json_path};
}

}  // namespace fenestra
