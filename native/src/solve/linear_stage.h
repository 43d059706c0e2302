#pragma once
// Stages 1 and 2 of the solver on per-sensor goals (docs/solver.md, steps 1 to 4): the linear start
// (NNLS, rounded), starts from coarser grids, the genetic algorithm, successive linearisation about
// its best state, and the exact choice among the best states. Each stage is listed in the result's
// `stages` with its seconds and why it stopped.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "scene/scene.h"
#include "solve/element_grid.h"
#include "solve/exact_values.h"
#include "solve/genetic.h"
#include "solve/solve_result.h"

namespace fenestra {

class Progress;
class RecordQueries;  // solve/record_queries.h

// What the element stages hand the constraints stage: the answer in elements, its exact values and
// fitness, and the start the second search within the constraints begins from.
struct ElementStage {
  std::vector<uint8_t> open, start_open;
  Eigen::VectorXd start_continuous;  // the linear start before rounding (empty on climate goals)
  // The best states the element search evaluated exactly, best first (the search over whole
  // openings starts from some of them).
  std::vector<std::vector<uint8_t>> candidates;
  SensorValues values;
  double fitness = std::numeric_limits<double>::infinity();
};

// The stages "linear start", "coarse grids", "genetic", "successive linearisation" and "exact
// evaluation". Fills `out`'s element answer, errors before the constraints, history, timings and
// stages. `ga.shape` scores the shape.
ElementStage linear_element_stages(const Scene& scene, const LinearObjective& objective, const ElementGrid& grid,
                                   const GeneticSettings& ga, RecordQueries& records, SolveResult& out,
                                   Progress* progress);

// A set of open elements with its exact values and fitness.
struct ElementChoice {
  std::vector<uint8_t> open;
  SensorValues values;
  double fitness = std::numeric_limits<double>::infinity();
};

// The element search again with the elements flagged in `excluded` kept closed: a genetic run
// (half the generations) on the exact linear model about the free answer less those elements,
// seeded with it and with the linear start without them; the exact evaluation picks among its best.
ElementChoice search_within_bounds(const LinearObjective& objective, const ElementGrid& grid, const GeneticSettings& ga,
                                   RecordQueries& records, const std::vector<uint8_t>& linear_start_open,
                                   const std::vector<uint8_t>& free_open, const std::vector<uint8_t>& excluded,
                                   Progress* progress);

}  // namespace fenestra
