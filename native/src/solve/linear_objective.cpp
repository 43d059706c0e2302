#include "solve/linear_objective.h"

#include <algorithm>
#include <limits>

#include "solve/genetic_search.h"
#include "solve/record_queries.h"

namespace fenestra {

LinearObjective linear_objective(const Contributions& c, const SolverGoals& goals, double bound_weight) {
  LinearObjective o;
  o.E = c.E;
  const Eigen::Index n = c.E.rows();
  double norm = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (goals.weight[i] > 0.0) norm += goals.weight[i] * goals.target[i] * goals.target[i];
  if (!(norm > 0.0)) norm = goals.weight.sum() * std::max(1e-30, c.all_open.value.squaredNorm() / n);  // all goals 0
  o.target = Eigen::VectorXd::Zero(n);
  o.weight = Eigen::VectorXd::Zero(n);
  o.lower = Eigen::VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
  o.upper = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(goals.weight[i] > 0.0)) continue;
    o.target[i] = goals.target[i] - c.closed.value[i];
    o.weight[i] = goals.weight[i] / norm;
    o.lower[i] = goals.lower[i] - c.closed.value[i];
    o.upper[i] = goals.upper[i] - c.closed.value[i];
  }
  o.bound_weight = bound_weight;
  return o;
}

LinearObjective linearised_objective(const LinearObjective& objective, RecordQueries& records,
                                     const std::vector<uint8_t>& about, const Eigen::VectorXd& about_values) {
  const Contributions& c = records.contributions();
  const Eigen::MatrixXd D = records.flip_effects(about);
  LinearObjective local = objective;
  Eigen::VectorXd base = about_values;
  for (size_t k = 0; k < about.size(); ++k) {
    if (about[k]) {
      base += D.col(k);
      local.E.col(k) = -D.col(k);
    } else {
      local.E.col(k) = D.col(k);
    }
  }
  const Eigen::VectorXd shift = base - c.closed.value;  // the objective's targets are net of the closed values
  for (Eigen::Index i = 0; i < shift.size(); ++i)
    if (local.weight[i] > 0.0) {
      local.target[i] -= shift[i];
      local.lower[i] -= shift[i];
      local.upper[i] -= shift[i];
    }
  return local;
}

LinearObjective without_elements(LinearObjective o, const std::vector<uint8_t>& excluded) {
  for (size_t k = 0; k < excluded.size(); ++k)
    if (excluded[k]) o.E.col(static_cast<Eigen::Index>(k)).setZero();
  return o;
}

std::vector<uint8_t> without_elements(std::vector<uint8_t> open, const std::vector<uint8_t>& excluded) {
  for (size_t k = 0; k < open.size(); ++k)
    if (excluded[k]) open[k] = 0;
  return open;
}

bool opens_any(const std::vector<uint8_t>& open, const std::vector<uint8_t>& flagged) {
  for (size_t k = 0; k < open.size(); ++k)
    if (open[k] && flagged[k]) return true;
  return false;
}

double exact_fitness(const LinearObjective& o, const ElementGrid& grid, const ShapeWeights& shape,
                     const std::vector<uint8_t>& open, const Eigen::VectorXd& predicted_net) {
  return prediction_error(o, predicted_net) + shape_penalty(shape, shape_counts(grid, open));
}

double exact_fitness_lower_bound(const LinearObjective& o, const ElementGrid& grid, const ShapeWeights& shape,
                                 const std::vector<uint8_t>& open, const Eigen::VectorXd& predicted_net,
                                 const Eigen::VectorXd& half_width) {
  double error = 0.0;
  for (Eigen::Index i = 0; i < predicted_net.size(); ++i) {
    const double low = predicted_net[i] - half_width[i], high = predicted_net[i] + half_width[i];
    const double r = std::max(0.0, std::max(low - o.target[i], o.target[i] - high));  // the nearest to the target
    double bounds = 0.0;  // each excess is least at the end of the interval nearer its bound
    if (o.lower.size()) bounds += genetic_search::squared_excess(o.lower[i] - high);
    if (o.upper.size()) bounds += genetic_search::squared_excess(low - o.upper[i]);
    error += o.weight[i] * (r * r + o.bound_weight * bounds);
  }
  return error + shape_penalty(shape, shape_counts(grid, open));
}

}  // namespace fenestra
