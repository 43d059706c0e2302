#pragma once
// Climate-based daylight metrics from hourly illuminance at sensors: annual mean illuminance,
// daylight autonomy (DA) and continuous DA, useful daylight illuminance (UDI), spatial daylight
// autonomy (sDA) and annual sunlight exposure (ASE) after IES LM-83-12 and LEED v4, and EN 17037
// daylight provision. Definitions, edge conventions and sources: docs/climate-metrics.md.
// Units: illuminance in lux, areas in m^2, clock times in hours of local standard time.
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace fenestra {

// The instant an hourly value stands for, in local standard time (no daylight saving time).
// An EPW record labelled hour h covers the hour ending at h:00; its instant is h - 0.5.
struct HourStamp {
  int month = 1;            // 1..12
  int day = 1;              // 1..days of the month (29 February accepted)
  double clock_hour = 0.0;  // [0, 24)
};

// One EN 17037 daylight provision level (Table A.1): target illuminance E_T and minimum target
// illuminance E_TM, lux.
struct En17037Level {
  std::string name;
  double target_lux = 0.0;
  double minimum_target_lux = 0.0;
};

// Which EN 17037 criterion applies: vertical or inclined openings need E_T over 50 % of the
// reference plane and E_TM over 95 %; horizontal openings (rooflights) need E_T over 95 %.
enum class DaylightOpenings { VerticalOrInclined, Horizontal };

struct AnnualMetricSettings {
  // Occupied period, every day: an hour counts when start <= clock_hour < end (local standard time).
  // LM-83-12's analysis period is 08:00-18:00 (3650 hours a year with EPW instants).
  double occupied_start_hour = 8.0;
  double occupied_end_hour = 18.0;
  double da_threshold_lux = 300.0;                           // DA, cDA and sDA
  double sda_time_fraction = 0.5;                            // of occupied hours, (0, 1]
  // LEED v4 EQ Daylight Option 1: 55 % and 75 % for 2 and 3 points; 90 % for 2 points in healthcare.
  std::vector<double> sda_pass_levels = {0.55, 0.75, 0.90};
  // UDI band edges, lux, increasing: bands below the first, between consecutive edges and above the last.
  std::vector<double> udi_edges_lux = {100.0, 300.0, 3000.0};
  double ase_threshold_lux = 1000.0;  // direct sun only; a sensor-hour counts when E_direct > this
  double ase_hours = 250.0;           // a sensor is overlit when it counts MORE than this many occupied hours
  double ase_pass_limit = 0.10;       // LEED v4: ASE1000,250 of no more than 10 %
  DaylightOpenings en17037_openings = DaylightOpenings::VerticalOrInclined;
  std::vector<En17037Level> en17037_levels = {
      {"minimum", 300.0, 100.0}, {"medium", 500.0, 300.0}, {"high", 750.0, 500.0}};
  double en17037_time_fraction = 0.5;  // of daylight hours, (0, 1]

  std::string describe() const;
};

// Everything about the hours and sensors except the illuminance itself.
struct AnnualMetricInputs {
  std::vector<HourStamp> hours;         // one per matrix column
  std::vector<double> sensor_areas_m2;  // one per matrix row, >= 0, not all 0; empty: equal areas
  // EN 17037 daylight hours, the first of these that is given:
  //  1. `daylight_hours`: an explicit selection, one flag per column (1 = daylight hour);
  //  2. `external_horizontal_illuminance` (lux, one per column): the half of the hours with the
  //     highest values (4380 of 8760), as en17037_daylight_hours(). Diffuse horizontal illuminance
  //     follows the standard's use of the median external diffuse illuminance; global also works;
  //  3. neither: the half of the hours with the highest area-mean interior illuminance, an
  //     approximation flagged in En17037Result::daylight_hours_basis.
  std::vector<char> daylight_hours;
  std::vector<double> external_horizontal_illuminance;
};

// One UDI band. Bands are half-open [lower, upper) except the highest inner band, closed at its
// upper edge, so that with the default edges: fell-short E < 100, supplementary 100 <= E < 300,
// autonomous 300 <= E <= 3000, exceeded E > 3000 (and autonomous + exceeded = DA300).
struct UdiBand {
  std::string name;
  double lower_lux = 0.0, upper_lux = 0.0;  // 0 below the first edge, +inf above the last
  bool lower_inclusive = true, upper_inclusive = false;
  Eigen::VectorXd sensor_fraction;  // fraction of occupied hours, per sensor
  double space_fraction = 0.0;      // area-weighted mean of sensor_fraction
};

struct PassLevel {
  double level = 0.0;  // area fraction
  bool passed = false;
};

struct En17037LevelResult {
  En17037Level level;
  // Fraction of daylight hours at which E >= E_T over the required fraction of the area (50 %, or
  // 95 % for horizontal openings), and at which E >= E_TM over 95 % (NaN for horizontal openings).
  double target_hours_fraction = 0.0;
  double minimum_hours_fraction = 0.0;
  bool target_met = false, minimum_met = false, met = false;
};

struct En17037Result {
  DaylightOpenings openings = DaylightOpenings::VerticalOrInclined;
  int daylight_hours = 0;
  std::string daylight_hours_basis;  // "given", "external illuminance", "interior illuminance (approximation)"
  std::vector<En17037LevelResult> levels;
  std::string level_reached;  // the highest level met with every lower level met too; "none"
};

struct AnnualMetrics {
  int sensors = 0, hours = 0, occupied_hours = 0;
  // Per sensor, over occupied hours.
  Eigen::VectorXd mean_illuminance_lux;
  Eigen::VectorXd daylight_autonomy;             // fraction of hours with E >= da_threshold
  Eigen::VectorXd continuous_daylight_autonomy;  // hours weighted min(1, E / da_threshold)
  std::vector<UdiBand> udi;
  // Area-weighted means of the above.
  double space_mean_illuminance_lux = 0.0;
  double space_daylight_autonomy = 0.0;
  double space_continuous_daylight_autonomy = 0.0;
  // sDA: area fraction whose DA >= sda_time_fraction.
  double spatial_daylight_autonomy = 0.0;
  std::vector<PassLevel> sda_levels;
  // ASE (only with direct-sun illuminance): occupied hours above the threshold per sensor, and the
  // area fraction with more than ase_hours of them.
  bool has_ase = false;
  Eigen::VectorXi ase_sensor_hours;
  double annual_sunlight_exposure = 0.0;
  bool ase_passes = false;
  En17037Result en17037;

  std::string to_string() const;
};

// `illuminance`: lux, sensors x hours (rows = sensors). `direct_illuminance`, when given, the
// direct-sun-only illuminance of the same shape (for ASE). Throws std::invalid_argument naming the
// field and value at fault: shapes that disagree, NaN, infinite or negative illuminance (with its
// sensor and hour), settings out of range, weights, and no hour in the occupied period.
AnnualMetrics annual_metrics(const Eigen::MatrixXf& illuminance, const AnnualMetricInputs& inputs,
                             const AnnualMetricSettings& settings = {},
                             const Eigen::MatrixXf* direct_illuminance = nullptr);
AnnualMetrics annual_metrics(const Eigen::MatrixXd& illuminance, const AnnualMetricInputs& inputs,
                             const AnnualMetricSettings& settings = {},
                             const Eigen::MatrixXd* direct_illuminance = nullptr);

// EN 17037 daylight hours from one external horizontal illuminance (lux) per hour: the `count`
// hours with the highest values, ties going to the earlier hour; `count` < 0 means half of the
// hours, rounded down (4380 of 8760). One flag per hour, 1 = daylight hour.
std::vector<char> en17037_daylight_hours(const std::vector<double>& external_horizontal_illuminance,
                                         int count = -1);

}  // namespace fenestra
