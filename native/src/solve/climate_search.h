#pragma once
// The genetic algorithm on climate goals: each individual's year of its goal sensors' hours is kept
// where the model's shards are (ClimateModel), derived from its parent's by the flips between
// them; the search sends each generation's states in one batch and scores them from the tallies
// that come back, so a child costs a few vector additions in the shards and no hourly row moves.
#include <cstdint>
#include <vector>

#include "annual/hourly_flip_model.h"
#include "solve/climate_model.h"
#include "solve/climate_objective.h"
#include "solve/element_grid.h"
#include "solve/genetic.h"

namespace fenestra {

class Progress;

// The hourly illuminance of `open` in the model: its base plus the changes of the elements where
// `open` differs from the model's state (exact where it differs in at most one element).
struct ClimateResponse {
  HourlyMatrix total, direct;  // rows x columns, lux (direct: empty unless an ASE goal needs it)
  double open_area = 0.0;         // m^2
};
ClimateResponse climate_response(const HourlyFlipModel& model, const ClimateObjective& objective,
                                 const std::vector<uint8_t>& open);
// The same after element j flips (`open` before it).
void flip_climate_response(const HourlyFlipModel& model, const ClimateObjective& objective,
                           const std::vector<uint8_t>& open, int j, ClimateResponse* response);

// Same settings and seed, same result, whatever the thread count and however the model is
// sharded (genetic.h; the tallies add exactly). The model's slots are the search's own: it uses
// 0 .. 2 * population.
GeneticResult run_climate_genetic(ClimateModel& model, const ClimateObjective& objective, const ElementGrid& grid,
                                  const std::vector<std::vector<uint8_t>>& seeds, const GeneticSettings& settings,
                                  Progress* progress = nullptr);

}  // namespace fenestra
