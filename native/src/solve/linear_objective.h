#pragma once
// The linear objective of per-sensor goals (the genetic algorithm's LinearObjective): built from the
// contributions' linear model, or about a state from each element's exact flip effect (successive
// linearisation), and the fitness of a state from its exact values.
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solve/element_grid.h"
#include "solve/genetic.h"
#include "solve/goals.h"
#include "trace/contributions.h"

namespace fenestra {

class RecordQueries;  // solve/record_queries.h

// Rounds of successive linearisation about a best state (each stops early when it gains nothing).
constexpr int kLinearisationRounds = 4;

// The linear model net of the all-closed values, weighted so that its error is a relative
// mean-squared error (sum w (p - g)^2 / sum w g^2).
LinearObjective linear_objective(const Contributions& c, const SolverGoals& goals, double bound_weight);

// The objective with the model V(o) = V(S) + sum over the elements o flips from S of their exact
// flip effect D(., k): a constant base plus columns +D(., k) (k closed in S) or -D(., k) (k open).
LinearObjective linearised_objective(const LinearObjective& objective, RecordQueries& records,
                                     const std::vector<uint8_t>& about, const Eigen::VectorXd& about_values);

// The objective with no light from the elements flagged in `excluded` (their columns zeroed).
LinearObjective without_elements(LinearObjective o, const std::vector<uint8_t>& excluded);
// The state with the elements flagged in `excluded` closed.
std::vector<uint8_t> without_elements(std::vector<uint8_t> open, const std::vector<uint8_t>& excluded);
// Whether `open` opens any element flagged in `flagged`.
bool opens_any(const std::vector<uint8_t>& open, const std::vector<uint8_t>& flagged);

// Fitness with the error part taken from exact predictions (net of the all-closed values; the
// shape part as the genetic algorithm counts it).
double exact_fitness(const LinearObjective& o, const ElementGrid& grid, const ShapeWeights& shape,
                     const std::vector<uint8_t>& open, const Eigen::VectorXd& predicted_net);
// The least exact_fitness can be with each sensor's prediction anywhere within `half_width[i]` of
// `predicted_net[i]`: each sensor's terms at their least over its interval, summed (a bound from
// below, reached when all are at once).
double exact_fitness_lower_bound(const LinearObjective& o, const ElementGrid& grid, const ShapeWeights& shape,
                                 const std::vector<uint8_t>& open, const Eigen::VectorXd& predicted_net,
                                 const Eigen::VectorXd& half_width);

}  // namespace fenestra
