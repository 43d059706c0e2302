#include "solve/goals.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "io/sky_output.h"

namespace fenestra {

int SolverGoals::count() const { return static_cast<int>((weight.array() > 0.0).count()); }

SolverGoals resolve_goals(const Scene& scene, const Contributions& c) {
  const Sensors& s = scene.sensors;
  const Eigen::Index n = static_cast<Eigen::Index>(s.size());
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  SolverGoals g;
  g.given = Eigen::VectorXd::Constant(n, nan);
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(s.goals.size()); ++i) g.given[i] = s.goals[i];
  Eigen::VectorXd given_lower = Eigen::VectorXd::Constant(n, -inf), given_upper = Eigen::VectorXd::Constant(n, inf);
  for (const UniformGoal& u : s.uniform_goals)
    for (int i : u.sensors) {
      g.given[i] = u.level;
      given_lower[i] = u.min;
      given_upper[i] = u.max;
    }

  // Goal units -> the sensors' units.
  const double horizontal = s.goal_units == "daylight_factor" ? unobstructed_horizontal_illuminance(scene) : 0.0;
  auto absolute = [&](Eigen::Index i, double v) {
    if (!std::isfinite(v)) return v;
    if (s.goal_units == "normalized") return v * c.all_open.value[i];
    if (s.goal_units == "daylight_factor") return v / 100.0 * horizontal;
    return v;
  };
  g.target.resize(n);
  g.lower.resize(n);
  g.upper.resize(n);
  g.weight.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    g.target[i] = absolute(i, g.given[i]);
    g.lower[i] = absolute(i, given_lower[i]);
    g.upper[i] = absolute(i, given_upper[i]);
    const double w = s.weights.empty() ? 1.0 : s.weights[i];
    g.weight[i] = std::isnan(g.given[i]) ? 0.0 : w;
  }
  if (g.count() == 0 && scene.sensors.climate_goals.empty())
    throw std::invalid_argument("scene '" + scene.source +
                                "': no sensor has a goal (give sensors.goals or goals.uniform, and weights above 0)");
  return g;
}

double goal_noise(const SolverGoals& goals, const Eigen::VectorXd& standard_error) {
  double num = 0.0, den = 0.0;
  for (Eigen::Index i = 0; i < standard_error.size(); ++i) {
    if (!(goals.weight[i] > 0.0)) continue;
    num += goals.weight[i] * standard_error[i] * standard_error[i];
    den += goals.weight[i] * goals.target[i] * goals.target[i];
  }
  return den > 0.0 ? std::sqrt(num / den) : std::sqrt(num);
}

GoalError goal_error(const SolverGoals& goals, const Eigen::VectorXd& predicted) {
  GoalError e;
  double num = 0.0, den = 0.0;
  for (Eigen::Index i = 0; i < predicted.size(); ++i) {
    if (!(goals.weight[i] > 0.0)) continue;
    const double d = predicted[i] - goals.target[i];
    num += goals.weight[i] * d * d;
    den += goals.weight[i] * goals.target[i] * goals.target[i];
    if (goals.target[i] > 0.0 && std::abs(d) / goals.target[i] > e.max_relative) {
      e.max_relative = std::abs(d) / goals.target[i];
      e.worst_sensor = static_cast<int>(i);
    }
  }
  e.relative_rms = den > 0.0 ? std::sqrt(num / den) : std::sqrt(num);
  return e;
}

}  // namespace fenestra
