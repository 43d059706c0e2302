#pragma once
// One shard of the climate goals' hourly model (docs/solver.md, "Climate goals"): the hourly flip
// model of some goal sensors about a state, and the years of the genetic search's individuals in
// numbered slots. It answers in tallies of its sensors (climate_tally.h), never in hourly rows: a
// floor's search on a cluster holds each sensor's hours only in the shard that traced it.
#include <cstdint>
#include <vector>

#include "annual/hourly_flip_model.h"
#include "solve/climate_objective.h"
#include "solve/climate_tally.h"

namespace fenestra {

// A state to settle: slot `slot` takes the year of `open`, derived from the year in slot `base`
// (kModelState: the model's own state; `slot` itself: changed in place).
struct ClimateRecipe {
  static constexpr int kModelState = -1;
  int slot = 0;
  int base = kModelState;
  std::vector<uint8_t> open;
};

class ClimateShard {
 public:
  // `part`: the model at this shard's goal sensors; `model_rows`: each of its rows' row in the
  // whole model; `objective`: the whole model's (it outlives the shard).
  ClimateShard(HourlyFlipModel part, std::vector<int> model_rows, const ClimateObjective& objective);

  // Settles the recipes in order (one may derive from a slot settled before it in the batch) and
  // returns each state's tally of this shard's sensors. std::invalid_argument for a base never
  // settled, a negative slot, a state of another size, or a slot written twice in one batch.
  std::vector<ClimateTally> settle(const std::vector<ClimateRecipe>& batch);
  // The tallies of the state in `slot` with each of `elements` flipped alone (the slot unchanged).
  std::vector<ClimateTally> flip_tallies(int slot, const std::vector<int>& elements) const;
  size_t memory_bytes() const;  // the model and the slots' years
  size_t model_bytes() const { return model_.memory_bytes(); }
  const std::vector<int>& model_rows() const { return model_rows_; }

 private:
  struct Year {
    std::vector<uint8_t> open;
    HourlyMatrix total, direct;  // direct: empty unless an ASE goal needs it
  };
  const Year& settled(int slot) const;
  void flip(Year* year, int k) const;  // element k flips from year->open
  void change_to(Year* year, const std::vector<uint8_t>& open) const;
  ClimateTally tally(const Year& year) const { return objective_.tally(year.total, year.direct, &model_rows_); }

  HourlyFlipModel model_;
  std::vector<int> model_rows_;
  const ClimateObjective& objective_;
  std::vector<Year> slots_;
  std::vector<uint8_t> settled_;  // per slot
};

}  // namespace fenestra
