#pragma once
// What the scene file's "goals" and "solver" sections say (docs/scene-format.md, docs/solver.md).
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "scene/opening_constraints.h"

namespace fenestra {

// One goal level for a set of sensors, optionally with bounds penalised outside (in the scene's
// goal units).
struct UniformGoal {
  std::vector<int> sensors;
  double level = 0.0;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};

struct SolverSettings {
  int paths_per_sensor = 0;   // 0: render.paths_per_sensor
  int population = 64;
  int generations = 500;
  uint64_t seed = 1;
  double time_budget_s = 0.0;  // genetic stage; 0: none
  double isolated_weight = 1e-4, boundary_weight = 1e-5, regions_weight = 1e-4;  // shape coherence
  double bound_weight = 10.0;  // penalty of a sensor outside its [min, max], relative to the error
  bool coarse_to_fine = true;
  int elite = 8;               // best genetic states re-ranked with the exact evaluation
  OpeningConstraints constraints;  // what an opening may be (docs/solver.md)
  int improve_iterations = 20000;  // local search over whole openings after the refinement; 0: none
  // Sets of openings the exact search over whole openings may score (solve/opening_search.h); 0: none.
  int search_evaluations = 3000;
  bool refine_edges = true;        // move openings' edges off the element grid (thick walls: by real cuts)
  bool verify = true;              // path-trace the final openings with real cutters (evaluate)
  int verify_paths = 0;            // paths per sensor of that check; 0: as many as the contributions'
  bool tradeoffs = true;           // also the best answers with fewer openings (solve/tradeoffs.h)
};

}  // namespace fenestra
