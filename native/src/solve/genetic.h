#pragma once
// Stage 2 of the solver: a genetic algorithm over 0/1 opening states, scored by the linear model
// predicted = E o (targets already net of the all-closed values), bound penalties and shape
// coherence. Children are scored incrementally from their parents (a bit flip is O(sensors)).
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solve/element_grid.h"

namespace fenestra {

// The error part of the fitness: sum_i weight_i (p_i - target_i)^2
//   + bound_weight * sum_i weight_i (max(0, lower_i - p_i)^2 + max(0, p_i - upper_i)^2),
// with p = E o. Sensors without a goal have weight 0 (and infinite bounds).
struct LinearObjective {
  Eigen::MatrixXd E;       // sensors x elements
  Eigen::VectorXd target;  // sensors
  Eigen::VectorXd weight;  // sensors, >= 0
  Eigen::VectorXd lower, upper;  // sensors; -inf / +inf where unbounded
  double bound_weight = 10.0;
};

// Shape coherence, added to the error: per open element with no open N-8 neighbour, per edge
// between an open and a closed (or missing) element, per connected open region.
struct ShapeWeights {
  double isolated = 1e-3;
  double boundary = 1e-4;
  double regions = 1e-3;
};

struct GeneticSettings {
  int population = 64;
  int generations = 500;
  uint64_t seed = 1;
  double time_budget_s = 0.0;  // 0: none; otherwise stop after this many seconds (whole generations)
  int elite = 8;               // best distinct states returned for the final (exact) choice
  ShapeWeights shape;
};

struct GenerationRecord {
  int generation = 0;
  double best = 0.0, mean = 0.0;  // fitness
  double seconds = 0.0;           // since the start
};

struct GeneticResult {
  std::vector<uint8_t> best;
  double best_fitness = 0.0;
  std::vector<std::vector<uint8_t>> elite;  // best first, distinct, includes `best`
  std::vector<GenerationRecord> history;    // one per generation, best fitness non-increasing
  int generations = 0;                      // run (fewer than asked when the budget ran out)
};

// The full fitness of one state (reference implementation; the GA scores incrementally).
double fitness(const LinearObjective& objective, const ElementGrid& grid, const ShapeWeights& shape,
               const std::vector<uint8_t>& open);

// `seeds`: starting states (at least one); the rest of the first population are their mutations.
// Same settings and seed, same result, whatever the thread count.
GeneticResult run_genetic(const LinearObjective& objective, const ElementGrid& grid,
                          const std::vector<std::vector<uint8_t>>& seeds, const GeneticSettings& settings);

}  // namespace fenestra
