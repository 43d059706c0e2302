#include "scene/climate_goals.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "format/json_keys.h"
#include "scene/input_limits.h"
#include "util/number_text.h"
#include "util/quoted_text.h"

namespace fenestra {
namespace {

using nlohmann::json;

constexpr double kHoursPerYear = 8784.0;  // a leap year's
constexpr double kMaxGoalLux = 200000.0;  // above full sunlight (about 130 000 lx)

std::string lux(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

class GoalReader {
 public:
  GoalReader(std::string source, const json& groups, size_t sensors)
      : source_(std::move(source)), groups_(groups), sensors_(sensors) {}

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    throw std::invalid_argument("scene '" + source_ + "': " + key + ": " + message);
  }

  void check_groups() const {
    if (groups_.is_null()) return;
    if (!groups_.is_object()) fail("sensors.groups", "expected an object of \"name\": [sensor indices]");
    for (const auto& [name, list] : groups_.items()) {
      if (name == "all") fail("sensors.groups.all", "\"all\" already means every sensor: choose another name");
      indices(list, "sensors.groups." + quoted_text(name));
    }
  }

  std::vector<int> indices(const json& list, const std::string& key) const {
    if (!list.is_array() || list.empty()) fail(key, "expected a non-empty list of sensor indices");
    std::vector<int> out;
    for (const json& i : list) {
      if (!i.is_number_integer() || i.get<long long>() < 0 || i.get<long long>() >= static_cast<long long>(sensors_))
        fail(key, "expected sensor indices 0.." + std::to_string(sensors_ - 1) + ", got " + quoted_json(i));
      out.push_back(i.get<int>());
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  void sensors_of(const json& goal, const std::string& key, ClimateGoal* g) const {
    const json which = goal.value("sensors", json("all"));
    if (which.is_string()) {
      const std::string name = which.get<std::string>();
      g->sensors_given = name;
      if (name == "all") {
        for (size_t i = 0; i < sensors_; ++i) g->sensors.push_back(static_cast<int>(i));
        return;
      }
      if (!groups_.is_object() || !groups_.contains(name))
        fail(key + ".sensors", "no sensor group named '" + quoted_text(name) + "'" + did_you_mean(name, group_list()) +
                                   " (sensors.groups" +
                                   (groups_.is_object() && !groups_.empty() ? " has " + group_names() : " is empty") + ")");
      g->sensors = indices(groups_.at(name), "sensors.groups." + quoted_text(name));
      return;
    }
    g->sensors_given = "list";
    g->sensors = indices(which, key + ".sensors");
  }

  double number(const json& goal, const std::string& name, const std::string& key, double fallback, double lo,
                double hi, bool lo_open, const std::string& unit) const {
    if (!goal.contains(name)) {
      if (std::isnan(fallback)) fail(key + "." + name, "missing (" + unit + ")");
      return fallback;
    }
    const json& j = goal.at(name);
    if (!j.is_number()) fail(key + "." + name, "expected a number (" + unit + "), got " + quoted_json(j));
    const double v = j.get<double>();
    if (!std::isfinite(v) || (lo_open ? !(v > lo) : !(v >= lo)) || !(v <= hi))
      fail(key + "." + name, std::string("must lie in ") + (lo_open ? "(" : "[") + lux(lo) + ", " + lux(hi) + "] " +
                                 unit + ", got " + quoted_json(j));
    return v;
  }

  ClimateGoal goal(const json& j, const std::string& key) const {
    if (!j.is_object()) fail(key, "expected an object with \"metric\"");
    if (!j.contains("metric"))
      for (const auto& item : j.items())  // a misspelt "metric" is named as such
        if (closest_word(item.key(), {"metric"}) == "metric")
          fail(key + "." + quoted_text(item.key()), "unknown key; did you mean `metric`?");
    if (!j.contains("metric") || !j.at("metric").is_string())
      fail(key + ".metric", "missing: give \"sda\", \"ase\", \"en17037\", \"udi\" or \"mean\"");
    const std::string metric = j.at("metric").get<std::string>();
    ClimateGoal g;
    std::vector<std::string> known = {"metric", "sensors", "weight"};
    const double max_lux = kMaxGoalLux;
    if (metric == "sda") {
      g.metric = ClimateMetric::SpatialDaylightAutonomy;
      g.illuminance_lux = number(j, "illuminance_lux", key, 300.0, 0.0, max_lux, true, "lux");
      g.time_fraction = number(j, "time_fraction", key, 0.5, 0.0, 1.0, true, "of the occupied hours");
      g.area_fraction = number(j, "min_area_fraction", key, 0.55, 0.0, 1.0, false, "of the sensors");
      known.insert(known.end(), {"illuminance_lux", "time_fraction", "min_area_fraction"});
    } else if (metric == "ase") {
      g.metric = ClimateMetric::SunlightExposure;
      g.illuminance_lux = number(j, "illuminance_lux", key, 1000.0, 0.0, max_lux, true, "lux");
      g.hours = number(j, "hours", key, 250.0, 0.0, kHoursPerYear, false, "hours");
      g.area_fraction = number(j, "max_area_fraction", key, 0.10, 0.0, 1.0, false, "of the sensors");
      known.insert(known.end(), {"illuminance_lux", "hours", "max_area_fraction"});
    } else if (metric == "en17037") {
      g.metric = ClimateMetric::En17037;
      if (j.contains("level")) {
        if (!j.at("level").is_string()) fail(key + ".level", "expected \"minimum\", \"medium\" or \"high\"");
        g.level = j.at("level").get<std::string>();
      }
      if (g.level != "minimum" && g.level != "medium" && g.level != "high")
        fail(key + ".level", "expected \"minimum\", \"medium\" or \"high\", got \"" + g.level + "\"");
      known.push_back("level");
    } else if (metric == "udi") {
      g.metric = ClimateMetric::UsefulDaylight;
      g.lower_lux = number(j, "lower_lux", key, 100.0, 0.0, max_lux, false, "lux");
      g.upper_lux = number(j, "upper_lux", key, 3000.0, 0.0, max_lux, true, "lux");
      if (!(g.lower_lux < g.upper_lux))
        fail(key, "needs lower_lux < upper_lux, got " + lux(g.lower_lux) + " and " + lux(g.upper_lux));
      g.area_fraction = number(j, "min_area_fraction", key, 0.5, 0.0, 1.0, false, "of the sensors");
      known.insert(known.end(), {"lower_lux", "upper_lux", "min_area_fraction"});
    } else if (metric == "mean") {
      g.metric = ClimateMetric::MeanIlluminance;
      g.illuminance_lux = number(j, "illuminance_lux", key, std::nan(""), 0.0, max_lux, true, "lux");
      known.push_back("illuminance_lux");
    } else {
      fail(key + ".metric", "unknown metric \"" + quoted_text(metric) + "\"" +
                                did_you_mean(metric, {"sda", "ase", "en17037", "udi", "mean"}) +
                                ": give \"sda\", \"ase\", \"en17037\", \"udi\" or \"mean\"");
    }
    g.weight = number(j, "weight", key, 1.0, 0.0, limits::kMaxWeight, true, "");
    if (const auto unknown = find_unknown_key(j, known))
      fail(key + "." + quoted_text(unknown->key), unknown->message + " of a \"" + metric + "\" goal");
    sensors_of(j, key, &g);
    return g;
  }

 private:
  std::string group_names() const {
    std::string out;
    for (const auto& item : groups_.items()) out += (out.empty() ? "" : ", ") + quoted_text(item.key());
    return out;
  }
  std::vector<std::string> group_list() const {
    std::vector<std::string> out;
    if (groups_.is_object())
      for (const auto& item : groups_.items()) out.push_back(item.key());
    return out;
  }

  std::string source_;
  const json& groups_;
  size_t sensors_;
};

}  // namespace

GoalSense ClimateGoal::sense() const {
  switch (metric) {
    case ClimateMetric::SunlightExposure: return GoalSense::AtMost;
    case ClimateMetric::MeanIlluminance: return GoalSense::Target;
    default: return GoalSense::AtLeast;
  }
}

double ClimateGoal::required() const {
  switch (metric) {
    case ClimateMetric::En17037: return 0.5;
    case ClimateMetric::MeanIlluminance: return illuminance_lux;
    default: return area_fraction;
  }
}

std::string ClimateGoal::unit() const {
  switch (metric) {
    case ClimateMetric::En17037: return "hours fraction";
    case ClimateMetric::MeanIlluminance: return "lux";
    default: return "area fraction";
  }
}

std::string ClimateGoal::metric_name() const {
  switch (metric) {
    case ClimateMetric::SpatialDaylightAutonomy: return "sda";
    case ClimateMetric::SunlightExposure: return "ase";
    case ClimateMetric::En17037: return "en17037";
    case ClimateMetric::UsefulDaylight: return "udi";
    case ClimateMetric::MeanIlluminance: return "mean";
  }
  return "?";
}

std::string ClimateGoal::describe() const {
  char text[160];
  switch (metric) {
    case ClimateMetric::SpatialDaylightAutonomy:
      std::snprintf(text, sizeof text, "sDA%s/%g%% >= %s", lux(illuminance_lux).c_str(),
                    std::round(1000.0 * time_fraction) / 10.0, short_percent_text(area_fraction).c_str());
      break;
    case ClimateMetric::SunlightExposure:
      std::snprintf(text, sizeof text, "ASE%s,%s <= %s", lux(illuminance_lux).c_str(), lux(hours).c_str(),
                    short_percent_text(area_fraction).c_str());
      break;
    case ClimateMetric::En17037:
      std::snprintf(text, sizeof text, "EN 17037 %s level", level.c_str());
      break;
    case ClimateMetric::UsefulDaylight:
      std::snprintf(text, sizeof text, "UDI %s-%s lx >= %s", lux(lower_lux).c_str(), lux(upper_lux).c_str(),
                    short_percent_text(area_fraction).c_str());
      break;
    case ClimateMetric::MeanIlluminance:
      std::snprintf(text, sizeof text, "annual mean %s lx", lux(illuminance_lux).c_str());
      break;
  }
  std::string out = text;
  if (sensors_given != "all") out += sensors_given == "list" ? " (" + std::to_string(sensors.size()) + " sensors)"
                                                             : " (" + sensors_given + ")";
  return out;
}

En17037Illuminances en17037_illuminances(const std::string& level) {
  if (level == "medium") return {500.0, 300.0};
  if (level == "high") return {750.0, 500.0};
  return {300.0, 100.0};
}

ClimateGoals parse_climate_goals(const json& goals, const json& groups, size_t sensors, const std::string& source) {
  GoalReader reader(source, groups, sensors);
  reader.check_groups();
  ClimateGoals out;
  if (!goals.is_object()) return out;
  if (goals.contains("least_glazing")) {
    if (!goals.at("least_glazing").is_boolean()) reader.fail("goals.least_glazing", "expected true or false");
    out.least_glazing = goals.at("least_glazing").get<bool>();
  }
  const bool any = goals.contains("climate") && goals.at("climate").is_array() && !goals.at("climate").empty();
  if (out.least_glazing && !any)
    reader.fail("goals.least_glazing", "weighs the glass against climate goals: give them in goals.climate");
  if (!goals.contains("climate") || goals.at("climate").is_null()) return out;
  const json& list = goals.at("climate");
  if (!list.is_array()) reader.fail("goals.climate", "expected a list of goals, e.g. [{\"metric\": \"sda\"}]");
  if (list.size() > 64) reader.fail("goals.climate", "has " + std::to_string(list.size()) + " goals, more than 64");
  for (size_t i = 0; i < list.size(); ++i)
    out.goals.push_back(reader.goal(list[i], "goals.climate[" + std::to_string(i) + "]"));
  return out;
}

}  // namespace fenestra
