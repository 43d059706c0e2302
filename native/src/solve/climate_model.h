#pragma once
// The climate goals' hourly flip model as the genetic search asks it (docs/solver.md, "Climate
// goals"): held in shards of the goal sensors where their records are (ClimateShard: in this
// process, or on a cluster's workers), asked in batches of states and answered in tallies added
// over the shards. No hourly row leaves its shard.
#include <memory>
#include <vector>

#include "solve/climate_objective.h"
#include "solve/climate_shard.h"
#include "solve/climate_tally.h"

namespace fenestra {

class ClimateModel {
 public:
  virtual ~ClimateModel() = default;
  // ClimateShard::settle and ::flip_tallies on every shard, each state's tallies added.
  virtual std::vector<ClimateTally> settle(const std::vector<ClimateRecipe>& batch) = 0;
  virtual std::vector<ClimateTally> flip_tallies(int slot, const std::vector<int>& elements) = 0;
  // Bytes of the model over all its shards (their slots' years aside).
  virtual double model_bytes() const = 0;
};

// Shards held in this process (one for a single process's records, or one per block of sensors).
class LocalClimateModel : public ClimateModel {
 public:
  LocalClimateModel(const ClimateObjective& objective, std::vector<std::unique_ptr<ClimateShard>> shards);
  std::vector<ClimateTally> settle(const std::vector<ClimateRecipe>& batch) override;
  std::vector<ClimateTally> flip_tallies(int slot, const std::vector<int>& elements) override;
  double model_bytes() const override;

 private:
  const ClimateObjective& objective_;
  std::vector<std::unique_ptr<ClimateShard>> shards_;
};

// Per state, the shards' tallies added (parts[shard][state]); std::invalid_argument when a shard
// answered for another number of states.
std::vector<ClimateTally> added_tallies(const ClimateObjective& objective,
                                        const std::vector<std::vector<ClimateTally>>& parts, size_t states);

}  // namespace fenestra
