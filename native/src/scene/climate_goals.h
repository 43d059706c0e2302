#pragma once
// Goals that are climate-based metrics over the weather file's year (docs/scene-format.md,
// "Climate goals"): sDA, ASE, EN 17037, UDI and the annual mean, each over a set of sensors.
// Units: illuminance in lux, hours in hours of the occupied period, fractions in [0, 1].
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace fenestra {

enum class ClimateMetric { SpatialDaylightAutonomy, SunlightExposure, En17037, UsefulDaylight, MeanIlluminance };

// Which way a goal's figure must go.
enum class GoalSense { AtLeast, AtMost, Target };

struct ClimateGoal {
  ClimateMetric metric = ClimateMetric::SpatialDaylightAutonomy;
  std::vector<int> sensors;   // indices, sorted, distinct
  std::string sensors_given;  // as the scene names them: "all", a group's name, or "list"
  double weight = 1.0;
  double illuminance_lux = 300.0;   // sDA, ASE, mean
  double time_fraction = 0.5;       // sDA: of occupied hours
  double hours = 250.0;             // ASE: occupied hours above the threshold
  double area_fraction = 0.55;      // sDA, UDI: at least; ASE: at most
  double lower_lux = 100.0, upper_lux = 3000.0;  // UDI band, lower <= E <= upper
  std::string level = "minimum";    // EN 17037: minimum, medium, high

  GoalSense sense() const;
  // The figure the goal asks for: an area fraction (sDA, ASE, UDI), the fraction of daylight
  // hours (EN 17037: 0.5) or lux (mean).
  double required() const;
  std::string unit() const;         // "area fraction", "hours fraction" or "lux"
  std::string metric_name() const;  // "sda", "ase", "en17037", "udi", "mean"
  std::string describe() const;     // e.g. "sDA300/50% >= 55 %"
};

struct ClimateGoals {
  std::vector<ClimateGoal> goals;
  bool least_glazing = false;  // among configurations meeting the goals, the least open area
  bool empty() const { return goals.empty(); }
};

// EN 17037 (Table A.1) levels: target and minimum target illuminance, lux.
struct En17037Illuminances {
  double target_lux = 300.0, minimum_target_lux = 100.0;
};
En17037Illuminances en17037_illuminances(const std::string& level);

// Parses goals.climate and goals.least_glazing, with the sensor groups of sensors.groups (null or
// an object of name: [indices]). Throws std::invalid_argument "scene 'SOURCE': KEY: problem".
ClimateGoals parse_climate_goals(const nlohmann::json& goals, const nlohmann::json& groups, size_t sensors,
                                 const std::string& source);

}  // namespace fenestra
