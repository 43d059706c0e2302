#pragma once
// The genetic algorithm on climate goals: each individual carries its goal sensors' hourly
// illuminance, and a flip adds or takes away that element's hourly change (HourlyFlipModel), so
// a child costs a few vector additions and one pass over its year, not a simulation.
#include <cstdint>
#include <vector>

#include "annual/hourly_flip_model.h"
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

// Same settings and seed, same result, whatever the thread count (genetic.h).
GeneticResult run_climate_genetic(const HourlyFlipModel& model, const ClimateObjective& objective,
                                  const ElementGrid& grid, const std::vector<std::vector<uint8_t>>& seeds,
                                  const GeneticSettings& settings, Progress* progress = nullptr);

}  // namespace fenestra
