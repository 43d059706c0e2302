#include "solve/climate_model.h"

#include <stdexcept>
#include <string>

namespace fenestra {

std::vector<ClimateTally> added_tallies(const ClimateObjective& objective,
                                        const std::vector<std::vector<ClimateTally>>& parts, size_t states) {
  std::vector<ClimateTally> out(states, objective.empty_tally());
  for (size_t s = 0; s < parts.size(); ++s) {
    if (parts[s].size() != states)
      throw std::invalid_argument("climate model: shard " + std::to_string(s) + " answered for " +
                                  std::to_string(parts[s].size()) + " states, not " + std::to_string(states));
    for (size_t i = 0; i < states; ++i) out[i].add(parts[s][i]);
  }
  return out;
}

LocalClimateModel::LocalClimateModel(const ClimateObjective& objective, std::vector<std::unique_ptr<ClimateShard>> shards)
    : objective_(objective), shards_(std::move(shards)) {}

std::vector<ClimateTally> LocalClimateModel::settle(const std::vector<ClimateRecipe>& batch) {
  std::vector<std::vector<ClimateTally>> parts;
  for (auto& shard : shards_) parts.push_back(shard->settle(batch));
  return added_tallies(objective_, parts, batch.size());
}

std::vector<ClimateTally> LocalClimateModel::flip_tallies(int slot, const std::vector<int>& elements) {
  std::vector<std::vector<ClimateTally>> parts;
  for (auto& shard : shards_) parts.push_back(shard->flip_tallies(slot, elements));
  return added_tallies(objective_, parts, elements.size());
}

double LocalClimateModel::model_bytes() const {
  double bytes = 0.0;
  for (const auto& shard : shards_) bytes += static_cast<double>(shard->model_bytes());
  return bytes;
}

}  // namespace fenestra
