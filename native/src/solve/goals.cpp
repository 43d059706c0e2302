#include "solve/goals.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "daylight/sky_figures.h"

namespace fenestra {

int SolverGoals::count() const { return static_cast<int>((weight.array() > 0.0).count()); }
int GivenGoals::count() const { return static_cast<int>((weight.array() > 0.0).count()); }

GivenGoals given_goals(const Scene& scene) {
  const Sensors& s = scene.sensors;
  const Eigen::Index n = static_cast<Eigen::Index>(s.size());
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  GivenGoals g;
  g.level = Eigen::VectorXd::Constant(n, nan);
  g.lower = Eigen::VectorXd::Constant(n, -inf);
  g.upper = Eigen::VectorXd::Constant(n, inf);
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(s.goals.size()); ++i) g.level[i] = s.goals[i];
  for (const UniformGoal& u : s.uniform_goals)
    for (int i : u.sensors) {
      g.level[i] = u.level;
      g.lower[i] = u.min;
      g.upper[i] = u.max;
    }
  g.weight.resize(n);
  for (Eigen::Index i = 0; i < n; ++i)
    g.weight[i] = std::isnan(g.level[i]) ? 0.0 : (s.weights.empty() ? 1.0 : s.weights[i]);
  return g;
}

void require_goals(const Scene& scene) {
  if (scene.sensors.climate_goals.empty() && given_goals(scene).count() == 0)
    throw std::invalid_argument("scene '" + scene.source +
                                "': no sensor has a goal (give sensors.goals, goals.uniform or goals.climate, and "
                                "weights above 0): a solve would have nothing to aim for");
}

SolverGoals resolve_goals(const Scene& scene, const Contributions& c) {
  const Sensors& s = scene.sensors;
  const Eigen::Index n = static_cast<Eigen::Index>(s.size());
  const GivenGoals given = given_goals(scene);
  SolverGoals g;
  g.given = given.level;

  // Goal units -> the sensors' units.
  const double horizontal = s.goal_units == "daylight_factor" ? unobstructed_horizontal_illuminance(*scene.sky, scene.suns, scene.daylight.get()) : 0.0;
  auto absolute = [&](Eigen::Index i, double v) {
    if (!std::isfinite(v)) return v;
    if (s.goal_units == "normalized") return v * c.all_open.value[i];
    if (s.goal_units == "daylight_factor") return v / 100.0 * horizontal;
    return v;
  };
  g.target.resize(n);
  g.lower.resize(n);
  g.upper.resize(n);
  g.weight = given.weight;
  for (Eigen::Index i = 0; i < n; ++i) {
    g.target[i] = absolute(i, g.given[i]);
    g.lower[i] = absolute(i, given.lower[i]);
    g.upper[i] = absolute(i, given.upper[i]);
  }
  require_goals(scene);
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
