#include "scene/sensor_input.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "scene/input_limits.h"
#include "util/quoted_text.h"

namespace fenestra {

using namespace scene_json;  // the path-aware readers

Sensors parse_sensors(const ScenePath& sp, const json& j, const SiteFrame& frame) {
  if (!j.is_object()) sp.fail("sensors", "expected an object");
  check_known_keys(sp, j, "sensors", {"points", "normals", "goals", "goal_units", "weights", "groups"});
  Sensors s;
  if (!j.contains("points") || !j.at("points").is_array() || j.at("points").empty())
    sp.fail("sensors.points", "the scene has no sensors");
  for (size_t i = 0; i < j.at("points").size(); ++i)
    s.points.push_back(point(sp, j.at("points")[i], "sensors.points[" + std::to_string(i) + "]", frame));
  json normals = j.value("normals", json::array({json::array({0, 0, 1})}));
  if (normals.is_array() && normals.size() == 3 && normals[0].is_number()) normals = json::array({normals});
  if (!normals.is_array() || (normals.size() != 1 && normals.size() != s.points.size()))
    sp.fail("sensors.normals", "give one normal for all sensors or one per sensor");
  for (size_t i = 0; i < s.points.size(); ++i) {
    const std::string key = "sensors.normals[" + std::to_string(normals.size() == 1 ? 0 : i) + "]";
    s.normals.push_back(direction(sp, normals[normals.size() == 1 ? 0 : i], key));
  }
  if (j.contains("goals") && !j.at("goals").is_null()) {
    const json& g = j.at("goals");
    if (!g.is_array() || g.size() != s.points.size())
      sp.fail("sensors.goals", "expected one goal per sensor (" + std::to_string(s.points.size()) + ")");
    for (size_t i = 0; i < g.size(); ++i)
      s.goals.push_back(g[i].is_null() ? std::nan("") : number(sp, g[i], "sensors.goals[" + std::to_string(i) + "]"));
  }
  s.goal_units = text_or(sp, j, "goal_units", "sensors", "normalized");
  if (s.goal_units != "normalized" && s.goal_units != "lux" && s.goal_units != "daylight_factor")
    sp.fail("sensors.goal_units", "must be \"normalized\", \"lux\" or \"daylight_factor\"");
  if (j.contains("weights")) {
    const json& w = j.at("weights");
    if (!w.is_array() || w.size() != s.points.size())
      sp.fail("sensors.weights", "expected one weight per sensor (" + std::to_string(s.points.size()) + ")");
    for (size_t i = 0; i < w.size(); ++i) {
      s.weights.push_back(number(sp, w[i], "sensors.weights[" + std::to_string(i) + "]"));
      if (s.weights.back() < 0.0) sp.fail("sensors.weights[" + std::to_string(i) + "]", "must not be negative");
    }
  }
  return s;
}

void parse_goals(const ScenePath& sp, const json& j, Sensors* s) {
  if (j.is_null()) return;
  if (!j.is_object()) sp.fail("goals", "expected an object");
  check_known_keys(sp, j, "goals", {"per_sensor", "units", "weights", "uniform", "climate", "least_glazing"});
  const size_t n = s->points.size();
  if (j.contains("per_sensor")) {
    if (!s->goals.empty()) sp.fail("goals.per_sensor", "the goals are already given in sensors.goals");
    const json& g = j.at("per_sensor");
    if (!g.is_array() || g.size() != n) sp.fail("goals.per_sensor", "expected one goal per sensor (" + std::to_string(n) + ")");
    for (size_t i = 0; i < n; ++i)
      s->goals.push_back(g[i].is_null() ? std::nan("") : number(sp, g[i], "goals.per_sensor[" + std::to_string(i) + "]"));
  }
  if (j.contains("units")) {
    s->goal_units = text(sp, j, "units", "goals");
    if (s->goal_units != "normalized" && s->goal_units != "lux" && s->goal_units != "daylight_factor")
      sp.fail("goals.units", "must be \"normalized\", \"lux\" or \"daylight_factor\"");
  }
  if (j.contains("weights")) {
    if (!s->weights.empty()) sp.fail("goals.weights", "the weights are already given in sensors.weights");
    s->weights = numbers(sp, j.at("weights"), "goals.weights", n);
    for (size_t i = 0; i < n; ++i)
      if (s->weights[i] < 0.0) sp.fail("goals.weights[" + std::to_string(i) + "]", "must not be negative");
  }
  if (j.contains("uniform")) {
    const json& list = j.at("uniform");
    if (!list.is_array()) sp.fail("goals.uniform", "expected a list of {\"sensors\", \"level\", \"min\", \"max\"}");
    for (size_t u = 0; u < list.size(); ++u) {
      const std::string key = "goals.uniform[" + std::to_string(u) + "]";
      const json& g = list[u];
      if (!g.is_object()) sp.fail(key, "expected an object");
      check_known_keys(sp, g, key, {"sensors", "level", "min", "max"});
      UniformGoal goal;
      const json& which = g.value("sensors", json("all"));
      if (which.is_string() && which.get<std::string>() == "all") {
        for (size_t i = 0; i < n; ++i) goal.sensors.push_back(static_cast<int>(i));
      } else if (which.is_array() && !which.empty()) {
        for (const json& i : which) {
          if (!i.is_number_integer() || i.get<long long>() < 0 || i.get<long long>() >= static_cast<long long>(n))
            sp.fail(key + ".sensors", "expected sensor indices 0.." + std::to_string(n - 1) + ", got " + quoted_json(i));
          goal.sensors.push_back(i.get<int>());
        }
      } else {
        sp.fail(key + ".sensors", "expected \"all\" or a non-empty list of sensor indices");
      }
      if (!g.contains("level")) sp.fail(key + ".level", "missing");
      goal.level = number(sp, g.at("level"), key + ".level");
      goal.min = number_or(sp, g, "min", key, goal.min);
      goal.max = number_or(sp, g, "max", key, goal.max);
      if (!(goal.min <= goal.level && goal.level <= goal.max))
        sp.fail(key, "needs min <= level <= max");
      s->uniform_goals.push_back(goal);
    }
  }
}

void check_goals(const ScenePath& sp, const Sensors& s) {
  const double top = s.goal_units == "normalized" ? 1.0 : s.goal_units == "daylight_factor" ? 100.0
                                                                                          : limits::kMaxIlluminance;
  for (size_t i = 0; i < s.weights.size(); ++i)
    if (s.weights[i] > limits::kMaxWeight)
      sp.fail("weights[" + std::to_string(i) + "]", "must not exceed " + show(limits::kMaxWeight));
  auto check = [&](double g, const std::string& key) {
    if (std::isnan(g)) return;
    if (g < 0.0) sp.fail(key, "a goal must not be negative, got " + std::to_string(g));
    if (g > top)
      sp.fail(key, "a goal in " + s.goal_units + " units must not exceed " + std::to_string(top) + ", got " +
                       std::to_string(g));
  };
  for (size_t i = 0; i < s.goals.size(); ++i) check(s.goals[i], "goals[" + std::to_string(i) + "]");
  for (size_t u = 0; u < s.uniform_goals.size(); ++u) {
    const std::string key = "goals.uniform[" + std::to_string(u) + "]";
    check(s.uniform_goals[u].level, key + ".level");
    if (std::isfinite(s.uniform_goals[u].min)) check(s.uniform_goals[u].min, key + ".min");
  }
}

}  // namespace fenestra
