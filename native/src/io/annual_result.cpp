#include "io/annual_result.h"

#include <cmath>

#include "annual/annual_records.h"
#include "format/atomic_file.h"
#include "format/npz_writer.h"
#include "format/output_pair.h"
#include "io/results.h"

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

}  // namespace

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
  json j = {
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
  if (!s.cutters) j["dropped"] = dropped_json(s.dropped);  // the records' (cut paths record nothing)
  return j;
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
