#pragma once
// The scene's goals turned into what the solver works with: per-sensor targets and bounds in the
// sensors' own units (lux for a sky in cd/m^2), and weights (0: no goal, the sensor is ignored).
#include <Eigen/Dense>

#include "scene/scene.h"
#include "trace/contributions.h"

namespace fenestra {

struct SolverGoals {
  Eigen::VectorXd target;        // NaN where a sensor has no goal
  Eigen::VectorXd weight;        // 0 where a sensor has no goal
  Eigen::VectorXd lower, upper;  // -inf / +inf where unbounded
  Eigen::VectorXd given;         // the goal as written (goal units), NaN where none
  int count() const;             // sensors with a goal
};

// The goals as the scene writes them, per sensor, before any tracing (goal units): a uniform goal
// overrides the per-sensor goal of its sensors; NaN level and weight 0 where a sensor has none.
struct GivenGoals {
  Eigen::VectorXd level, lower, upper;  // lower / upper: -inf / +inf where unbounded
  Eigen::VectorXd weight;
  int count() const;                    // sensors with a goal
};
GivenGoals given_goals(const Scene& scene);

// Throws std::invalid_argument (naming the scene) when no sensor has a goal and there is no climate
// goal: a solve would trace for nothing. Checked before any tracing.
void require_goals(const Scene& scene);

// Normalized goals scale each sensor's all-open value; daylight factors the sky's unobstructed
// horizontal illuminance. A uniform goal overrides the per-sensor goal of its sensors. Throws
// std::invalid_argument (naming the scene) when no sensor has a goal.
SolverGoals resolve_goals(const Scene& scene, const Contributions& contributions);

// Relative RMS error of `predicted` against the goals, sqrt(sum w (p - g)^2 / sum w g^2), and the
// largest relative error of one sensor, |p - g| / g (sensors with g > 0).
struct GoalError {
  double relative_rms = 0.0;
  double max_relative = 0.0;
  int worst_sensor = -1;
};
GoalError goal_error(const SolverGoals& goals, const Eigen::VectorXd& predicted);
// The Monte Carlo noise of that relative RMS error: the values' standard errors in its place,
// sqrt(sum w se^2 / sum w goal^2) over the sensors with a goal.
double goal_noise(const SolverGoals& goals, const Eigen::VectorXd& standard_error);

}  // namespace fenestra
