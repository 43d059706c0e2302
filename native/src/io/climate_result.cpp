#include "io/climate_result.h"

#include <algorithm>

#include "daylight/sky_matrix.h"
#include "io/annual_result.h"

namespace fenestra {
namespace {

using nlohmann::json;

const char* sense_name(GoalSense s) {
  switch (s) {
    case GoalSense::AtLeast: return "at_least";
    case GoalSense::AtMost: return "at_most";
    case GoalSense::Target: return "target";
  }
  return "?";
}

json figure_or_null(const std::vector<ClimateFigure>& figures, size_t g) {
  return g < figures.size() ? json(figures[g].achieved) : json(nullptr);
}

json met_or_null(const ClimateGoal& goal, const std::vector<ClimateFigure>& figures, size_t g) {
  return g < figures.size() ? json(figure_meets(goal, figures[g].achieved)) : json(nullptr);
}

bool all_met(const ClimateGoals& goals, const std::vector<ClimateFigure>& figures) {
  for (size_t g = 0; g < goals.goals.size(); ++g)
    if (g >= figures.size() || !figure_meets(goals.goals[g], figures[g].achieved)) return false;
  return true;
}

std::vector<double> values(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

}  // namespace

json climate_result_json(const Scene& scene, const ClimateOutcome& c) {
  const ClimateGoals& goals = scene.sensors.climate_goals;
  json list = json::array();
  for (size_t g = 0; g < goals.goals.size(); ++g) {
    const ClimateGoal& goal = goals.goals[g];
    list.push_back({{"metric", goal.metric_name()},
                    {"description", goal.describe()},
                    {"sensors", goal.sensors},
                    {"sense", sense_name(goal.sense())},
                    {"required", goal.required()},
                    {"unit", goal.unit()},
                    {"weight", goal.weight},
                    {"achieved", figure_or_null(c.headline(), g)},
                    {"met", met_or_null(goal, c.headline(), g)},
                    {"records", figure_or_null(c.achieved, g)},
                    {"records_met", met_or_null(goal, c.achieved, g)},
                    {"verified", figure_or_null(c.verified, g)},
                    {"verified_met", met_or_null(goal, c.verified, g)},
                    {"apart", g < c.apart.size() ? json(c.apart[g] != 0) : json(nullptr)},
                    {"elements", figure_or_null(c.element_figures, g)},
                    {"all_open", figure_or_null(c.all_open_figures, g)}});
  }
  json per_sensor = nullptr, space = nullptr, verified_space = nullptr, records_space = nullptr;
  const std::shared_ptr<const AnnualStudy>& shown = c.headline_study();
  if (shown) {
    const AnnualMetrics& m = shown->metrics;
    std::vector<int> ase(m.ase_sensor_hours.data(), m.ase_sensor_hours.data() + m.ase_sensor_hours.size());
    per_sensor = {{"daylight_autonomy", values(m.daylight_autonomy)},
                  {"continuous_daylight_autonomy", values(m.continuous_daylight_autonomy)},
                  {"mean_illuminance_lux", values(m.mean_illuminance_lux)},
                  {"ase_hours", ase}};
    space = annual_space_json(m);
  }
  // Each sensor group the goals name (a room, as the add-on makes one per room): its figures of the
  // shown year. `space` is the whole floor's, all sensors with equal areas, as LEED counts sDA and ASE.
  json rooms = json::array();
  std::vector<std::string> named;
  for (const ClimateGoal& goal : goals.goals) {
    if (!shown || goal.sensors_given == "all" || goal.sensors_given == "list") continue;
    if (std::find(named.begin(), named.end(), goal.sensors_given) != named.end()) continue;
    named.push_back(goal.sensors_given);
    rooms.push_back({{"name", goal.sensors_given},
                     {"sensors", goal.sensors},
                     {"space", annual_space_json(annual_metrics_of(*shown, goal.sensors))}});
  }
  if (c.verified_study) verified_space = annual_space_json(c.verified_study->metrics);
  if (c.study) records_space = annual_space_json(c.study->metrics);
  json year = nullptr;  // what the year is, as `fenestra annual` names it
  if (shown && scene.climate) {
    const AnnualStudy& st = *shown;
    year = {{"weather", scene.climate->settings.weather_path},
            {"hours", st.metrics.hours},
            {"occupied_hours", st.metrics.occupied_hours},
            {"occupied", {{"start_hour", st.settings.occupied_start_hour}, {"end_hour", st.settings.occupied_end_hour},
                          {"clock", "local standard time"}}},
            {"paths_per_sensor", st.paths_per_sensor}};
  }
  return {{"goals", list},
          {"all_met", c.headline().empty() ? json(nullptr) : json(all_met(goals, c.headline()))},
          {"records_all_met", c.achieved.empty() ? json(nullptr) : json(all_met(goals, c.achieved))},
          {"headline", c.headline_is_cut() ? "real cutters" : "path records"},
          {"answer_from_tradeoffs", c.answer_from_tradeoffs},
          {"verified_all_met", c.verified.empty() ? json(nullptr) : json(all_met(goals, c.verified))},
          {"unmet", c.unmet},
          {"least_glazing", goals.least_glazing},
          {"glazing_area_m2", c.glazing_area_m2},
          {"domain_area_m2", c.domain_area_m2},
          {"per_sensor", per_sensor},
          {"space", space},
          {"rooms", rooms},
          {"verified_space", verified_space},
          {"records_space", records_space},
          {"year", year},
          {"linearisations", c.linearisations},
          {"model_bytes", c.model_bytes},
          {"units", "fractions in [0, 1] (of the sensors, or of EN 17037's daylight hours), illuminance in lux, "
                    "areas in m^2, hours of the occupied period"}};
}

}  // namespace fenestra
