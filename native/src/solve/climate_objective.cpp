#include "solve/climate_objective.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace fenestra {
namespace {

// Ramp widths of the surrogates: a sensor's DA (fraction of occupied hours), a sensor's hours of
// direct sun, and the area fraction over EN 17037's target in one hour. Wide enough that a
// sensor well short of its threshold still pulls the search toward it.
constexpr double kDaRamp = 0.2, kAseRampHours = 100.0, kEnAreaRamp = 0.2;
constexpr double kMeetTolerance = 1e-9;

double ramp(double x, double width) { return std::clamp(0.5 + x / width, 0.0, 1.0); }
double excess(double x) { return x > 0.0 ? x : 0.0; }

}  // namespace

bool figure_meets(const ClimateGoal& goal, double achieved) {
  switch (goal.sense()) {
    case GoalSense::AtLeast: return achieved >= goal.required() - kMeetTolerance;
    case GoalSense::AtMost: return achieved <= goal.required() + kMeetTolerance;
    case GoalSense::Target: return std::abs(achieved - goal.required()) <= 0.05 * goal.required();
  }
  return false;
}

ClimateObjective::ClimateObjective(const ClimateGoals& goals, const HourlyColumns& columns,
                                   const std::vector<int>& rows, const SolverGoals* linear,
                                   std::vector<double> element_area, ClimateObjectiveSettings settings)
    : goals_(goals), columns_(columns), element_area_(std::move(element_area)), settings_(settings) {
  std::vector<int> row_of_sensor;
  for (size_t r = 0; r < rows.size(); ++r) {
    if (rows[r] >= static_cast<int>(row_of_sensor.size())) row_of_sensor.resize(rows[r] + 1, -1);
    row_of_sensor[rows[r]] = static_cast<int>(r);
  }
  auto row_of = [&](int sensor) {
    if (sensor < 0 || sensor >= static_cast<int>(row_of_sensor.size()) || row_of_sensor[sensor] < 0)
      throw std::invalid_argument("climate objective: sensor " + std::to_string(sensor) + " is not in the model");
    return row_of_sensor[sensor];
  };
  for (const ClimateGoal& g : goals_.goals) {
    GoalRows gr;
    for (int s : g.sensors) gr.rows.push_back(row_of(s));
    goal_rows_.push_back(std::move(gr));
    needs_direct_ = needs_direct_ || g.metric == ClimateMetric::SunlightExposure;
  }
  occupied_columns_ = columns_.occupied_columns();
  for (size_t c = 0; c < columns_.hour.size(); ++c)
    if (columns_.daylight[c]) daylight_columns_.push_back(static_cast<int>(c));
  if (linear && linear->count() > 0) {
    const Eigen::Index n = static_cast<Eigen::Index>(rows.size());
    target_ = Eigen::VectorXd::Zero(n), weight_ = Eigen::VectorXd::Zero(n);
    lower_ = Eigen::VectorXd::Constant(n, -INFINITY), upper_ = Eigen::VectorXd::Constant(n, INFINITY);
    double norm = 0.0;
    for (Eigen::Index i = 0; i < linear->weight.size(); ++i)
      if (linear->weight[i] > 0.0) norm += linear->weight[i] * linear->target[i] * linear->target[i];
    if (!(norm > 0.0)) norm = 1.0;
    for (Eigen::Index i = 0; i < linear->weight.size(); ++i) {
      if (!(linear->weight[i] > 0.0)) continue;
      const int r = row_of(static_cast<int>(i));
      target_[r] = linear->target[i], weight_[r] = linear->weight[i] / norm;
      lower_[r] = linear->lower[i], upper_[r] = linear->upper[i];
    }
  }
  domain_area_ = std::accumulate(element_area_.begin(), element_area_.end(), 0.0);
}

Eigen::VectorXd ClimateObjective::occupied_mean(const HourlyMatrix& total) const {
  Eigen::VectorXd mean(total.rows());
  for (Eigen::Index r = 0; r < total.rows(); ++r) mean[r] = total.row(r).head(occupied_columns_).cast<double>().sum();
  return mean / static_cast<double>(std::max(1, columns_.occupied_hours));
}

ClimateFigure ClimateObjective::mean_figure(const ClimateGoal&, const std::vector<int>& rows,
                                            const HourlyMatrix& total) const {
  ClimateFigure f;
  double sum = 0.0;
  for (int r : rows) sum += total.row(r).head(occupied_columns_).cast<double>().sum();
  f.achieved = f.smooth = sum / (static_cast<double>(rows.size()) * std::max(1, columns_.occupied_hours));
  return f;
}

std::vector<ClimateFigure> ClimateObjective::figures(const HourlyMatrix& total, const HourlyMatrix& direct) const {
  std::vector<ClimateFigure> out;
  const double occupied = std::max(1, columns_.occupied_hours);
  const int dark_occupied = columns_.occupied_hours - occupied_columns_;
  const int m = occupied_columns_;
  for (size_t g = 0; g < goals_.goals.size(); ++g) {
    const ClimateGoal& goal = goals_.goals[g];
    const std::vector<int>& rows = goal_rows_[g].rows;
    const double n = static_cast<double>(rows.size());
    ClimateFigure f;
    switch (goal.metric) {
      case ClimateMetric::SpatialDaylightAutonomy: {
        const float threshold = static_cast<float>(goal.illuminance_lux);
        for (int r : rows) {
          const int hours = static_cast<int>((total.row(r).head(m).array() >= threshold).count());
          const double da = hours / occupied;
          f.achieved += da >= goal.time_fraction;
          f.smooth += ramp(da - goal.time_fraction, kDaRamp);
        }
        f.achieved /= n, f.smooth /= n;
        break;
      }
      case ClimateMetric::SunlightExposure: {
        const float threshold = static_cast<float>(goal.illuminance_lux);
        for (int r : rows) {
          const int hours = direct.size() ? static_cast<int>((direct.row(r).head(m).array() > threshold).count()) : 0;
          f.achieved += hours > goal.hours;
          f.smooth += ramp(hours - goal.hours, kAseRampHours);
        }
        f.achieved /= n, f.smooth /= n;
        break;
      }
      case ClimateMetric::UsefulDaylight: {
        const float lo = static_cast<float>(goal.lower_lux), hi = static_cast<float>(goal.upper_lux);
        double in_band = goal.lower_lux <= 0.0 ? n * dark_occupied : 0.0;
        for (int r : rows) {
          const auto year = total.row(r).head(m).array();
          in_band += static_cast<double>(((year >= lo) && (year <= hi)).count());
        }
        f.achieved = f.smooth = in_band / (n * occupied);
        break;
      }
      case ClimateMetric::En17037: {
        const En17037Illuminances e = en17037_illuminances(goal.level);
        const double target_area = settings_.horizontal_openings ? kEnTargetAreaHorizontal : kEnTargetAreaVertical;
        double target_hours = 0.0, minimum_hours = 0.0, target_smooth = 0.0, minimum_smooth = 0.0;
        for (int c : daylight_columns_) {
          int above_target = 0, above_minimum = 0;
          for (int r : rows) {
            above_target += total(r, c) >= e.target_lux;
            above_minimum += total(r, c) >= e.minimum_target_lux;
          }
          target_hours += above_target / n >= target_area;
          minimum_hours += above_minimum / n >= kEnMinimumArea;
          target_smooth += ramp(above_target / n - target_area, kEnAreaRamp);
          minimum_smooth += ramp(above_minimum / n - kEnMinimumArea, kEnAreaRamp);
        }
        const double hours = std::max(1, columns_.daylight_hours);
        if (settings_.horizontal_openings) {
          f.achieved = target_hours / hours, f.smooth = target_smooth / hours;
        } else {
          f.achieved = std::min(target_hours, minimum_hours) / hours;
          f.smooth = std::min(target_smooth, minimum_smooth) / hours;
        }
        break;
      }
      case ClimateMetric::MeanIlluminance:
        f = mean_figure(goal, rows, total);
        break;
    }
    out.push_back(f);
  }
  return out;
}

double ClimateObjective::shortfall(const ClimateGoal& goal, const ClimateFigure& f) const {
  const double m = settings_.margin;
  switch (goal.sense()) {
    case GoalSense::AtLeast: {
      const double x = std::min(1.0, goal.required() + m);
      return excess(x - f.achieved) + excess(x - f.smooth);
    }
    case GoalSense::AtMost: {
      const double x = std::max(0.0, goal.required() - m);
      return excess(f.achieved - x) + excess(f.smooth - x);
    }
    case GoalSense::Target: {  // the relative squared error of the sensors' average
      const double d = (f.achieved - goal.required()) / goal.required();
      return d * d;
    }
  }
  return 0.0;
}

double ClimateObjective::error(const HourlyMatrix& total, const HourlyMatrix& direct, double open_area) const {
  const std::vector<ClimateFigure> f = figures(total, direct);
  double error = 0.0;
  for (size_t g = 0; g < goals_.goals.size(); ++g) error += goals_.goals[g].weight * shortfall(goals_.goals[g], f[g]);
  if (target_.size()) {
    const Eigen::VectorXd mean = occupied_mean(total);
    for (Eigen::Index r = 0; r < target_.size(); ++r) {
      if (!(weight_[r] > 0.0)) continue;
      const double d = mean[r] - target_[r];
      const double bounds = excess(lower_[r] - mean[r]) * excess(lower_[r] - mean[r]) +
                            excess(mean[r] - upper_[r]) * excess(mean[r] - upper_[r]);
      error += weight_[r] * (d * d + settings_.bound_weight * bounds);
    }
  }
  if (settings_.glazing_weight > 0.0 && domain_area_ > 0.0)
    error += settings_.glazing_weight * open_area / domain_area_;
  return error;
}

}  // namespace fenestra
