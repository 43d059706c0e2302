#include "solve/genetic.h"

#include "scene/solver_settings.h"
#include "solve/genetic_search.h"

namespace fenestra {

using namespace genetic_search;

namespace {

using Eigen::VectorXd;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Validation (the only place that checks; the search trusts its input).

void check_objective(const LinearObjective& objective, int elements) {
  const Eigen::Index sensors = objective.E.rows();
  auto fail = [](const std::string& what) { throw std::invalid_argument("genetic objective: " + what); };
  if (objective.E.cols() != elements)
    fail("E has " + std::to_string(objective.E.cols()) + " columns for " + std::to_string(elements) + " elements");
  if (objective.target.size() != sensors || objective.weight.size() != sensors)
    fail("target and weight need one value per sensor (" + std::to_string(sensors) + ")");
  for (const VectorXd* bound : {&objective.lower, &objective.upper})
    if (bound->size() != 0 && bound->size() != sensors)
      fail("lower and upper need one value per sensor (" + std::to_string(sensors) + ") or none");
  if (!objective.E.allFinite() || !objective.target.allFinite()) fail("E and target must be finite");
  if (!objective.weight.allFinite() || (objective.weight.array() < 0.0).any())
    fail("weights must be finite and >= 0");
  if (objective.lower.hasNaN() || objective.upper.hasNaN()) fail("bounds must not be NaN");
  if (!std::isfinite(objective.bound_weight) || objective.bound_weight < 0.0) fail("bound_weight must be >= 0");
}

// ---------------------------------------------------------------------------------------------
// The error term in terms of the residual r = E o - target, so that a flip only adds or
// subtracts a column of E. The bounds are shifted by the target once.

class ResidualError {
 public:
  using Response = VectorXd;  // r = E o - target
  static constexpr bool kPairPolish = true;
  static constexpr bool kBatched = false;

  explicit ResidualError(const LinearObjective& objective)
      : E_(objective.E), target_(objective.target), weight_(objective.weight), bound_weight_(objective.bound_weight) {
    const Eigen::Index sensors = objective.E.rows();
    lower_ = objective.lower.size() ? VectorXd(objective.lower - objective.target) : VectorXd::Constant(sensors, -kInfinity);
    upper_ = objective.upper.size() ? VectorXd(objective.upper - objective.target) : VectorXd::Constant(sensors, kInfinity);
    bounded_ = bound_weight_ > 0.0 && ((lower_.array() > -kInfinity).any() || (upper_.array() < kInfinity).any());
    column_weight_ = (objective.E.array().square().colwise() * weight_.array()).colwise().sum().transpose();
  }

  VectorXd response(const State& open) const {
    VectorXd o(open.size());
    for (size_t k = 0; k < open.size(); ++k) o[k] = open[k];
    return E_ * o - target_;
  }
  void flip(VectorXd* r, const State& open, int j) const {
    if (open[j]) *r -= E_.col(j);
    else *r += E_.col(j);
  }
  double scale() const { return (*this)(-target_); }  // the error with every element closed

  double flip_change(const VectorXd& r, const State& open, int j) const { return flip_change(r, j, open[j] ? -1.0 : 1.0); }
  double pair_change(const VectorXd& r, const State& open, int j, int k) const {
    return pair_change(r, j, open[j] ? -1.0 : 1.0, k, open[k] ? -1.0 : 1.0);
  }

  double operator()(const VectorXd& r) const {
    double error = 0.0;
    for (Eigen::Index i = 0; i < r.size(); ++i) error += weight_[i] * (r[i] * r[i] + penalty(i, r[i]));
    return error;
  }

  // Change of the error when column j is added to r with `sign` (+1 opening, -1 closing).
  double flip_change(const VectorXd& r, int j, double sign) const {
    const auto column = E_.col(j);
    if (!bounded_) return 2.0 * sign * (weight_.array() * r.array() * column.array()).sum() + column_weight_[j];
    double change = 0.0;
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      const double after = r[i] + sign * column[i];
      change += weight_[i] * (after * after - r[i] * r[i] + penalty(i, after) - penalty(i, r[i]));
    }
    return change;
  }

  // The same for two columns at once.
  double pair_change(const VectorXd& r, int j, double sign_j, int k, double sign_k) const {
    const auto a = E_.col(j), b = E_.col(k);
    double change = 0.0;
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      const double after = r[i] + sign_j * a[i] + sign_k * b[i];
      change += weight_[i] * (after * after - r[i] * r[i] + penalty(i, after) - penalty(i, r[i]));
    }
    return change;
  }

 private:
  double penalty(Eigen::Index i, double r) const {
    if (!bounded_) return 0.0;
    return bound_weight_ * (squared_excess(lower_[i] - r) + squared_excess(r - upper_[i]));
  }

  const Eigen::MatrixXd& E_;
  const VectorXd& target_;
  const VectorXd& weight_;
  double bound_weight_;
  VectorXd lower_, upper_;
  VectorXd column_weight_;  // sum_i weight_i E_ij^2
  bool bounded_ = false;
};


}  // namespace

double prediction_error(const LinearObjective& objective, const VectorXd& p) {
  double error = 0.0;
  for (Eigen::Index i = 0; i < p.size(); ++i) {
    double bounds = 0.0;
    if (objective.lower.size()) bounds += squared_excess(objective.lower[i] - p[i]);
    if (objective.upper.size()) bounds += squared_excess(p[i] - objective.upper[i]);
    const double r = p[i] - objective.target[i];
    error += objective.weight[i] * (r * r + objective.bound_weight * bounds);
  }
  return error;
}

double objective_error(const LinearObjective& objective, const std::vector<uint8_t>& open) {
  check_objective(objective, static_cast<int>(objective.E.cols()));
  check_state(open, static_cast<int>(objective.E.cols()), "state");
  VectorXd o(open.size());
  for (size_t k = 0; k < open.size(); ++k) o[k] = open[k] != 0;
  return prediction_error(objective, objective.E * o);
}

ShapeCounts shape_counts(const ElementGrid& grid, const std::vector<uint8_t>& open) {
  check_state(open, grid.size(), "state");
  State binary(open.size());
  for (size_t k = 0; k < open.size(); ++k) binary[k] = open[k] != 0;
  ShapeCounts counts;
  for (int k = 0; k < grid.size(); ++k) {
    if (!binary[k]) continue;
    counts.isolated += isolated(grid, binary, k);
    counts.boundary += kEdgeSlots - open_edge_neighbours(grid, binary, k);
  }
  std::vector<int> labels;
  counts.regions = label_regions(grid, binary, &labels);
  return counts;
}

double shape_penalty(const ShapeWeights& shape, const ShapeCounts& counts) {
  return shape.isolated * counts.isolated + shape.boundary * counts.boundary + shape.regions * counts.regions;
}

double fitness(const LinearObjective& objective, const ElementGrid& grid, const ShapeWeights& shape,
               const std::vector<uint8_t>& open) {
  return objective_error(objective, open) + shape_penalty(shape, shape_counts(grid, open));
}

ShapeWeights shape_weights_from(const SolverSettings& s) {
  return {/*isolated=*/s.isolated_weight, /*boundary=*/s.boundary_weight, /*regions=*/s.regions_weight};
}

GeneticSettings genetic_settings_from(const SolverSettings& s) {
  // In GeneticSettings' order; `polish` keeps its default.
  return {/*population=*/s.population, /*generations=*/s.generations, /*seed=*/s.seed,
          /*time_budget_s=*/s.time_budget_s, /*elite=*/s.elite, /*shape=*/shape_weights_from(s)};
}

GeneticResult run_genetic(const LinearObjective& objective, const ElementGrid& grid,
                          const std::vector<std::vector<uint8_t>>& seeds, const GeneticSettings& settings,
                          Progress* progress) {
  if (grid.size() == 0) throw std::invalid_argument("genetic: the element grid is empty");
  check_objective(objective, grid.size());
  return run_search(ResidualError(objective), grid, seeds, settings, progress);
}

}  // namespace fenestra
