// Climate goals' figures from tallies: the tallies of sensors held in shards, added in any order,
// give the whole model's figures and error bit for bit, and a tally counts what the metrics define.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "solve/climate_objective.h"

namespace fenestra {
namespace {

// 30 occupied columns (the first 24 also daylight hours), then 10 daylight hours outside the
// occupied period; 40 occupied hours in the year (10 dark), 36 daylight hours.
HourlyColumns test_columns() {
  HourlyColumns c;
  for (int j = 0; j < 40; ++j) {
    c.hour.push_back(j);
    c.occupied.push_back(j < 30);
    c.daylight.push_back(j < 24 || j >= 30);
  }
  c.occupied_hours = 40;
  c.daylight_hours = 36;
  return c;
}

ClimateGoal goal(ClimateMetric metric, std::vector<int> sensors) {
  ClimateGoal g;
  g.metric = metric;
  g.sensors = std::move(sensors);
  return g;
}

// Three rooms of sensors (0-9, 10-24, 25-36) with goals per room and over all; per-sensor goals
// on some sensors.
struct Floor {
  static constexpr int kSensors = 37;
  HourlyColumns columns = test_columns();
  std::vector<int> rows;
  SolverGoals linear;
  std::unique_ptr<ClimateObjective> objective;

  Floor() {
    std::vector<int> room_a(10), room_b(15), room_c(12), all(kSensors);
    std::iota(room_a.begin(), room_a.end(), 0);
    std::iota(room_b.begin(), room_b.end(), 10);
    std::iota(room_c.begin(), room_c.end(), 25);
    std::iota(all.begin(), all.end(), 0);
    ClimateGoals goals;
    goals.goals = {goal(ClimateMetric::SpatialDaylightAutonomy, room_a), goal(ClimateMetric::SpatialDaylightAutonomy, room_b),
                   goal(ClimateMetric::SunlightExposure, all),          goal(ClimateMetric::UsefulDaylight, room_c),
                   goal(ClimateMetric::En17037, room_b),                goal(ClimateMetric::MeanIlluminance, room_c)};
    goals.goals[2].illuminance_lux = 1000.0, goals.goals[2].hours = 5.0;  // ASE1000,5 (of 30 occupied hours)
    goals.least_glazing = true;
    rows = all;
    linear.target = Eigen::VectorXd::Constant(kSensors, NAN);
    linear.weight = Eigen::VectorXd::Zero(kSensors);
    linear.lower = Eigen::VectorXd::Constant(kSensors, -INFINITY);
    linear.upper = Eigen::VectorXd::Constant(kSensors, INFINITY);
    for (int i : {3, 11, 30}) linear.target[i] = 500.0, linear.weight[i] = 1.0, linear.lower[i] = 300.0;
    ClimateObjectiveSettings settings;
    settings.glazing_weight = 0.05;
    objective = std::make_unique<ClimateObjective>(goals, columns, rows, &linear, std::vector<double>(8, 0.5), settings);
  }
};

// Lux spread over the thresholds (100, 300, 1000, 3000 lx), some sensors dark, direct sun on some.
void random_year(uint32_t seed, HourlyMatrix* total, HourlyMatrix* direct) {
  std::mt19937 rng(seed);
  std::lognormal_distribution<float> lux(5.8f, 1.3f);
  *total = HourlyMatrix(Floor::kSensors, 40);
  *direct = HourlyMatrix::Zero(Floor::kSensors, 40);
  for (int r = 0; r < Floor::kSensors; ++r)
    for (int j = 0; j < 40; ++j) {
      (*total)(r, j) = r % 9 == 4 ? 0.0f : lux(rng);
      if (r % 3 == 0 && rng() % 4 == 0) (*direct)(r, j) = 800.0f + static_cast<float>(rng() % 1000);
    }
}

HourlyMatrix rows_of(const HourlyMatrix& m, const std::vector<int>& rows) {
  HourlyMatrix out(static_cast<Eigen::Index>(rows.size()), m.cols());
  for (size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = m.row(rows[i]);
  return out;
}

void expect_same_figures(const std::vector<ClimateFigure>& a, const std::vector<ClimateFigure>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t g = 0; g < a.size(); ++g) {
    EXPECT_EQ(a[g].achieved, b[g].achieved) << what << ", goal " << g;
    EXPECT_EQ(a[g].smooth, b[g].smooth) << what << ", goal " << g;
  }
}

TEST(ClimateTally, ShardsOfTheSensorsGiveTheWholeModelsFiguresBitForBit) {
  Floor floor;
  for (uint32_t seed : {1u, 2u, 3u}) {
    HourlyMatrix total, direct;
    random_year(seed, &total, &direct);
    const std::vector<ClimateFigure> whole = floor.objective->figures(total, direct);
    const double whole_error = floor.objective->error(total, direct, 1.5);
    // Contiguous shards of 1 to 37 sensors, and shards of scattered sensors added in reverse.
    for (int shards : {1, 2, 3, 5, 37}) {
      std::vector<std::vector<int>> parts(static_cast<size_t>(shards));
      for (int r = 0; r < Floor::kSensors; ++r) parts[static_cast<size_t>(r * shards / Floor::kSensors)].push_back(r);
      std::vector<std::vector<int>> scattered(static_cast<size_t>(shards));
      for (int r = 0; r < Floor::kSensors; ++r) scattered[static_cast<size_t>((r * 7) % shards)].push_back(r);
      for (const auto* split : {&parts, &scattered}) {
        ClimateTally sum = floor.objective->empty_tally();
        for (auto it = split->rbegin(); it != split->rend(); ++it)
          sum.add(floor.objective->tally(rows_of(total, *it), rows_of(direct, *it), &*it));
        const std::string what = std::to_string(shards) + " shards, seed " + std::to_string(seed);
        expect_same_figures(floor.objective->figures(sum), whole, what);
        EXPECT_EQ(floor.objective->error(sum, 1.5), whole_error) << what;
      }
    }
  }
}

TEST(ClimateTally, CountsWhatTheMetricsDefine) {
  Floor floor;
  HourlyMatrix total, direct;
  random_year(4, &total, &direct);
  const std::vector<ClimateFigure> f = floor.objective->figures(total, direct);
  // sDA300/50 % of room A: sensors lit at 300 lx or more for half of the 40 occupied hours.
  int passing = 0;
  for (int r = 0; r < 10; ++r) {
    int hours = 0;
    for (int j = 0; j < 30; ++j) hours += total(r, j) >= 300.0f;
    passing += hours >= 20;
  }
  EXPECT_DOUBLE_EQ(f[0].achieved, passing / 10.0);
  EXPECT_GT(passing, 0);
  EXPECT_LT(passing, 10);
  // ASE1000,5 over all: sensors with more than 5 occupied hours of direct sun above 1000 lx.
  int exposed = 0;
  for (int r = 0; r < Floor::kSensors; ++r) {
    int hours = 0;
    for (int j = 0; j < 30; ++j) hours += direct(r, j) > 1000.0f;
    exposed += hours > 5;
  }
  EXPECT_DOUBLE_EQ(f[2].achieved, exposed / double(Floor::kSensors));
  EXPECT_GT(exposed, 0);
  // UDI 100-3000 lx of room C: hours within the band over its sensors' occupied hours (dark ones count out).
  int in_band = 0;
  for (int r = 25; r < 37; ++r)
    for (int j = 0; j < 30; ++j) in_band += total(r, j) >= 100.0f && total(r, j) <= 3000.0f;
  EXPECT_DOUBLE_EQ(f[3].achieved, in_band / (12.0 * 40.0));
  // EN 17037 minimum of room B: daylight hours with half its sensors at 300 lx and 95 % at 100 lx.
  int target_hours = 0, minimum_hours = 0;
  for (int j = 0; j < 40; ++j) {
    if (!(j < 24 || j >= 30)) continue;
    int above = 0, above_min = 0;
    for (int r = 10; r < 25; ++r) above += total(r, j) >= 300.0f, above_min += total(r, j) >= 100.0f;
    target_hours += above >= 7.5, minimum_hours += above_min >= 0.95 * 15;
  }
  EXPECT_DOUBLE_EQ(f[4].achieved, std::min(target_hours, minimum_hours) / 36.0);
  // Mean of room C over its occupied hours.
  double sum = 0.0;
  for (int r = 25; r < 37; ++r) sum += total.row(r).head(30).cast<double>().sum();
  EXPECT_NEAR(f[5].achieved, sum / (12 * 40), 1e-9 * sum);
}

TEST(ClimateTally, TalliesOfAnotherModelOrTwiceTheSameRowAreRefused) {
  Floor floor;
  HourlyMatrix total, direct;
  random_year(5, &total, &direct);
  const std::vector<int> first = {0, 1, 2};
  ClimateTally a = floor.objective->tally(rows_of(total, first), rows_of(direct, first), &first);
  EXPECT_THROW(a.add(floor.objective->tally(rows_of(total, first), rows_of(direct, first), &first)), std::invalid_argument);
  ClimateTally other = a;
  other.hours.pop_back();
  EXPECT_THROW(a.add(other), std::invalid_argument);
  const std::vector<int> outside = {37};
  EXPECT_THROW(floor.objective->tally(rows_of(total, {0}), rows_of(direct, {0}), &outside), std::invalid_argument);
  const std::vector<int> too_few = {0};
  EXPECT_THROW(floor.objective->tally(rows_of(total, first), rows_of(direct, first), &too_few), std::invalid_argument);
}

}  // namespace
}  // namespace fenestra
