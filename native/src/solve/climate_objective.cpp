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
  model_rows_ = static_cast<int>(rows.size());
  for (const ClimateGoal& g : goals_.goals) {
    GoalRows gr;
    gr.member.assign(rows.size(), 0);
    for (int s : g.sensors) gr.rows.push_back(row_of(s)), gr.member[gr.rows.back()] = 1;
    goal_rows_.push_back(std::move(gr));
    needs_direct_ = needs_direct_ || g.metric == ClimateMetric::SunlightExposure;
    needs_occupied_sum_ = needs_occupied_sum_ || g.metric == ClimateMetric::MeanIlluminance;
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
    needs_occupied_sum_ = true;
  }
  domain_area_ = std::accumulate(element_area_.begin(), element_area_.end(), 0.0);
}

ClimateTally ClimateObjective::empty_tally() const {
  ClimateTally t;
  const size_t goals = goals_.goals.size();
  t.hours.resize(goals), t.above_target.resize(goals), t.above_minimum.resize(goals);
  for (size_t g = 0; g < goals; ++g) switch (goals_.goals[g].metric) {
      case ClimateMetric::SpatialDaylightAutonomy:
      case ClimateMetric::SunlightExposure:
      case ClimateMetric::UsefulDaylight: t.hours[g].assign(static_cast<size_t>(model_rows_), 0); break;
      case ClimateMetric::En17037:
        t.above_target[g].assign(daylight_columns_.size(), 0);
        t.above_minimum[g].assign(daylight_columns_.size(), 0);
        break;
      case ClimateMetric::MeanIlluminance: break;
    }
  if (needs_occupied_sum_) t.occupied_sum.assign(static_cast<size_t>(model_rows_), 0.0);
  return t;
}

ClimateTally ClimateObjective::tally(const HourlyMatrix& total, const HourlyMatrix& direct,
                                     const std::vector<int>* model_rows) const {
  if (model_rows && static_cast<Eigen::Index>(model_rows->size()) != total.rows())
    throw std::invalid_argument("climate tally: " + std::to_string(total.rows()) + " rows of hours, " +
                                std::to_string(model_rows->size()) + " model rows named");
  ClimateTally t = empty_tally();
  for (Eigen::Index i = 0; i < total.rows(); ++i) {
    const int r = model_rows ? (*model_rows)[static_cast<size_t>(i)] : static_cast<int>(i);
    if (r < 0 || r >= model_rows_)
      throw std::invalid_argument("climate tally: model row " + std::to_string(r) + " outside the model's " +
                                  std::to_string(model_rows_));
    tally_row(&t, total.row(i).data(), direct.size() ? direct.row(i).data() : nullptr, r, false);
  }
  return t;
}

void ClimateObjective::tally_row(ClimateTally* t, const float* total, const float* direct, int r, bool remove) const {
  const int m = occupied_columns_;
  const Eigen::Map<const Eigen::ArrayXf> year(total, m);
  if (needs_occupied_sum_) t->occupied_sum[r] = remove ? 0.0 : year.cast<double>().sum();
  for (size_t g = 0; g < goals_.goals.size(); ++g) {
    if (!goal_rows_[g].member[r]) continue;
    const ClimateGoal& goal = goals_.goals[g];
    switch (goal.metric) {
      case ClimateMetric::SpatialDaylightAutonomy:
        t->hours[g][r] = remove ? 0 : static_cast<int32_t>((year >= static_cast<float>(goal.illuminance_lux)).count());
        break;
      case ClimateMetric::SunlightExposure:
        t->hours[g][r] = remove || !direct ? 0
                                           : static_cast<int32_t>((Eigen::Map<const Eigen::ArrayXf>(direct, m) >
                                                                   static_cast<float>(goal.illuminance_lux)).count());
        break;
      case ClimateMetric::UsefulDaylight: {
        const float lo = static_cast<float>(goal.lower_lux), hi = static_cast<float>(goal.upper_lux);
        t->hours[g][r] = remove ? 0 : static_cast<int32_t>(((year >= lo) && (year <= hi)).count());
        break;
      }
      case ClimateMetric::En17037: {
        const En17037Illuminances e = en17037_illuminances(goal.level);
        const int32_t step = remove ? -1 : 1;
        for (size_t j = 0; j < daylight_columns_.size(); ++j) {
          const float lux = total[daylight_columns_[j]];
          t->above_target[g][j] += step * (lux >= e.target_lux);
          t->above_minimum[g][j] += step * (lux >= e.minimum_target_lux);
        }
        break;
      }
      case ClimateMetric::MeanIlluminance: break;
    }
  }
}

std::vector<ClimateFigure> ClimateObjective::figures(const ClimateTally& t) const {
  std::vector<ClimateFigure> out;
  const double occupied = std::max(1, columns_.occupied_hours);
  const int dark_occupied = columns_.occupied_hours - occupied_columns_;
  for (size_t g = 0; g < goals_.goals.size(); ++g) {
    const ClimateGoal& goal = goals_.goals[g];
    const std::vector<int>& rows = goal_rows_[g].rows;
    const double n = static_cast<double>(rows.size());
    ClimateFigure f;
    switch (goal.metric) {
      case ClimateMetric::SpatialDaylightAutonomy:
        for (int r : rows) {
          const double da = t.hours[g][r] / occupied;
          f.achieved += da >= goal.time_fraction;
          f.smooth += ramp(da - goal.time_fraction, kDaRamp);
        }
        f.achieved /= n, f.smooth /= n;
        break;
      case ClimateMetric::SunlightExposure:
        for (int r : rows) {
          const int hours = t.hours[g][r];
          f.achieved += hours > goal.hours;
          f.smooth += ramp(hours - goal.hours, kAseRampHours);
        }
        f.achieved /= n, f.smooth /= n;
        break;
      case ClimateMetric::UsefulDaylight: {
        double in_band = goal.lower_lux <= 0.0 ? n * dark_occupied : 0.0;
        for (int r : rows) in_band += static_cast<double>(t.hours[g][r]);
        f.achieved = f.smooth = in_band / (n * occupied);
        break;
      }
      case ClimateMetric::En17037: {
        const double target_area = settings_.horizontal_openings ? kEnTargetAreaHorizontal : kEnTargetAreaVertical;
        double target_hours = 0.0, minimum_hours = 0.0, target_smooth = 0.0, minimum_smooth = 0.0;
        for (size_t j = 0; j < daylight_columns_.size(); ++j) {
          const int above_target = t.above_target[g][j], above_minimum = t.above_minimum[g][j];
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
      case ClimateMetric::MeanIlluminance: {
        double sum = 0.0;
        for (int r : rows) sum += t.occupied_sum[r];
        f.achieved = f.smooth = sum / (n * std::max(1, columns_.occupied_hours));
        break;
      }
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

double ClimateObjective::error(const ClimateTally& t, double open_area) const {
  const std::vector<ClimateFigure> f = figures(t);
  double error = 0.0;
  for (size_t g = 0; g < goals_.goals.size(); ++g) error += goals_.goals[g].weight * shortfall(goals_.goals[g], f[g]);
  if (target_.size()) {
    const double hours = static_cast<double>(std::max(1, columns_.occupied_hours));
    for (Eigen::Index r = 0; r < target_.size(); ++r) {
      if (!(weight_[r] > 0.0)) continue;
      const double mean_r = t.occupied_sum[static_cast<size_t>(r)] / hours;
      const double d = mean_r - target_[r];
      const double bounds = excess(lower_[r] - mean_r) * excess(lower_[r] - mean_r) +
                            excess(mean_r - upper_[r]) * excess(mean_r - upper_[r]);
      error += weight_[r] * (d * d + settings_.bound_weight * bounds);
    }
  }
  if (settings_.glazing_weight > 0.0 && domain_area_ > 0.0)
    error += settings_.glazing_weight * open_area / domain_area_;
  return error;
}

}  // namespace fenestra
