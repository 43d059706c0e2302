#pragma once
// Stage 2 of the solver: a genetic algorithm over 0/1 opening states, scored by the linear model
// predicted = E o (targets already net of the all-closed values), bound penalties and shape
// coherence. Children are scored incrementally from their parents (a bit flip is O(sensors)).
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solve/element_grid.h"

namespace fenestra {

class Progress;
struct SolverSettings;  // scene/solver_settings.h

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
// between an open and a closed (or missing) element, per connected open region. The defaults
// assume sensor weights that make the error a relative mean squared error (1e-4: 1% RMS): a lone
// element costs 2.4e-4 (itself, its region, 4 edges), as much as a 1.5% RMS error, and a
// one-element notch or bump (2 edges) 2e-5, i.e. 0.45% RMS. On fine grids (many more than ~20
// elements a side) scale `boundary` down with the element size, or the perimeter outweighs the fit.
struct ShapeWeights {
  double isolated = 1e-4;
  double boundary = 1e-5;
  double regions = 1e-4;
};

// What the shape weights multiply.
struct ShapeCounts {
  int isolated = 0;  // open elements with no open N-8 neighbour
  int boundary = 0;  // element edges between an open element and a closed or missing one
  int regions = 0;   // connected open regions (N-8 connectivity, within a panel)
};

struct GeneticSettings {
  int population = 64;
  int generations = 500;
  uint64_t seed = 1;
  double time_budget_s = 0.0;  // 0: none; otherwise stop after this many seconds (whole generations)
  int elite = 8;               // best distinct states returned for the final (exact) choice
  ShapeWeights shape;
  bool polish = true;          // finish with greedy one- and two-element flips on the best
};

// The scene's solver settings as the genetic algorithm takes them.
ShapeWeights shape_weights_from(const SolverSettings& settings);
GeneticSettings genetic_settings_from(const SolverSettings& settings);

struct GenerationRecord {
  int generation = 0;             // 0: the first one bred from the seeds
  double best = 0.0, mean = 0.0;  // fitness
  double seconds = 0.0;           // since the start
};

constexpr size_t kMaxHistory = 2048;  // records kept of a genetic run's history

struct GeneticResult {
  std::vector<uint8_t> best;
  double best_fitness = 0.0;
  std::vector<std::vector<uint8_t>> elite;  // best first, distinct, includes `best`
  // One per generation up to kMaxHistory generations, then evenly thinned (every 2nd, 4th, ...
  // generation, and the last); best fitness non-increasing.
  std::vector<GenerationRecord> history;
  int generations = 0;                      // run (fewer than asked when the budget ran out)
  bool out_of_time = false;                 // the time budget ended it before its last generation
};

// The error part of the fitness for predictions p (net of the all-closed values), however made.
double prediction_error(const LinearObjective& objective, const Eigen::VectorXd& p);
// The error part of the fitness of one state (p = E o computed in full).
double objective_error(const LinearObjective& objective, const std::vector<uint8_t>& open);
ShapeCounts shape_counts(const ElementGrid& grid, const std::vector<uint8_t>& open);
double shape_penalty(const ShapeWeights& shape, const ShapeCounts& counts);
// The full fitness of one state (reference implementation; the GA scores incrementally).
double fitness(const LinearObjective& objective, const ElementGrid& grid, const ShapeWeights& shape,
               const std::vector<uint8_t>& open);

// `seeds`: starting states (at least one, at most `population` are used); the rest of the first
// population are their mutations. `best_fitness` includes the final polish, so it may be below the
// history's last best. Same settings and seed, same result, whatever the thread count, except
// that a time budget stops after however many generations fit: a faster machine runs more.
// `progress` (optional) counts generations and is polled for cancellation between them.
GeneticResult run_genetic(const LinearObjective& objective, const ElementGrid& grid,
                          const std::vector<std::vector<uint8_t>>& seeds, const GeneticSettings& settings,
                          Progress* progress = nullptr);

}  // namespace fenestra
