#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "daylight/annual_metrics.h"

using namespace fenestra;

namespace {

// One day (1 January) of 24 EPW hours: instants 00:30 ... 23:30.
std::vector<HourStamp> one_day() {
  std::vector<HourStamp> hours;
  for (int h = 0; h < 24; ++h) hours.push_back({1, 1, h + 0.5});
  return hours;
}

// The date of day-of-year `d` (0-based) in a 365-day year.
HourStamp stamp(int d, double clock_hour) {
  static const int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  int month = 0;
  while (d >= kDays[month]) d -= kDays[month++];
  return {month + 1, d + 1, clock_hour};
}

// Three sensors over one day; the occupied hours (08:00-18:00) are columns 8..17.
//  sensor 0: 500 lx all day;
//  sensor 1: the occupied values below, 100 000 lx outside them (so any leak of an unoccupied hour shows);
//  sensor 2: 150 lx when occupied, 0 otherwise.
const float kSensor1Occupied[10] = {50, 100, 150, 299, 300, 1000, 3000, 3001, 6000, 0};

Eigen::MatrixXf day_pattern() {
  Eigen::MatrixXf e(3, 24);
  for (int j = 0; j < 24; ++j) {
    const bool occupied = j >= 8 && j < 18;
    e(0, j) = 500.0f;
    e(1, j) = occupied ? kSensor1Occupied[j - 8] : 100000.0f;
    e(2, j) = occupied ? 150.0f : 0.0f;
  }
  return e;
}

// Expects `run` to throw std::invalid_argument whose message holds every one of `parts`.
void expect_refused(const std::function<void()>& run, std::initializer_list<std::string> parts) {
  try {
    run();
    ADD_FAILURE() << "accepted; expected a message with \"" << *parts.begin() << "\"";
  } catch (const std::invalid_argument& e) {
    for (const std::string& part : parts)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << "missing \"" << part << "\" in: " << e.what();
  }
}

}  // namespace

// ---- Hand-computed answers ----

TEST(AnnualMetrics, HandComputedDayPattern) {
  AnnualMetricInputs in;
  in.hours = one_day();
  const AnnualMetrics m = annual_metrics(day_pattern(), in);
  EXPECT_EQ(m.occupied_hours, 10);

  // Sensor 1: sum 13 900 lx over 10 hours; 5 values >= 300; partial credit (50+100+150+299)/300.
  EXPECT_DOUBLE_EQ(m.mean_illuminance_lux[0], 500.0);
  EXPECT_DOUBLE_EQ(m.mean_illuminance_lux[1], 1390.0);
  EXPECT_DOUBLE_EQ(m.mean_illuminance_lux[2], 150.0);
  EXPECT_DOUBLE_EQ(m.daylight_autonomy[0], 1.0);
  EXPECT_DOUBLE_EQ(m.daylight_autonomy[1], 0.5);  // 300 lx itself counts
  EXPECT_DOUBLE_EQ(m.daylight_autonomy[2], 0.0);
  EXPECT_NEAR(m.continuous_daylight_autonomy[0], 1.0, 1e-12);
  EXPECT_NEAR(m.continuous_daylight_autonomy[1], (599.0 / 300.0 + 5.0) / 10.0, 1e-12);
  EXPECT_NEAR(m.continuous_daylight_autonomy[2], 0.5, 1e-12);

  // UDI of sensor 1: <100 {50, 0}; [100, 300) {100, 150, 299}; [300, 3000] {300, 1000, 3000}; >3000 {3001, 6000}.
  ASSERT_EQ(m.udi.size(), 4u);
  const double expected[3][4] = {{0, 0, 1, 0}, {0.2, 0.3, 0.3, 0.2}, {0, 1, 0, 0}};
  for (int s = 0; s < 3; ++s)
    for (int b = 0; b < 4; ++b)
      EXPECT_DOUBLE_EQ(m.udi[b].sensor_fraction[s], expected[s][b]) << "sensor " << s << " band " << b;
  EXPECT_NE(m.udi[0].name.find("fell-short"), std::string::npos);
  EXPECT_NE(m.udi[3].name.find("exceeded"), std::string::npos);
  EXPECT_TRUE(m.udi[2].upper_inclusive);
  EXPECT_FALSE(m.udi[1].upper_inclusive);
  EXPECT_FALSE(m.udi[3].lower_inclusive);
  // UDI-autonomous + UDI-exceeded is DA300 when 300 is an edge.
  for (int s = 0; s < 3; ++s)
    EXPECT_DOUBLE_EQ(m.udi[2].sensor_fraction[s] + m.udi[3].sensor_fraction[s], m.daylight_autonomy[s]);

  // Equal areas: space values are plain means; DA >= 50 % at sensors 0 and 1.
  EXPECT_DOUBLE_EQ(m.space_mean_illuminance_lux, 680.0);
  EXPECT_DOUBLE_EQ(m.space_daylight_autonomy, 0.5);
  EXPECT_DOUBLE_EQ(m.spatial_daylight_autonomy, 2.0 / 3.0);
  ASSERT_EQ(m.sda_levels.size(), 3u);
  EXPECT_TRUE(m.sda_levels[0].passed);   // 55 %
  EXPECT_FALSE(m.sda_levels[1].passed);  // 75 %
  EXPECT_FALSE(m.sda_levels[2].passed);  // 90 %
  EXPECT_DOUBLE_EQ(m.udi[1].space_fraction, (0.0 + 0.3 + 1.0) / 3.0);
  EXPECT_FALSE(m.has_ase);
}

TEST(AnnualMetrics, DoubleInputGivesTheSameAnswers) {
  AnnualMetricInputs in;
  in.hours = one_day();
  const Eigen::MatrixXd e = day_pattern().cast<double>();
  const AnnualMetrics f = annual_metrics(day_pattern(), in), d = annual_metrics(e, in);
  EXPECT_EQ(f.mean_illuminance_lux, d.mean_illuminance_lux);
  EXPECT_EQ(f.daylight_autonomy, d.daylight_autonomy);
  EXPECT_EQ(f.continuous_daylight_autonomy, d.continuous_daylight_autonomy);
  EXPECT_EQ(f.spatial_daylight_autonomy, d.spatial_daylight_autonomy);
}

TEST(AnnualMetrics, SensorAreasWeightSpatialDaylightAutonomy) {
  AnnualMetricInputs in;
  in.hours = one_day();
  const Eigen::MatrixXf e = day_pattern();
  in.sensor_areas_m2 = {1.0, 2.0, 7.0};  // sensors 0 and 1 pass: 3 of 10 m^2
  EXPECT_DOUBLE_EQ(annual_metrics(e, in).spatial_daylight_autonomy, 0.3);
  EXPECT_DOUBLE_EQ(annual_metrics(e, in).space_mean_illuminance_lux, (500.0 + 2 * 1390.0 + 7 * 150.0) / 10.0);
  in.sensor_areas_m2 = {0.0, 1.0, 0.0};  // sensor 1 alone, at exactly DA = 50 %
  EXPECT_DOUBLE_EQ(annual_metrics(e, in).spatial_daylight_autonomy, 1.0);
  in.sensor_areas_m2 = {0.0, 0.0, 5.0};
  EXPECT_DOUBLE_EQ(annual_metrics(e, in).spatial_daylight_autonomy, 0.0);

  // Raising the time fraction just above 50 % drops sensor 1.
  in.sensor_areas_m2.clear();
  AnnualMetricSettings s;
  s.sda_time_fraction = 0.51;
  EXPECT_DOUBLE_EQ(annual_metrics(e, in, s).spatial_daylight_autonomy, 1.0 / 3.0);
}

TEST(AnnualMetrics, OccupiedPeriodIsHalfOpen) {
  // Instants just before and at the edges of [08:00, 18:00).
  AnnualMetricInputs in;
  in.hours = {{6, 1, 7.999}, {6, 1, 8.0}, {6, 1, 17.999}, {6, 1, 18.0}};
  Eigen::MatrixXf e(1, 4);
  e << 1, 2, 4, 8;
  AnnualMetrics m = annual_metrics(e, in);
  EXPECT_EQ(m.occupied_hours, 2);
  EXPECT_DOUBLE_EQ(m.mean_illuminance_lux[0], 3.0);  // (2 + 4) / 2

  AnnualMetricSettings all_day;
  all_day.occupied_start_hour = 0.0;
  all_day.occupied_end_hour = 24.0;
  m = annual_metrics(e, in, all_day);
  EXPECT_EQ(m.occupied_hours, 4);
  EXPECT_DOUBLE_EQ(m.mean_illuminance_lux[0], 15.0 / 4.0);
}

TEST(AnnualMetrics, UdiWithOtherEdges) {
  // Two edges make three bands: E < 100, 100 <= E <= 2000, E > 2000.
  AnnualMetricInputs in;
  in.hours = one_day();
  AnnualMetricSettings s;
  s.udi_edges_lux = {100.0, 2000.0};
  const AnnualMetrics m = annual_metrics(day_pattern(), in, s);
  ASSERT_EQ(m.udi.size(), 3u);
  // Sensor 1: {50, 0} | {100, 150, 299, 300, 1000} | {3000, 3001, 6000}.
  EXPECT_DOUBLE_EQ(m.udi[0].sensor_fraction[1], 0.2);
  EXPECT_DOUBLE_EQ(m.udi[1].sensor_fraction[1], 0.5);
  EXPECT_DOUBLE_EQ(m.udi[2].sensor_fraction[1], 0.3);
  EXPECT_TRUE(m.udi[1].upper_inclusive);
}

// ---- ASE: more than 250 hours, above (not at) 1000 lx ----

TEST(AnnualMetrics, AseCountsMoreThan250HoursAbove1000Lux) {
  // 300 occupied hours (one at 12:30 on each of 300 days) and 10 unoccupied ones (06:30).
  AnnualMetricInputs in;
  for (int d = 0; d < 300; ++d) in.hours.push_back(stamp(d, 12.5));
  for (int d = 0; d < 10; ++d) in.hours.push_back(stamp(d, 6.5));
  const int n = static_cast<int>(in.hours.size());
  Eigen::MatrixXf total = Eigen::MatrixXf::Constant(3, n, 500.0f), direct = Eigen::MatrixXf::Zero(3, n);
  for (int j = 0; j < 250; ++j) direct(0, j) = 1500.0f;  // exactly 250 hours: not overlit
  for (int j = 0; j < 251; ++j) direct(1, j) = 1500.0f;  // 251 hours: overlit
  for (int j = 0; j < 300; ++j) direct(2, j) = 1000.0f;  // at the threshold, never above it
  for (int j = 300; j < n; ++j) direct(0, j) = 5000.0f;  // unoccupied: must not count

  AnnualMetrics m = annual_metrics(total, in, {}, &direct);
  ASSERT_TRUE(m.has_ase);
  EXPECT_EQ(m.ase_sensor_hours[0], 250);
  EXPECT_EQ(m.ase_sensor_hours[1], 251);
  EXPECT_EQ(m.ase_sensor_hours[2], 0);
  EXPECT_DOUBLE_EQ(m.annual_sunlight_exposure, 1.0 / 3.0);
  EXPECT_FALSE(m.ase_passes);

  AnnualMetricSettings s;
  s.ase_hours = 249.0;  // now sensor 0 is overlit too
  EXPECT_DOUBLE_EQ(annual_metrics(total, in, s, &direct).annual_sunlight_exposure, 2.0 / 3.0);

  // The LEED limit, ASE <= 10 % of the area, at the areas that put sensor 1 just inside and outside it.
  in.sensor_areas_m2 = {1.0, 10.0, 89.0};
  m = annual_metrics(total, in, {}, &direct);
  EXPECT_DOUBLE_EQ(m.annual_sunlight_exposure, 0.10);
  EXPECT_TRUE(m.ase_passes);
  in.sensor_areas_m2 = {1.0, 11.0, 88.0};
  m = annual_metrics(total, in, {}, &direct);
  EXPECT_DOUBLE_EQ(m.annual_sunlight_exposure, 0.11);
  EXPECT_FALSE(m.ase_passes);
}

// ---- EN 17037 ----

namespace {

// Four sensors over eight hours; the daylight hours are columns 0..5. Per hour and criterion (equal
// areas; the target needs 2 of 4 sensors, the minimum target all 4):
//   hour  E (lx)                 T300 T500 T750  M100 M300 M500
//   0     800 800 600 600        y    y    y     y    y    y
//   1     600 600 150 150        y    y    -     y    -    -
//   2     400 400 120  90        y    -    -     -    -    -
//   3     500 500 350 350        y    y    -     y    y    -
//   4     300 100 100 100        -    -    -     y    -    -
//   5       0   0   0   0        -    -    -     -    -    -
//   6, 7  5000 everywhere, not daylight hours
// Of 6 daylight hours: T300 4, T500 3, T750 1; M100 4, M300 2, M500 1.
Eigen::MatrixXf en_pattern() {
  Eigen::MatrixXf e(4, 8);
  e.col(0) << 800, 800, 600, 600;
  e.col(1) << 600, 600, 150, 150;
  e.col(2) << 400, 400, 120, 90;
  e.col(3) << 500, 500, 350, 350;
  e.col(4) << 300, 100, 100, 100;
  e.col(5) << 0, 0, 0, 0;
  e.col(6).setConstant(5000);
  e.col(7).setConstant(5000);
  return e;
}

AnnualMetricInputs en_inputs() {
  AnnualMetricInputs in;
  for (int j = 0; j < 8; ++j) in.hours.push_back({3, 21, 9.5 + j});
  in.daylight_hours = {1, 1, 1, 1, 1, 1, 0, 0};
  return in;
}

}  // namespace

TEST(AnnualMetrics, En17037VerticalOpeningsWithGivenDaylightHours) {
  const En17037Result r = annual_metrics(en_pattern(), en_inputs()).en17037;
  EXPECT_EQ(r.daylight_hours, 6);
  EXPECT_EQ(r.daylight_hours_basis, "given");
  ASSERT_EQ(r.levels.size(), 3u);
  const double target[3] = {4.0 / 6, 3.0 / 6, 1.0 / 6}, minimum[3] = {4.0 / 6, 2.0 / 6, 1.0 / 6};
  for (int l = 0; l < 3; ++l) {
    EXPECT_DOUBLE_EQ(r.levels[l].target_hours_fraction, target[l]) << r.levels[l].level.name;
    EXPECT_DOUBLE_EQ(r.levels[l].minimum_hours_fraction, minimum[l]) << r.levels[l].level.name;
  }
  EXPECT_TRUE(r.levels[0].met);
  EXPECT_TRUE(r.levels[1].target_met);  // exactly 50 % of the daylight hours
  EXPECT_FALSE(r.levels[1].minimum_met);
  EXPECT_FALSE(r.levels[1].met);
  EXPECT_FALSE(r.levels[2].met);
  EXPECT_EQ(r.level_reached, "minimum");

  // Levels are grades: one met above a lower one missed is not reached.
  AnnualMetricSettings s;
  s.en17037_levels = {{"a", 300.0, 300.0}, {"b", 500.0, 100.0}};  // a: M300 2 of 6; b: T500 3 of 6, M100 4 of 6
  const En17037Result graded = annual_metrics(en_pattern(), en_inputs(), s).en17037;
  EXPECT_FALSE(graded.levels[0].met);
  EXPECT_TRUE(graded.levels[1].met);
  EXPECT_EQ(graded.level_reached, "none");
}

TEST(AnnualMetrics, En17037HorizontalOpeningsNeedTheTargetOver95Percent) {
  AnnualMetricSettings s;
  s.en17037_openings = DaylightOpenings::Horizontal;
  // All four sensors >= 300 lx at hours 0 and 3 only; >= 500 at hour 0 only.
  En17037Result r = annual_metrics(en_pattern(), en_inputs(), s).en17037;
  EXPECT_DOUBLE_EQ(r.levels[0].target_hours_fraction, 2.0 / 6);
  EXPECT_DOUBLE_EQ(r.levels[1].target_hours_fraction, 1.0 / 6);
  EXPECT_TRUE(std::isnan(r.levels[0].minimum_hours_fraction));
  EXPECT_EQ(r.level_reached, "none");
  s.en17037_time_fraction = 1.0 / 3.0;  // 2 of 6 hours is exactly one third
  r = annual_metrics(en_pattern(), en_inputs(), s).en17037;
  EXPECT_TRUE(r.levels[0].met);
  EXPECT_FALSE(r.levels[1].met);
  EXPECT_EQ(r.level_reached, "minimum");
}

TEST(AnnualMetrics, En17037DaylightHoursAreTheBrighterHalf) {
  // Top 3 of 6: 9 (hour 5), 5 (hour 0), then the tie at 3 goes to the earlier hour 2.
  EXPECT_EQ(en17037_daylight_hours({5, 1, 3, 3, 0, 9}), (std::vector<char>{1, 0, 1, 0, 0, 1}));
  EXPECT_EQ(en17037_daylight_hours({5, 1, 3, 3, 0, 9}, 1), (std::vector<char>{0, 0, 0, 0, 0, 1}));
  std::vector<double> year(8760);
  for (int j = 0; j < 8760; ++j) year[j] = (j * 7919) % 8760;  // a permutation of 0..8759
  const std::vector<char> flags = en17037_daylight_hours(year);
  EXPECT_EQ(std::count(flags.begin(), flags.end(), char(1)), 4380);
  for (int j = 0; j < 8760; ++j) ASSERT_EQ(flags[j], year[j] >= 4380 ? 1 : 0) << "hour " << j;

  // Through annual_metrics: external illuminance whose brighter half (4 of 8 hours) is hours 0..3.
  AnnualMetricInputs in = en_inputs();
  in.daylight_hours.clear();
  in.external_horizontal_illuminance = {9e4, 8e4, 7e4, 6e4, 1, 1, 0, 0};
  En17037Result r = annual_metrics(en_pattern(), in).en17037;
  EXPECT_EQ(r.daylight_hours_basis, "external illuminance");
  EXPECT_EQ(r.daylight_hours, 4);
  EXPECT_DOUBLE_EQ(r.levels[0].target_hours_fraction, 1.0);   // T300 at hours 0..3
  EXPECT_DOUBLE_EQ(r.levels[0].minimum_hours_fraction, 0.75); // M100 at 0, 1, 3

  // Without weather, the four brightest hours of the room itself: 6, 7, 0, 3.
  in.external_horizontal_illuminance.clear();
  r = annual_metrics(en_pattern(), in).en17037;
  EXPECT_EQ(r.daylight_hours_basis, "interior illuminance (approximation)");
  EXPECT_EQ(r.daylight_hours, 4);
  EXPECT_DOUBLE_EQ(r.levels[2].target_hours_fraction, 3.0 / 4);  // T750 at 6, 7, 0
}

// ---- Invariances ----

namespace {

struct RandomCase {
  Eigen::MatrixXf total, direct;
  AnnualMetricInputs in;
};

RandomCase random_case(unsigned seed, int sensors, int hours) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> lux(0.0f, 4000.0f);
  std::uniform_int_distribution<int> day(0, 364), clock(0, 23), flag(0, 1);
  std::uniform_real_distribution<double> area(0.1, 2.0);
  RandomCase c;
  c.total.resize(sensors, hours);
  c.direct.resize(sensors, hours);
  for (int j = 0; j < hours; ++j) {
    c.in.hours.push_back(stamp(day(rng), clock(rng) + 0.5));
    c.in.daylight_hours.push_back(static_cast<char>(flag(rng)));
    for (int i = 0; i < sensors; ++i) {
      c.total(i, j) = lux(rng);
      c.direct(i, j) = 0.5f * c.total(i, j);
    }
  }
  for (int i = 0; i < sensors; ++i) c.in.sensor_areas_m2.push_back(area(rng));
  return c;
}

void expect_same_metrics(const AnnualMetrics& a, const AnnualMetrics& b) {
  EXPECT_EQ(a.occupied_hours, b.occupied_hours);
  for (int i = 0; i < a.sensors; ++i)
    EXPECT_NEAR(a.mean_illuminance_lux[i], b.mean_illuminance_lux[i], 1e-12 * a.mean_illuminance_lux[i]);
  EXPECT_EQ(a.daylight_autonomy, b.daylight_autonomy);  // counts: exact
  EXPECT_TRUE(a.continuous_daylight_autonomy.isApprox(b.continuous_daylight_autonomy, 1e-12));
  for (size_t k = 0; k < a.udi.size(); ++k) EXPECT_EQ(a.udi[k].sensor_fraction, b.udi[k].sensor_fraction);
  EXPECT_EQ(a.spatial_daylight_autonomy, b.spatial_daylight_autonomy);
  EXPECT_EQ(a.ase_sensor_hours, b.ase_sensor_hours);
  EXPECT_EQ(a.annual_sunlight_exposure, b.annual_sunlight_exposure);
  EXPECT_EQ(a.en17037.daylight_hours, b.en17037.daylight_hours);
  for (size_t l = 0; l < a.en17037.levels.size(); ++l) {
    EXPECT_EQ(a.en17037.levels[l].target_hours_fraction, b.en17037.levels[l].target_hours_fraction);
    EXPECT_EQ(a.en17037.levels[l].minimum_hours_fraction, b.en17037.levels[l].minimum_hours_fraction);
  }
  EXPECT_EQ(a.en17037.level_reached, b.en17037.level_reached);
}

}  // namespace

TEST(AnnualMetrics, PermutingHoursChangesNothing) {
  const RandomCase c = random_case(7, 6, 600);
  std::vector<int> order(600);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(11));
  RandomCase p = c;
  for (int j = 0; j < 600; ++j) {
    p.total.col(j) = c.total.col(order[j]);
    p.direct.col(j) = c.direct.col(order[j]);
    p.in.hours[j] = c.in.hours[order[j]];
    p.in.daylight_hours[j] = c.in.daylight_hours[order[j]];
  }
  const AnnualMetrics a = annual_metrics(c.total, c.in, {}, &c.direct);
  const AnnualMetrics b = annual_metrics(p.total, p.in, {}, &p.direct);
  ASSERT_GT(a.occupied_hours, 100);
  expect_same_metrics(a, b);

  // The same with daylight hours chosen from (tie-free) external illuminance that moves with its hours.
  std::vector<double> external(600);
  for (int j = 0; j < 600; ++j) external[j] = 1000.0 + j * 37.0;
  RandomCase ce = c, pe = p;
  ce.in.daylight_hours.clear();
  pe.in.daylight_hours.clear();
  ce.in.external_horizontal_illuminance = external;
  pe.in.external_horizontal_illuminance.resize(600);
  for (int j = 0; j < 600; ++j) pe.in.external_horizontal_illuminance[j] = external[order[j]];
  expect_same_metrics(annual_metrics(ce.total, ce.in, {}, &ce.direct), annual_metrics(pe.total, pe.in, {}, &pe.direct));
}

TEST(AnnualMetrics, DoublingIlluminanceIsHalvingTheThresholds) {
  // DA_T(2E) = DA_{T/2}(E) and the same for cDA and UDI; doubling a float is exact.
  const RandomCase c = random_case(3, 5, 400);
  const Eigen::MatrixXf doubled = 2.0f * c.total;
  AnnualMetricSettings half;
  half.da_threshold_lux = 150.0;
  half.udi_edges_lux = {50.0, 150.0, 1500.0};
  const AnnualMetrics base = annual_metrics(c.total, c.in);
  const AnnualMetrics twice = annual_metrics(doubled, c.in);
  const AnnualMetrics lowered = annual_metrics(c.total, c.in, half);
  EXPECT_EQ(twice.daylight_autonomy, lowered.daylight_autonomy);
  EXPECT_EQ(twice.continuous_daylight_autonomy, lowered.continuous_daylight_autonomy);
  for (size_t k = 0; k < twice.udi.size(); ++k) EXPECT_EQ(twice.udi[k].sensor_fraction, lowered.udi[k].sensor_fraction);
  EXPECT_EQ(twice.spatial_daylight_autonomy, lowered.spatial_daylight_autonomy);
  EXPECT_TRUE(twice.mean_illuminance_lux.isApprox(2.0 * base.mean_illuminance_lux, 1e-12));
  // More light never lowers DA, and here (uniform 0..4000 lx) it raises it at every sensor.
  for (int i = 0; i < 5; ++i) EXPECT_GT(twice.daylight_autonomy[i], base.daylight_autonomy[i]);
}

// ---- Bad input ----

TEST(AnnualMetrics, RefusesBadInputNamingTheValue) {
  AnnualMetricInputs in;
  in.hours = one_day();
  const Eigen::MatrixXf good = day_pattern();

  Eigen::MatrixXf nan = good;
  nan(1, 5) = std::nanf("");
  expect_refused([&] { annual_metrics(nan, in); }, {"illuminance at sensor 1", "hour 5 (01-01 05:30)", "nan"});
  Eigen::MatrixXf negative = good;
  negative(2, 9) = -2.5f;
  expect_refused([&] { annual_metrics(negative, in); }, {"sensor 2", "hour 9 (01-01 09:30)", "-2.5"});
  Eigen::MatrixXf infinite = good;
  infinite(0, 0) = INFINITY;
  expect_refused([&] { annual_metrics(infinite, in); }, {"sensor 0", "hour 0", "inf"});
  Eigen::MatrixXf direct = Eigen::MatrixXf::Zero(3, 23);
  expect_refused([&] { annual_metrics(good, in, {}, &direct); }, {"direct_illuminance is 3 x 23", "3 x 24"});
  direct = Eigen::MatrixXf::Zero(3, 24);
  direct(0, 3) = -1.0f;
  expect_refused([&] { annual_metrics(good, in, {}, &direct); }, {"direct_illuminance at sensor 0", "hour 3"});

  AnnualMetricInputs short_hours = in;
  short_hours.hours.pop_back();
  expect_refused([&] { annual_metrics(good, short_hours); }, {"hours has 23 stamps for 24"});
  AnnualMetricInputs bad_date = in;
  bad_date.hours[4] = {2, 30, 4.5};
  expect_refused([&] { annual_metrics(good, bad_date); }, {"hours[4]", "month 2, day 30"});
  bad_date.hours[4] = {2, 3, 24.0};
  expect_refused([&] { annual_metrics(good, bad_date); }, {"hours[4].clock_hour = 24"});

  AnnualMetricInputs areas = in;
  areas.sensor_areas_m2 = {1.0, -0.5, 1.0};
  expect_refused([&] { annual_metrics(good, areas); }, {"sensor_areas_m2[1] = -0.5"});
  areas.sensor_areas_m2 = {0.0, 0.0, 0.0};
  expect_refused([&] { annual_metrics(good, areas); }, {"sensor_areas_m2 are all 0"});
  areas.sensor_areas_m2 = {1.0, 1.0};
  expect_refused([&] { annual_metrics(good, areas); }, {"sensor_areas_m2 has 2 values for 3 sensors"});

  const auto with = [&](const std::function<void(AnnualMetricSettings&)>& change,
                        std::initializer_list<std::string> parts) {
    AnnualMetricSettings s;
    change(s);
    expect_refused([&] { annual_metrics(good, in, s); }, parts);
  };
  with([](AnnualMetricSettings& s) { s.da_threshold_lux = 0.0; }, {"da_threshold_lux = 0"});
  with([](AnnualMetricSettings& s) { s.sda_time_fraction = 1.5; }, {"sda_time_fraction = 1.5"});
  with([](AnnualMetricSettings& s) { s.sda_time_fraction = 0.0; }, {"sda_time_fraction = 0"});
  with([](AnnualMetricSettings& s) { s.udi_edges_lux = {100, 3000, 300}; }, {"udi_edges_lux[2] = 300", "3000"});
  with([](AnnualMetricSettings& s) { s.udi_edges_lux = {100}; }, {"at least 2 edges"});
  with([](AnnualMetricSettings& s) { s.ase_threshold_lux = -1000; }, {"ase_threshold_lux = -1000"});
  with([](AnnualMetricSettings& s) { s.ase_hours = NAN; }, {"ase_hours = nan"});
  with([](AnnualMetricSettings& s) { s.occupied_start_hour = s.occupied_end_hour = 8.0; }, {"occupied hours [8, 8)"});
  with([](AnnualMetricSettings& s) { s.en17037_levels[1].target_lux = 200; },
       {"en17037_levels[1] (medium).target_lux = 200"});
  with([](AnnualMetricSettings& s) { s.en17037_time_fraction = 2.0; }, {"en17037_time_fraction = 2"});

  // No occupied hour: a night-time study.
  AnnualMetricInputs night;
  for (int h = 0; h < 24; ++h) night.hours.push_back({1, 1, h < 12 ? 2.5 : 21.5});
  expect_refused([&] { annual_metrics(good, night); }, {"none of the 24 hours", "[08:00, 18:00)"});

  AnnualMetricInputs flags = in;
  flags.daylight_hours.assign(24, 0);
  expect_refused([&] { annual_metrics(good, flags); }, {"daylight_hours selects no hour"});
  flags.daylight_hours[3] = 2;
  expect_refused([&] { annual_metrics(good, flags); }, {"daylight_hours[3] = 2"});
  flags.daylight_hours.assign(5, 1);
  expect_refused([&] { annual_metrics(good, flags); }, {"daylight_hours has 5 flags for 24"});
  AnnualMetricInputs external = in;
  external.external_horizontal_illuminance.assign(24, 1000.0);
  external.external_horizontal_illuminance[7] = NAN;
  expect_refused([&] { annual_metrics(good, external); }, {"external_horizontal_illuminance[7] = nan"});
  expect_refused([&] { en17037_daylight_hours({1, 2, 3}, 4); }, {"cannot take 4 of 3"});
}

// ---- A synthetic year against a plain recomputation ----

namespace {

constexpr double kPi = 3.14159265358979323846;

// Sine of the solar elevation at latitude 45 N for day `d` (0-based) and solar hour `clock`
// (Cooper's declination; a proxy, not an ephemeris).
double sin_elevation(int d, double clock) {
  const double lat = 45.0 * kPi / 180.0;
  const double decl = 23.44 * kPi / 180.0 * std::sin(2.0 * kPi * (284 + d + 1) / 365.0);
  const double hour_angle = (clock - 12.0) * 15.0 * kPi / 180.0;
  return std::sin(lat) * std::sin(decl) + std::cos(lat) * std::cos(decl) * std::cos(hour_angle);
}

// A deterministic "cloudiness" per day in [0.3, 1].
double clearness(int d) {
  const double x = std::sin(d * 12.9898) * 43758.5453;
  return 0.3 + 0.7 * (x - std::floor(x));
}

}  // namespace

TEST(AnnualMetrics, SyntheticYearMatchesAPlainRecomputation) {
  const int sensors = 42, hours = 8760;  // not a multiple of 4: the partial sums' tail runs
  Eigen::MatrixXd total(sensors, hours), direct(sensors, hours);
  AnnualMetricInputs in;
  in.external_horizontal_illuminance.resize(hours);
  for (int d = 0; d < 365; ++d)
    for (int h = 0; h < 24; ++h) {
      const int j = d * 24 + h;
      const double s = std::max(0.0, sin_elevation(d, h + 0.5)), c = clearness(d);
      in.hours.push_back(stamp(d, h + 0.5));
      in.external_horizontal_illuminance[j] = 20000.0 * c * (1.0 + sin_elevation(d, h + 0.5));
      for (int i = 0; i < sensors; ++i) {
        total(i, j) = (100.0 + 150.0 * i) * c * s;  // deeper sensors (low i) are darker
        direct(i, j) = (i % 3 == 0) ? 4000.0 * c * c * s : 0.0;
      }
    }
  for (int i = 0; i < sensors; ++i) in.sensor_areas_m2.push_back(0.5 + 0.01 * i);
  const AnnualMetricSettings settings;
  const AnnualMetrics m = annual_metrics(total, in, settings, &direct);

  // The occupied hours: 10 a day.
  std::vector<int> occupied;
  for (int j = 0; j < hours; ++j)
    if (j % 24 >= 8 && j % 24 < 18) occupied.push_back(j);
  ASSERT_EQ(m.occupied_hours, 3650);
  const double n = occupied.size();

  double area = 0, sda_area = 0, ase_area = 0;
  for (int i = 0; i < sensors; ++i) {
    // Sorted occupied values: counts by binary search.
    std::vector<double> v;
    for (int j : occupied) v.push_back(total(i, j));
    std::sort(v.begin(), v.end());
    const auto at_least = [&](double x) { return double(v.end() - std::lower_bound(v.begin(), v.end(), x)); };
    const auto above = [&](double x) { return double(v.end() - std::upper_bound(v.begin(), v.end(), x)); };
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / n;
    double cda = 0;
    for (double e : v) cda += e >= 300.0 ? 1.0 : e / 300.0;
    EXPECT_NEAR(m.mean_illuminance_lux[i], mean, 1e-9 * mean) << "sensor " << i;
    EXPECT_DOUBLE_EQ(m.daylight_autonomy[i], at_least(300.0) / n) << "sensor " << i;
    EXPECT_NEAR(m.continuous_daylight_autonomy[i], cda / n, 1e-12) << "sensor " << i;
    EXPECT_DOUBLE_EQ(m.udi[0].sensor_fraction[i], (n - at_least(100.0)) / n);
    EXPECT_DOUBLE_EQ(m.udi[1].sensor_fraction[i], (at_least(100.0) - at_least(300.0)) / n);
    EXPECT_DOUBLE_EQ(m.udi[2].sensor_fraction[i], (at_least(300.0) - above(3000.0)) / n);
    EXPECT_DOUBLE_EQ(m.udi[3].sensor_fraction[i], above(3000.0) / n);
    const int sun_hours = static_cast<int>(
        std::count_if(occupied.begin(), occupied.end(), [&](int j) { return direct(i, j) > 1000.0; }));
    EXPECT_EQ(m.ase_sensor_hours[i], sun_hours) << "sensor " << i;
    const double a = in.sensor_areas_m2[i];
    area += a;
    if (2.0 * at_least(300.0) >= n) sda_area += a;
    if (sun_hours > 250) ase_area += a;
  }
  EXPECT_NEAR(m.spatial_daylight_autonomy, sda_area / area, 1e-12);
  EXPECT_NEAR(m.annual_sunlight_exposure, ase_area / area, 1e-12);
  // The case must exercise every outcome, or the comparison proves little.
  EXPECT_GT(m.spatial_daylight_autonomy, 0.1);
  EXPECT_LT(m.spatial_daylight_autonomy, 0.9);
  EXPECT_GT(m.annual_sunlight_exposure, 0.0);
  EXPECT_LT(m.annual_sunlight_exposure, 1.0);

  // EN 17037: the 4380 brightest hours by a stable sort, then per hour the sensors meeting each
  // level, compared with the area in integer-free form: 2 x area >= total area, 20 x area >= 19 x total.
  std::vector<int> order(hours);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return in.external_horizontal_illuminance[a] > in.external_horizontal_illuminance[b];
  });
  order.resize(4380);
  ASSERT_EQ(m.en17037.daylight_hours, 4380);
  for (size_t l = 0; l < settings.en17037_levels.size(); ++l) {
    const En17037Level& level = settings.en17037_levels[l];
    int target_hours = 0, minimum_hours = 0;
    for (int j : order) {
      double target_area = 0, minimum_area = 0;
      for (int i = 0; i < sensors; ++i) {
        if (total(i, j) >= level.target_lux) target_area += in.sensor_areas_m2[i];
        if (total(i, j) >= level.minimum_target_lux) minimum_area += in.sensor_areas_m2[i];
      }
      if (2.0 * target_area >= area) ++target_hours;
      if (20.0 * minimum_area >= 19.0 * area) ++minimum_hours;
    }
    EXPECT_DOUBLE_EQ(m.en17037.levels[l].target_hours_fraction, target_hours / 4380.0) << level.name;
    EXPECT_DOUBLE_EQ(m.en17037.levels[l].minimum_hours_fraction, minimum_hours / 4380.0) << level.name;
    EXPECT_GT(target_hours, 0) << level.name;
    EXPECT_LT(target_hours, 4380) << level.name;
  }
  std::printf("[synthetic year] %s\n", m.to_string().c_str());
}
