#pragma once
// What the climate goals make of a year of hourly illuminance: each goal's figure (sDA, ASE,
// EN 17037, UDI, annual mean) exactly as the annual metrics define it, a smooth surrogate of it
// for the search, and the error the genetic algorithm minimises (docs/solver.md, "Climate goals").
#include <Eigen/Core>
#include <string>
#include <vector>

#include "annual/hourly_flip_model.h"
#include "scene/climate_goals.h"
#include "solve/climate_tally.h"
#include "solve/goals.h"

namespace fenestra {

struct ClimateFigure {
  double achieved = 0.0;  // the goal's figure, exact (area fraction, hours fraction or lux)
  double smooth = 0.0;    // its surrogate: sensor and hour steps replaced by ramps
};

// Per goal: the figure met (within 1e-9)?
bool figure_meets(const ClimateGoal& goal, double achieved);

struct ClimateObjectiveSettings {
  // Least glazing: the error gains this times the open fraction of the domain. A point of sDA
  // (0.01 of the sensors) costs 0.02 in the error, so meeting the goals always outweighs glass.
  double glazing_weight = 0.0;
  double bound_weight = 10.0;  // as LinearObjective's
  bool horizontal_openings = false;  // EN 17037: rooflights alone (the 95 % criterion)
  // The search aims this far past each fraction goal (sDA, ASE, UDI, EN 17037), so that the
  // openings made within the constraints from its answer, and the real cutters, keep meeting it.
  double margin = 0.02;
};

class ClimateObjective {
 public:
  // `rows`: the model's sensors (scene indices); `linear`: the per-sensor goals (lux on the mean of
  // the occupied hours; weight 0 where none) or null; `element_area`: m^2 per element.
  ClimateObjective(const ClimateGoals& goals, const HourlyColumns& columns, const std::vector<int>& rows,
                   const SolverGoals* linear, std::vector<double> element_area, ClimateObjectiveSettings settings);

  bool needs_direct() const { return needs_direct_; }
  const ClimateGoals& goals() const { return goals_; }

  // The tally of some model rows (climate_tally.h): row i of `total` and `direct` (rows x columns of
  // lux; direct may be empty without an ASE goal) is model row model_rows[i], or row i without
  // `model_rows`. std::invalid_argument when a row is outside the model.
  ClimateTally tally(const HourlyMatrix& total, const HourlyMatrix& direct,
                     const std::vector<int>* model_rows = nullptr) const;
  // The tally of no rows, to add the parts' tallies to.
  ClimateTally empty_tally() const;
  // Model row r's share of a tally, from its hours (`total`, and `direct` or null without an ASE
  // goal: the model's columns each): added to `t`, or with `remove` taken out of it.
  void tally_row(ClimateTally* t, const float* total, const float* direct, int r, bool remove) const;
  // The figures and the error of a whole model's tally (its parts' tallies added).
  std::vector<ClimateFigure> figures(const ClimateTally& tally) const;
  // The error: goals' shortfalls (hard and smooth; a mean goal's relative squared error), the
  // per-sensor goals' relative squared error, and the glazing term for `open_area` m^2.
  double error(const ClimateTally& tally, double open_area) const;
  // The same from all the model's rows at once.
  std::vector<ClimateFigure> figures(const HourlyMatrix& total, const HourlyMatrix& direct) const {
    return figures(tally(total, direct));
  }
  double error(const HourlyMatrix& total, const HourlyMatrix& direct, double open_area) const {
    return error(tally(total, direct), open_area);
  }
  double element_area(int k) const { return element_area_[static_cast<size_t>(k)]; }

 private:
  struct GoalRows {
    std::vector<int> rows;        // model rows of the goal's sensors
    std::vector<uint8_t> member;  // per model row: in the goal
  };
  double shortfall(const ClimateGoal& goal, const ClimateFigure& f) const;

  ClimateGoals goals_;
  HourlyColumns columns_;
  std::vector<GoalRows> goal_rows_;
  int model_rows_ = 0;
  bool needs_occupied_sum_ = false;  // a mean goal or per-sensor goals
  int occupied_columns_ = 0;  // the first columns
  std::vector<int> daylight_columns_;
  // Per-sensor goals, per model row: target lux, weight / sum(w g^2), bounds; empty without any.
  Eigen::VectorXd target_, weight_, lower_, upper_;
  std::vector<double> element_area_;
  double domain_area_ = 0.0;
  ClimateObjectiveSettings settings_;
  bool needs_direct_ = false;
};

// EN 17037's area fractions for the target illuminance: 50 % for vertical or inclined openings,
// 95 % for horizontal ones (rooflights alone); the minimum target always over 95 %.
inline constexpr double kEnTargetAreaVertical = 0.5, kEnTargetAreaHorizontal = 0.95, kEnMinimumArea = 0.95;

}  // namespace fenestra
